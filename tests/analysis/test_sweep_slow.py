"""End to end on LAMMPS: a smoke MCA run analysed into rates.json, and the quick sweep (slow)."""

from __future__ import annotations

import csv
import importlib.util
import json
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.slow
@pytest.mark.lammps
def test_quick_sweep_one_point_writes_table_and_figures(lammps_available, tmp_path):
    spec = importlib.util.spec_from_file_location(
        "mca_friction_sweep", ROOT / "workflows" / "mca_friction_sweep.py"
    )
    mod = importlib.util.module_from_spec(spec)
    sys.modules["mca_friction_sweep"] = mod
    spec.loader.exec_module(mod)
    out = tmp_path / "sweep"
    code = mod.main(
        [
            "--quick",
            "--velocities",
            "20",
            "--pressures",
            "150e6",
            "--out",
            str(out),
            "--campaign",
            str(tmp_path / "campaign.csv"),
            "--table",
            str(tmp_path / "table.json"),
        ]
    )
    assert code == 0
    with (tmp_path / "campaign.csv").open() as fh:
        camp = list(csv.DictReader(fh))
    assert len(camp) == 1 and camp[0]["law"] and camp[0]["valid_mu_per_s"] in ("True", "False")
    table = json.loads((tmp_path / "table.json").read_text())
    assert table["rows"][0]["pressure_Pa"] == 150e6 and table["rows"][0]["mu"] == pytest.approx(
        float(camp[0]["mu"])
    )
    assert table["provenance"]["laws"] == [camp[0]["law"]]
    with (out / "summary.csv").open() as fh:
        rows = list(csv.DictReader(fh))
    assert len(rows) == 1 and float(rows[0]["velocity_m_s"]) == 20.0
    run = out / "v20_p150MPa"
    rates = json.loads((run / "rates.json").read_text())
    assert rates["units"]["mu"] == "1" and rates["mu"] is not None
    # the smoke run slides 20 nm: the interface is sheared, so some link breaks are recorded
    assert rates["links_broken_per_s"] > 0
    for name in ("mu_t.png", "snapshot.png", "profiles.png"):
        assert (run / name).stat().st_size > 5000
    assert "| V (m/s) |" in (out / "summary.md").read_text()
