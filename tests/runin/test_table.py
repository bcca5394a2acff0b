"""The shipped nanoscale table and the precedence of the running-in's coefficients (issue 15).

Precedence, per coefficient: the scene's ``[rates]`` > this run's valid measurement > the shipped
nanoscale table at the part's condition > the ``[topography]`` values; stated in report.json.
"""

from __future__ import annotations

import csv
import json
import math
import runpy
import sys
from pathlib import Path

import pytest

from tribolmp.models import bridges
from tribolmp.scene import parse_scene, scene_path

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

ROOT = Path(__file__).resolve().parents[2]


def test_shipped_table_is_built_from_the_campaign_csv():
    """Check the shipped table is exactly what the workflow builds from the campaign CSV."""
    main = runpy.run_path(str(ROOT / "workflows" / "nanoscale_table.py"))["main"]
    # content: rows, units and provenance, incl. the CSV's SHA-256
    assert main(["--check"]) == 0
    table = json.loads((ROOT / "tribolmp" / "data" / "nanoscale_table.json").read_text())
    assert table["provenance"]["laws"] == ["mca"]
    # Independent check of the seed combination on the condition with several seeds.
    with (ROOT / "docs" / "data" / "mca_campaign.csv").open() as fh:
        # the table is one law and one dimension (2D): a 3D run at 150 MPa is not a seed
        runs = [r for r in csv.DictReader(fh) if r["law"] == "mca" and r["mu"] and r["dim"] == "2"
                and float(r["pressure_Pa"]) == 150e6 and float(r["sliding_velocity_m_s"]) == 5.0]
    row = next(r for r in table["rows"]
               if r["pressure_Pa"] == 150e6 and r["sliding_velocity_m_s"] == 5.0)
    mus = [float(r["mu"]) for r in runs]
    n = len(runs)
    assert row["n_runs"] == n >= 2
    assert row["mu"] == pytest.approx(sum(mus) / n, rel=1e-12)
    # error >= the seed scatter std/sqrt(n) (the rule stated in the provenance; sample std)
    sd = math.sqrt(sum((m - row["mu"]) ** 2 for m in mus) / (n - 1))
    assert row["mu_err"] >= sd / math.sqrt(n) * (1 - 1e-12)


def test_table_at_part_interpolates_in_log_p_and_flags_extrapolation():
    """Exact log-p interpolation between two rows; outside their range or velocity: flagged."""
    rows = [
        {"pressure_Pa": 1e6, "sliding_velocity_m_s": 5.0, "mu": 0.2, "d0_m2_s": 1e-10},
        {"pressure_Pa": 1e8, "sliding_velocity_m_s": 5.0, "mu": 0.4, "d0_m2_s": 1e-8},
        # a coefficient the analysis did not validate is never used
        {"pressure_Pa": 1e7, "sliding_velocity_m_s": 5.0, "mu": 9.0, "d0_m2_s": 5.0,
         "d0_m2_s_valid": False},
    ][:2]
    t = bridges.table_at_part(rows, "mu", pressure_Pa=1e7, velocity_m_s=5.0)
    assert t.value == pytest.approx(0.3, rel=1e-12) and not t.extrapolated  # log-midpoint
    d = bridges.table_at_part(rows, "d0_m2_s", pressure_Pa=1e7, velocity_m_s=5.0, log_values=True)
    assert d.value == pytest.approx(1e-9, rel=1e-12)  # geometric midpoint in log value
    bad = rows + [{"pressure_Pa": 1e7, "sliding_velocity_m_s": 5.0, "mu": 0.3, "d0_m2_s": 5.0,
                   "d0_m2_s_valid": False}]
    assert bridges.table_at_part(bad, "d0_m2_s", pressure_Pa=1e7, velocity_m_s=5.0,
                                 log_values=True).value == pytest.approx(1e-9, rel=1e-12)
    assert bridges.table_at_part(rows, "dz", pressure_Pa=1e7, velocity_m_s=5.0) is None
    slow = bridges.table_at_part(rows, "mu", pressure_Pa=1e7, velocity_m_s=0.01)
    assert slow.extrapolated and "velocity" in slow.extrapolation
    high = bridges.table_at_part(rows, "mu", pressure_Pa=1e9, velocity_m_s=5.0)
    assert high.extrapolated and high.value == pytest.approx(0.4)
    assert "pressure" in high.extrapolation
    # within 10 % of the measured range is not an extrapolation (the stated margin)
    assert not bridges.table_at_part(rows, "mu", pressure_Pa=1.05e8, velocity_m_s=5.0).extrapolated


