"""compute_rates / rates.json on synthetic output directories with known answers."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from tribolmp.analysis.eq23 import read_profile
from tribolmp.analysis.rates import DEFINITIONS, RATES_UNITS, REMOVED_IDENTITIES, compute_rates
from tribolmp.analysis.synthetic import (
    make_friction,
    make_oscillating_friction,
    make_transfer,
    make_walkers,
    write_friction_csv,
)

CONTRACT = (
    "mu",
    "mu_err",
    "layer_depth_m",
    "diffusion_m2_s",
    "transfer_rate",
    "transfer_per_s",
    "transfer_per_m",
    "wear_lower_per_s",
    "wear_lower_per_m",
    "wear_upper_per_s",
    "wear_upper_per_m",
    "cross_body_links_formed",
    "mu_per_s",
    "d0_m2_s",
    "dz",
    "dx_l2",
    "mu_per_s_err",
    "d0_m2_s_err",
    "dz_err",
    "dx_l2_err",
    "valid",
    "modes_used",
    "step_length_m",
    "time_s",
    "conditions",
    "units",
    "definitions",
    "provenance",
)


def test_rates_json_contract_and_values(tmp_path):
    rng = np.random.default_rng(9)
    exp_t = make_transfer(tmp_path, rng)
    exp_f = make_friction(tmp_path, rng, n=400, dt=1e-11, transient=0.0, phi=0.3, tau=1e-12)
    r = compute_rates(tmp_path, start_s=0.0, window=1)
    on_disk = json.loads(
        (tmp_path / "rates.json").read_text()
    )  # strict JSON (no NaN) by construction
    for key in CONTRACT:
        assert key in on_disk, key
    for key, unit in on_disk["units"].items():
        assert RATES_UNITS[key] == unit
    assert (
        on_disk["units"]["transfer_per_s"] == "1/s" and on_disk["units"]["transfer_per_m"] == "1/m"
    )
    assert on_disk["conditions"] == {
        "pressure_Pa": 150e6,
        "sliding_velocity_m_s": exp_t["velocity_m_s"],
        "law": None,
        "dim": 2,
    }
    # exact scripted events (window 1, all frames; persistence 5 frames)
    for key in (
        "transfer_rate",
        "transfer_per_s",
        "transfer_per_s_err",
        "transfer_per_m",
        "wear_lower_per_s",
        "wear_lower_per_s_err",
        "wear_upper_per_m",
        "wear_upper_per_m_err",
    ):
        assert r[key] == pytest.approx(exp_t[key], rel=1e-4), key
    assert r["transfer_events"] == exp_t["transfer_events"]
    assert abs(r["mu"] - exp_f["mu"]) < 5 * r["mu_err"]
    assert r["step_length_source"] in ("layer_depth_m", "automaton_diameter_m")
    assert r["provenance"]["frames_analysed"] == 40
    # the bpm-era synthetic dump has no C2 tallies: null with a reason, never 0
    assert r["cross_body_links_formed"] is None and "cross_body_links_reason" in r
    # profile.npz in the C1 format, one row per dump frame
    prof = read_profile(tmp_path / "profile.npz")
    assert prof["h"].shape == (40, prof["x"].size) and prof["t"].size == 40
    assert np.all(np.diff(prof["t"]) > 0)


def test_no_rate_is_defined_by_an_identity(tmp_path):
    rng = np.random.default_rng(10)
    make_transfer(tmp_path, rng)
    make_friction(tmp_path, rng, n=400, dt=1e-11)
    r = json.loads(json.dumps(compute_rates(tmp_path, start_s=0.0, window=1)))
    for key in REMOVED_IDENTITIES:
        assert key not in r, key
    # every rate that has a value is a measurement with its error (or a
    # count, or a flagged lower bound)
    rate_units = {"1/s", "1/m", "m^2/s", "m^3/s", "m^5/s", "kg/m"}
    for key, unit in r["units"].items():
        if unit in rate_units and not key.endswith("_err") and r.get(key) is not None:
            assert r.get(f"{key}_err") is not None, key
    # no definition is another field times a constant or a ratio of fields
    # (the old wear = transfer * V)
    for name, text in DEFINITIONS.items():
        for other in r["units"]:
            for op in (f"{other} *", f"* {other}", f"{other} /", f"/ {other}", f"{other}**"):
                assert op not in text, (name, op)
    # the old identity would make the two coincide exactly; measured from
    # the slider's displacement they need not, but both are counts over the
    # same events, so they agree with the measured sliding speed
    v = r["sliding_distance_m"] / r["analysis_span_s"]
    assert r["transfer_per_s"] == pytest.approx(r["transfer_per_m"] * v, rel=1e-9)


def test_diffusion_reported_only_when_diffusive(tmp_path):
    rng = np.random.default_rng(4)
    # D = 5e-9 m^2/s over 4 ns: rms over the 1 ns fit window 3.2 nm > d
    exp = make_walkers(tmp_path, rng, n_walkers=200, n_frames=40, diffusion=5e-9)
    make_friction(tmp_path, rng, n=400, dt=1e-11)
    r = compute_rates(tmp_path, start_s=0.0)
    # rigid bodies, no shear layer thicker than one automaton: l = d, with a warning
    assert r["step_length_source"] == "automaton_diameter_m"
    assert r["step_length_m"] == pytest.approx(2.5e-9)
    assert any("step_length_m" in w for w in r["warnings"])
    # D of the walkers (scatter ~4 % at this size, 4 sigma)
    assert r["diffusion_m2_s"] == pytest.approx(exp["diffusion_m2_s"], rel=0.18)
    assert r["diffusion_err_m2_s"] is not None and r["diffusion_reason"] is None
    assert 0.8 < r["diffusion_exponent"] < 1.2
    assert math.isfinite(r["mu"])


def test_sheared_walkers_give_null_diffusion_with_reason(tmp_path):
    rng = np.random.default_rng(12)
    make_walkers(tmp_path, rng, n_walkers=200, n_frames=40, diffusion=2e-10, shear_velocity_sd=2.0)
    make_friction(tmp_path, rng, n=400, dt=1e-11)
    r = json.loads(json.dumps(compute_rates(tmp_path, start_s=0.0)))
    assert r["diffusion_m2_s"] is None and r["diffusion_err_m2_s"] is None
    assert r["diffusion_exponent"] > 1.5
    assert "ballistic or shear dispersion" in r["diffusion_reason"]


def test_too_few_frames_degrades_gracefully(tmp_path):
    rng = np.random.default_rng(2)
    make_transfer(
        tmp_path,
        rng,
        n_frames=3,
        t_transfer=1,
        t_detach=1,
        t_reattach=2,
        bond_events=(),
        n_flicker=0,
    )
    make_friction(tmp_path, rng, n=200, dt=1e-12)
    r = compute_rates(tmp_path)
    assert r["diffusion_m2_s"] is None and r["layer_depth_m"] is None
    assert all(r[c] is None for c in ("mu_per_s", "d0_m2_s", "dz", "dx_l2")) and not any(
        r["valid"].values()
    )
    assert any("skipped" in w for w in r["warnings"])
    json.loads((tmp_path / "rates.json").read_text())


def test_no_contact_still_writes_rates(tmp_path):
    rng = np.random.default_rng(5)
    make_transfer(tmp_path, rng)
    t = np.arange(1, 101) * 1e-11
    write_friction_csv(
        tmp_path / "friction.csv", t, np.zeros(100), np.r_[np.ones(3), np.zeros(97)], np.zeros(100)
    )
    r = compute_rates(tmp_path)
    assert r["mu"] is None and any(w.startswith("friction:") for w in r["warnings"])
    assert r["transfer_rate"] is not None


def test_c2_tallies_give_cross_body_links(tmp_path):
    rng = np.random.default_rng(13)
    make_transfer(tmp_path, rng)
    # friction.csv of a law with the C2 tallies: cumulative cross-body links
    # formed 0 -> 25 over the run
    t = np.arange(1, 401) * 1e-11
    formed = np.floor(np.linspace(0, 25, 400))
    broken = np.floor(np.linspace(0, 9, 400))
    import csv

    with open(tmp_path / "friction.csv", "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(
            [
                "time_s",
                "friction_N",
                "normal_N",
                "top_x_m",
                "cross_body_links_formed",
                "cross_body_links_broken",
            ]
        )
        for i in range(400):
            w.writerow(
                [t[i], 0.3 + 0.01 * rng.standard_normal(), 1.0, 10.0 * t[i], formed[i], broken[i]]
            )
    r = compute_rates(tmp_path, start_s=0.0)
    assert r["cross_body_links_formed"] == 25 and r["cross_body_links_broken"] == 9
    span = t[-1] - t[0]
    assert r["cross_body_links_formed_per_s"] == pytest.approx(25 / span)
    assert r["cross_body_links_formed_per_s_err"] == pytest.approx(5 / span)
    assert r["cross_body_links_formed_per_m"] == pytest.approx(25 / (10.0 * span))


def test_short_run_without_steady_state_is_flagged(tmp_path):
    """rates.json of a run whose mu(t) swings over half the run.

    mu_steady is false, there is no steady start, and the trajectory analyses use the same
    (second-half) window as the flagged mu.
    """
    rng = np.random.default_rng(6)
    make_walkers(tmp_path, rng, n_walkers=100, n_frames=40)  # dump frames every 0.1 ns up to 4 ns
    make_oscillating_friction(
        tmp_path, rng, n=200, dt=2e-11, period=1.8e-9
    )  # same 4 ns, 2.2 swings
    r = compute_rates(tmp_path)
    on_disk = json.loads((tmp_path / "rates.json").read_text())
    assert on_disk["mu_steady"] is False and on_disk["steady_start_s"] is None
    assert on_disk["mu_estimator"] == "second_half_mean"
    assert any("NOT a steady value" in w for w in on_disk["warnings"])
    # the window starts at the first row at or after t_end / 2 = 2 ns; the
    # frames analysed start there too
    assert on_disk["mu_window_start_s"] == pytest.approx(2e-9, rel=1e-9)
    assert r["analysis_start_s"] == pytest.approx(
        2e-9, rel=1e-6
    )  # dump times are float32-exact to ~1e-7
    assert on_disk["units"]["mu_window_start_s"] == "s"


def test_rates_json_loads_into_the_shared_record(tmp_path):
    """rates.json is read by the chain through tribolmp.records.Rates.

    Every shared field must validate.
    """
    from tribolmp.records import Rates

    rng = np.random.default_rng(14)
    make_transfer(tmp_path, rng)
    make_friction(tmp_path, rng, n=400, dt=1e-11)
    compute_rates(tmp_path, start_s=0.0)
    rec = Rates.from_mapping(json.loads((tmp_path / "rates.json").read_text()), source="test")
    assert rec.mu is not None and rec.sliding_velocity_m_s == 10.0
