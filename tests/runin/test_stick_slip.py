"""Repeated stick-slip from the scene's data: the analytic re-stick condition against the model.

The body of mass m is pulled by a drive spring k_d at V; it sticks on a tangential contact spring
k_c (the apparent contact's) and slips with mu_k.  It sticks again after a slip iff the static
excess (mu_s - mu_k) N exceeds sqrt(k_d m v0 (2V - v0)), v0 = V k_d/(k_d + k_c) its creep during
stick (:func:`tribolmp.models.macro.reference.restick_criterion`).
"""

from __future__ import annotations

import json
import sys

import numpy as np
import pytest

from tribolmp.models.macro.friction import ConstantFriction
from tribolmp.models.macro.reference import restick_criterion
from tribolmp.models.macro.rigid_body import StickSlipParams, stick_slip
from tribolmp.scene import parse_scene, scene_path

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

#: The default scene's body and drive, and its apparent contact's tangential stiffness (3e7 N/m).
M, KD, V, N, MU_K, KC = 0.1, 1e6, 0.01, 10.0, 0.3, 3e7


def _run(mu_s, kc=KC):
    res = stick_slip(
        StickSlipParams(mass=M, drive_stiffness=KD, drive_velocity=V, normal_force=N,
                        duration=0.05, contact_stiffness=kc),
        ConstantFriction(mu_s=mu_s, mu_k=MU_K),
    )
    resticks = [e for e in res.events if e["to_phase"] == "stick"]
    return res, resticks


@pytest.mark.parametrize("factor", [1.1, 0.9])
def test_restick_condition_predicts_the_model(factor):
    """Check 10 % above the threshold: repeated stick-slip; 10 % below: one stick, then sliding."""
    threshold = restick_criterion(M, KD, V, N, MU_K, MU_K, KC)["threshold_N"]
    mu_s = MU_K + factor * threshold / N
    crit = restick_criterion(M, KD, V, N, mu_s, MU_K, KC)
    res, resticks = _run(mu_s)
    slips = [e for e in res.events if e["to_phase"].startswith("slip")]
    assert slips, "the drive must break the first stick within the run"
    if factor > 1:
        assert crit["repeats"] and len(resticks) > 1
    else:
        assert not crit["repeats"] and len(resticks) == 0
        # The slip's slowest velocity is the analytic V - A omega: within 0.2 % of V (the creep
        # velocity at the slip is the quasi-static v0 once the contact's damped transient,
        # ~1/omega_c = 57 us, has died out during the 0.4 ms stick; measured 0.06 % of V).
        t, v = np.asarray(res.t), np.asarray(res.v)
        after = t > slips[0]["t"]
        assert float(v[after].min()) == pytest.approx(crit["min_slip_velocity_m_s"], abs=2e-3 * V)


def test_a_rigid_contact_resticks_with_any_static_excess():
    """Classic limit (v0 = 0): a 1 % static excess gives repeated stick-slip; none gives none."""
    assert restick_criterion(M, KD, V, N, 1.01 * MU_K, MU_K, 0.0)["threshold_N"] == 0.0
    _, resticks = _run(1.01 * MU_K, kc=0.0)
    assert len(resticks) > 1
    assert not restick_criterion(M, KD, V, N, MU_K, MU_K, KC)["repeats"]


def _chain(tmp_path, name, static_ratio):
    from tribolmp.chain.runner import run_chain

    data = tomllib.loads(scene_path("rates_given").read_text())
    data["roughness"].update(grid_points=32, realizations=4)
    data["running_in"].update(static_ratio=static_ratio)
    data["outputs"] = {"requested": ["stick_slip"], "figures": False}
    out = tmp_path / name
    run_chain(parse_scene(data, source=name), out, quiet=True, figures=False)
    return json.loads((out / "report.json").read_text())["results"]["macroscale"]["values"]


def test_chain_stick_phases_follow_the_condition_of_the_scene_data(tmp_path):
    """rates_given: 1.25 x mu_k is below the threshold of its contact (one stick); 2 x is above."""
    below = _chain(tmp_path, "below", 1.25)
    above = _chain(tmp_path, "above", 2.0)
    for v in (below, above):
        crit = v["restick_criterion"]
        # the criterion the report states is the one of the numbers the body ran with
        ref = restick_criterion(0.1, 1e6, 0.01, 10.0, v["mu_static"], v["mu_kinetic"],
                                v["contact_stiffness_N_m"])
        assert crit == pytest.approx(ref)
    assert not below["restick_criterion"]["repeats"] and below["n_stick_phases"] == 1
    assert above["restick_criterion"]["repeats"] and above["n_stick_phases"] > 2