#: A synthetic table: mu 0.2 -> 0.4 over 1e6..1e8 Pa at 5 m/s (0.3 at the scenes' 1e7 Pa),
#: mu_s/mu_k measured = 1.5, D0 valid only at 20 m/s, dx_l2 never valid.
TABLE = {"rows": [
    {"pressure_Pa": 1e6, "sliding_velocity_m_s": 5.0, "mu": 0.2, "mu_static": 0.3,
     "mu_kinetic": 0.2, "d0_m2_s": None, "d0_m2_s_valid": False, "dx_l2": None},
    {"pressure_Pa": 1e8, "sliding_velocity_m_s": 5.0, "mu": 0.4, "mu_static": 0.6,
     "mu_kinetic": 0.4, "d0_m2_s": None, "d0_m2_s_valid": False, "dx_l2": None},
    {"pressure_Pa": 1e6, "sliding_velocity_m_s": 20.0, "mu": 0.5, "d0_m2_s": 4e-10},
    {"pressure_Pa": 1e8, "sliding_velocity_m_s": 20.0, "mu": 0.5, "d0_m2_s": 4e-8},
], "provenance": {"source": "test"}}


def _scene(**rates_changes):
    data = tomllib.loads(scene_path("rates_given").read_text())
    data["roughness"].update(grid_points=32, realizations=2)
    data["contact"] = {"method": "mdr"}
    data["running_in"].update(checkpoints=1, phi_tolerance=1e9)
    data["outputs"] = {"requested": ["topography"], "figures": False}
    for k, v in rates_changes.items():
        if v is None:
            data["rates"].pop(k, None)
        else:
            data["rates"][k] = v
    return data


def _provenance(tmp_path, monkeypatch, data, table, name):
    import tribolmp.environment as env
    from tribolmp.chain.runner import run_chain

    real = env.data_path
    path = tmp_path / f"{name}_table.json"
    if table is not None:
        path.write_text(json.dumps(table))

    def fake(*parts):
        return path if parts == ("nanoscale_table.json",) else real(*parts)

    monkeypatch.setattr(env, "data_path", fake)
    out = tmp_path / name
    run_chain(parse_scene(data, source=name), out, quiet=True, figures=False)
    rep = json.loads((out / "report.json").read_text())
    prov = rep["stage_details"]["topography"]["provenance"]["coefficients"]
    assert prov == rep["results"]["topography"]["values"]["coefficient_provenance"]
    return prov


def test_scene_rates_win_over_the_table(tmp_path, monkeypatch):
    """[rates] gives mu and every Eq. 23 coefficient: the table changes nothing."""
    prov = _provenance(tmp_path, monkeypatch, _scene(), TABLE, "given")
    assert prov["mu_kinetic"]["tier"] == "scene [rates]" and prov["mu_kinetic"]["value"] == 0.16
    assert {prov[k]["tier"] for k in ("mu_per_s", "d0_m2_s", "dz", "dx_l2")} == {"scene [rates]"}
    # mu_s: not given anywhere but the table's measured ratio (1.5) at the part's pressure
    assert prov["mu_static"]["tier"] == "nanoscale table (mu_s/mu_k)"
    assert prov["mu_static"]["value"] == pytest.approx(1.5 * 0.16, rel=1e-12)


def _measured(**fields):
    """Return this run's rates.json (C1 fields, valid flags) as the nanoscale stage hands it on."""
    from tribolmp.records import Rates

    base = {"mu": 0.21, "sliding_velocity_m_s": 5.0, "pressure_Pa": 150e6, "step_length_m": 2.5e-9,
            "transfer_rate": 4.2e6, "mu_per_s": 1e5, "d0_m2_s": None, "dz": 1e-27, "dx_l2": None,
            "valid": {"mu_per_s": True, "d0_m2_s": False, "dz": True, "dx_l2": False}}
    base.update(fields)
    return Rates.from_mapping(base, source="nanoscale stage x (rates.json)")


