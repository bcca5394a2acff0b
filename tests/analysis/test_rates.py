"""compute_rates / rates.json on synthetic output directories with known answers."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from tribolmp.analysis.rates import RATES_UNITS, compute_rates
from tribolmp.analysis.synthetic import (
    make_friction,
    make_oscillating_friction,
    make_transfer,
    make_walkers,
)

CONTRACT = ("mu", "mu_err", "layer_depth_m", "diffusion_m2_s", "transfer_rate", "wear_rate", "detachment_rate",
            "reattachment_rate", "step_length_m", "step_time_s", "time_s", "units")


def test_rates_json_contract_and_values(tmp_path):
    rng = np.random.default_rng(9)
    exp_t = make_transfer(tmp_path, rng)
    exp_f = make_friction(tmp_path, rng, n=400, dt=1e-11, transient=0.0, phi=0.3, tau=1e-12)
    r = compute_rates(tmp_path, start_s=0.0, window=1)
    on_disk = json.loads((tmp_path / "rates.json").read_text())  # strict JSON (no NaN) by construction
    for key in CONTRACT:
        assert key in on_disk, key
    for key, unit in on_disk["units"].items():
        assert RATES_UNITS[key] == unit
    assert on_disk["units"]["transfer_rate"] == "1/m" and on_disk["units"]["detachment_rate"] == "1/s"
    # exact scripted events (window 1, all frames)
    for key in ("transfer_rate", "detachment_rate", "reattachment_rate", "wear_rate", "net_transfer_rate"):
        assert r[key] == pytest.approx(exp_t[key], rel=1e-4), key
    assert abs(r["mu"] - exp_f["mu"]) < 5 * r["mu_err"]
    # tau = l^2 / D by definition, with l the layer depth or the automaton diameter
    assert r["step_time_s"] == pytest.approx(r["step_length_m"] ** 2 / r["diffusion_m2_s"])
    assert r["step_length_source"] in ("layer_depth_m", "automaton_diameter_m")
    if r["step_length_source"] == "automaton_diameter_m":
        assert r["step_length_m"] == r["automaton_diameter_m"]
    assert r["provenance"]["frames_analysed"] == 40


def test_step_length_falls_back_to_diameter_and_D_is_reported(tmp_path):
    rng = np.random.default_rng(4)
    exp = make_walkers(tmp_path, rng, n_walkers=200, n_frames=40)
    make_friction(tmp_path, rng, n=400, dt=1e-11)
    r = compute_rates(tmp_path, start_s=0.0)
    # rigid bodies, no shear layer thicker than one automaton: l = d, with a warning
    assert r["step_length_source"] == "automaton_diameter_m"
    assert r["step_length_m"] == pytest.approx(2.5e-9)
    assert any("step_length_m" in w for w in r["warnings"])
    # D of the walkers (scatter ~4 % at this size, 4 sigma)
    assert r["diffusion_m2_s"] == pytest.approx(exp["diffusion_m2_s"], rel=0.18)
    assert r["step_time_s"] == pytest.approx(2.5e-9**2 / r["diffusion_m2_s"])
    assert math.isfinite(r["mu"])


def test_too_few_frames_degrades_gracefully(tmp_path):
    rng = np.random.default_rng(2)
    make_transfer(tmp_path, rng, n_frames=3, t_transfer=1, t_detach=1, t_reattach=2, bond_events=())
    make_friction(tmp_path, rng, n=200, dt=1e-12)
    r = compute_rates(tmp_path)
    assert r["diffusion_m2_s"] is None and r["layer_depth_m"] is None and r["step_time_s"] is None
    assert any("skipped" in w for w in r["warnings"])
    json.loads((tmp_path / "rates.json").read_text())


def test_no_contact_still_writes_rates(tmp_path):
    from tribolmp.analysis.synthetic import write_friction_csv

    rng = np.random.default_rng(5)
    make_transfer(tmp_path, rng)
    t = np.arange(1, 101) * 1e-11
    write_friction_csv(tmp_path / "friction.csv", t, np.zeros(100), np.r_[np.ones(3), np.zeros(97)], np.zeros(100))
    r = compute_rates(tmp_path)
    assert r["mu"] is None and any(w.startswith("friction:") for w in r["warnings"])
    assert r["transfer_rate"] is not None


def test_short_run_without_steady_state_is_flagged(tmp_path):
    """rates.json of a run whose mu(t) swings over half the run: mu_steady false, no steady start, and the
    trajectory analyses use the same (second-half) window as the flagged mu."""
    rng = np.random.default_rng(6)
    make_walkers(tmp_path, rng, n_walkers=100, n_frames=40)  # dump frames every 0.1 ns up to 4 ns
    make_oscillating_friction(tmp_path, rng, n=200, dt=2e-11, period=1.8e-9)  # same 4 ns, 2.2 swings
    r = compute_rates(tmp_path)
    on_disk = json.loads((tmp_path / "rates.json").read_text())
    assert on_disk["mu_steady"] is False and on_disk["steady_start_s"] is None
    assert on_disk["mu_estimator"] == "second_half_mean"
    assert any("NOT a steady value" in w for w in on_disk["warnings"])
    # the window starts at the first row at or after t_end / 2 = 2 ns; the frames analysed start there too
    assert on_disk["mu_window_start_s"] == pytest.approx(2e-9, rel=1e-9)
    assert r["analysis_start_s"] == pytest.approx(2e-9, rel=1e-6)  # dump times are float32-exact to ~1e-7
    assert on_disk["units"]["mu_window_start_s"] == "s"