def _choose(rates, table, **running_in):
    import numpy as np

    from tribolmp.chain.stages.topography import part_coefficients
    from tribolmp.models import runin

    data = _scene()
    del data["rates"]  # the rates come from the (simulated) nanoscale stage
    data["running_in"].update(running_in)
    scene = parse_scene(data, source="choose")
    h0 = np.random.default_rng(0).normal(size=(16, 16)) * 5e-7
    params = runin.RunInParams(normal_force=10.0, apparent_area=1e-6,
                               E_star=scene.effective_modulus)
    rows = None if table is None else table["rows"]
    # the precedence mechanics: MCA profiles taken long enough (1 mm) to cover the part's band
    # (the band rule itself is tests/runin/test_band.py)
    eq, friction, provenance, _ = part_coefficients(scene, rates, rates.source, rows, h0, 2e-6,
                                                    params, 2.5e-9, run_length=1e-3,
                                                    table_length=1e-3)
    return eq, provenance(friction(0.01))


def test_the_run_s_valid_measurement_beats_the_table_which_beats_topography():
    """Check: C1 valid -> the run's; invalid/null -> the table; else [topography]."""
    eq, prov = _choose(_measured(), TABLE)
    run = "measured by this run (nanoscale rates.json)"
    assert prov["mu_per_s"]["tier"] == prov["dz"]["tier"] == run
    assert prov["mu_kinetic"]["tier"] == run and prov["mu_kinetic"]["value"] == 0.21
    d0 = prov["d0_m2_s"]
    # D0 not valid in this run; only the table's 20 m/s rows measured it (4e-9 m^2/s at the scenes'
    # nominal 1e7 Pa, log-midpoint), moved per sliding distance to the run's 5 m/s
    assert d0["tier"] == "nanoscale table" and d0["table_velocity_m_s"] == 20.0
    assert d0["value"] == eq.d0 == pytest.approx(4e-9 * 5.0 / 20.0, rel=1e-12)
    assert d0["extrapolated"] is True  # 1 cm/s part against 20 m/s rows
    assert prov["dx_l2"]["tier"] == "[topography] fallback"  # never valid anywhere
    # mu_s: the table's measured ratio 1.5 times the run's mu_k
    assert prov["mu_static"]["tier"] == "nanoscale table (mu_s/mu_k)"
    assert prov["mu_static"]["value"] == pytest.approx(1.5 * 0.21, rel=1e-12)


def test_mu_from_the_table_when_the_run_s_mu_is_not_valid():
    """Check a flagged run mu: mu_k from the table at 1e7 Pa (0.3), extrapolation flagged."""
    _, prov = _choose(_measured(valid={"mu": False, "mu_per_s": True, "dz": True}), TABLE)
    k = prov["mu_kinetic"]
    assert k["tier"] == "nanoscale table" and k["value"] == pytest.approx(0.3, rel=1e-12)
    assert k["extrapolated"] is True and "velocity" in k["extrapolation"]
    assert prov["mu_static"]["value"] == pytest.approx(0.45, rel=1e-12)
    # the scene's stated mu_k wins over everything
    _, given = _choose(_measured(), TABLE, mu_kinetic=0.33)
    assert given["mu_kinetic"]["tier"] == "scene [running_in].mu_kinetic"
    assert given["mu_static"]["value"] == pytest.approx(1.5 * 0.33, rel=1e-12)


def test_without_a_table_the_scene_fallbacks_are_used():
    """No shipped table: D0 from [topography], mu_s by the stated ratio."""
    _, prov = _choose(_measured(), None)
    assert prov["d0_m2_s"]["tier"] == "[topography] fallback"
    assert prov["mu_static"]["tier"] == "scene [running_in].static_ratio (stated assumption)"
    assert prov["mu_static"]["value"] == pytest.approx(1.25 * 0.21, rel=1e-12)
