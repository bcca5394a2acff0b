"""Rigid body pulled through a spring: stick-slip against closed forms, hard cases."""

import math

import numpy as np
import pytest

from tests.conftest import assert_one_line_error
from tests.macro.helpers import run_main
from tribolmp.errors import DataFileError, ParameterError
from tribolmp.models.macro import (
    ConstantFriction,
    StickSlipParams,
    TabulatedFriction,
    VelocityWeakening,
    load_friction_law,
    stick_slip,
)
from tribolmp.models.macro.reference import free_oscillation, stick_slip_cycle

P = dict(mass=0.1, drive_stiffness=1e5, drive_velocity=0.01, normal_force=10.0)
LAW = ConstantFriction(0.4, 0.3)
REF = stick_slip_cycle(0.1, 1e5, 0.01, 10.0, 0.4, 0.3)


def _cycles(res):
    ev = res.events
    starts = [e for e in ev if e["from_phase"] == "stick"]
    stops = [e for e in ev if e["to_phase"] == "stick"]
    return starts, stops


def _check_cycle(res, rel):
    starts, stops = _cycles(res)
    assert len(stops) >= 3
    # periodic after the first slip; slip duration and the force drop as in the closed form
    periods = np.diff([e["t"] for e in stops])
    assert periods == pytest.approx(REF["period"], rel=rel)
    slips = [b["t"] - a["t"] for a, b in zip(starts, stops)]
    assert slips == pytest.approx([REF["slip_time"]] * len(slips), rel=rel)
    assert [e["force_N"] for e in stops] == pytest.approx([REF["force_min"]] * len(stops), rel=rel)
    assert [e["force_N"] for e in starts] == pytest.approx(
        [REF["force_max"]] * len(starts), rel=rel
    )


def test_analytic_segments_reproduce_closed_form():
    res = stick_slip(StickSlipParams(**P, duration=0.05), LAW, method="analytic")
    _check_cycle(res, 1e-11)  # exact segments: round-off only


@pytest.mark.parametrize("method", ["rk45", "radau"])
def test_ode_event_detection_matches_closed_form(method):
    res = stick_slip(StickSlipParams(**P, duration=0.03, rtol=1e-9), LAW, method=method)
    # event times are located on the dense output: error ~ rtol * (number of steps)
    _check_cycle(res, 1e-6)


def test_no_chattering_transitions_alternate():
    res = stick_slip(StickSlipParams(**P, duration=0.05, rtol=1e-8), LAW, method="rk45")
    ev = res.events
    # strictly alternating stick <-> slip, every phase of finite length
    kinds = [e["to_phase"] == "stick" for e in ev]
    assert all(a != b for a, b in zip(kinds, kinds[1:]))
    dt = np.diff([0.0] + [e["t"] for e in ev])
    assert dt.min() > 0.5 * min(REF["stick_time"], REF["slip_time"])
    # the expected number of transitions: one stick->slip after the first loading, then 2 per period
    t_first = 0.4 * 10 / (1e5 * 0.01)
    n_expected = 1 + 2 * math.floor((0.05 - t_first) / REF["period"])
    assert abs(len(ev) - n_expected) <= 1
    # velocity is exactly zero during stick, non-negative in forward slip
    stick = res.phase == 0
    assert np.all(res.v[stick] == 0.0)
    assert np.all(res.v[res.phase == 1] > -1e-9)


def test_equal_static_and_kinetic_friction_does_not_chatter():
    # mu_s == mu_k: the body starts sliding and touches v = 0 only tangentially
    res = stick_slip(StickSlipParams(**P, duration=0.05), ConstantFriction(0.3), method="rk45")
    assert res.n_transitions <= 2 * 0.05 / (2 * math.pi * math.sqrt(0.1 / 1e5)) + 2


def test_velocity_weakening_runs_without_chattering():
    law = VelocityWeakening(mu_s=0.4, mu_k=0.25, v_c=2e-3)
    res = stick_slip(StickSlipParams(**P, duration=0.05), law, method="rk45")
    starts, stops = _cycles(res)
    assert len(stops) >= 3
    for e in stops:  # the body stops where the spring force is within the static limit
        assert abs(e["force_N"]) <= 0.4 * 10 + 1e-9
    for e in starts:
        assert e["force_N"] == pytest.approx(4.0, rel=1e-9)
    dt = np.diff([e["t"] for e in res.events])
    assert dt.min() > 1e-5


def test_stiff_contact_spring_converges_to_rigid_contact():
    # k_c = 1e12 N/m on m = 0.1 kg: contact frequency 3e6 rad/s vs drive 1e3 rad/s.
    res = stick_slip(
        StickSlipParams(**P, duration=0.03, contact_stiffness=1e12), LAW, method="auto"
    )
    assert res.method == "radau-rk45"
    starts, stops = _cycles(res)
    # the contact compliance shifts the cycle by O(k_d / k_c) = 1e-7
    assert [e["force_N"] for e in stops] == pytest.approx([REF["force_min"]] * len(stops), rel=1e-5)
    # the implicit stick phase takes steps set by the slow dynamics, not by 1/omega_c:
    # explicit RK would need > 0.03 s * 3e6 rad/s ~ 1e5 steps
    assert res.nfev < 30000


def test_vanishing_normal_load_becomes_free_oscillation():
    t_off = 0.012
    p = StickSlipParams(**P, duration=0.03, unload_time=t_off, rtol=1e-10)
    res = stick_slip(p, LAW, method="rk45")
    assert np.all(np.isfinite(res.x))
    after = res.t > t_off + 1e-9
    i0 = np.argmax(after)
    # after the load vanished the body is a frictionless oscillator on the drive spring
    ref = free_oscillation(
        res.t[after], 0.1, 1e5, 0.01, res.x[i0], res.v[i0], res.t[i0], 0.01 * res.t[i0]
    )
    assert np.max(np.abs(res.x[after] - ref)) < 1e-6 * np.ptp(res.x[after]) + 1e-12
    # no stick once the load is gone (a free body never sticks)
    assert all(e["to_phase"] != "stick" for e in res.events if e["t"] > t_off)


def test_vanishing_load_with_mdr_contact_spring():
    from tribolmp.models.macro import ContactSprings, profile_from_geometry

    E = 113e9
    x, g = profile_from_geometry("sphere", 10.0, E, n_springs=201, radius=5e-3)
    kc = ContactSprings(x, g, E, 93e9, 0.4).stiffness_table(10.0)
    assert kc(0.0) == 0.0 and kc(10.0) > 1e6
    p = StickSlipParams(**P, duration=0.02, unload_time=0.01)
    res = stick_slip(p, LAW, contact_stiffness=kc)
    assert res.method == "radau-rk45"
    assert np.all(np.isfinite(res.x))


def test_friction_law_validation_and_files(tmp_path):
    with pytest.raises(ParameterError, match="mu_s"):
        ConstantFriction(0.2, 0.3)
    (tmp_path / "rates.json").write_text('{"mu": 0.25, "units": {"mu": "1"}}')
    law = load_friction_law(tmp_path / "rates.json")
    assert law.mu_s == 0.25 and law.kinetic(1.0) == 0.25
    (tmp_path / "mu.csv").write_text("velocity_m_s,mu\n0,0.4\n0.01,0.3\n1,0.2\n")
    law = load_friction_law(tmp_path / "mu.csv")
    assert isinstance(law, TabulatedFriction)
    assert law.kinetic(0.005) == pytest.approx(0.35)
    assert law.mu_s == 0.4
    (tmp_path / "bad.csv").write_text("velocity_m_s,mu\n0,0.4\n0.01,abc\n")
    with pytest.raises(DataFileError, match="line 3"):
        load_friction_law(tmp_path / "bad.csv")
    (tmp_path / "bad.json").write_text('{"mu": -1}')
    with pytest.raises(DataFileError, match="mu"):
        load_friction_law(tmp_path / "bad.json")


def test_tabulated_law_stick_slip(tmp_path):
    law = TabulatedFriction((0.0, 0.005, 0.05), (0.4, 0.3, 0.3))
    res = stick_slip(StickSlipParams(**P, duration=0.03), law, method="rk45")
    starts, stops = _cycles(res)
    assert len(stops) >= 2


def test_params_validation():
    with pytest.raises(ParameterError, match="mass"):
        StickSlipParams(mass=-1.0)
    with pytest.raises(ParameterError, match="method"):
        stick_slip(
            StickSlipParams(**P, duration=0.01, contact_stiffness=1e9), LAW, method="analytic"
        )


def test_cli_stick_slip(cli, capsys, tmp_path):
    res = cli(
        "macro",
        "stick-slip",
        "--mu-s",
        "0.4",
        "--mu-k",
        "0.3",
        "--velocity",
        "0.01",
        "--duration",
        "0.02",
        "--json",
    )
    assert res.returncode == 0, res.stderr
    out = res.json()
    assert out["method"] == "analytic"
    assert out["n_transitions"] >= 3
    # default scene: N = 10 N, stick ends at mu_s N
    assert out["events"][0]["force_N"] == pytest.approx(4.0, rel=1e-12)
    (tmp_path / "r.json").write_text('{"mu": "high"}')
    assert_one_line_error(
        cli("macro", "stick-slip", "--friction-file", tmp_path / "r.json"), "mu", code=2
    )
    assert_one_line_error(
        run_main(capsys, "macro", "stick-slip", "--mu-s", "0.2", "--mu-k", "0.3"), "mu_s", code=2
    )
    assert_one_line_error(
        run_main(capsys, "macro", "stick-slip", "--method", "euler"), "method", code=2
    )


@pytest.mark.parametrize("kc", [0.0, 1e9])
def test_zero_normal_load_from_the_start(kc):
    p = StickSlipParams(
        **{**P, "normal_force": 0.0}, duration=0.02, contact_stiffness=kc, rtol=1e-10
    )
    res = stick_slip(p, LAW)
    # no load, no friction: the body oscillates freely about the moving spring end from rest
    ref = free_oscillation(res.t, 0.1, 1e5, 0.01, 0.0, 0.0, 0.0, 0.0)
    assert np.max(np.abs(res.x - ref)) < 1e-6 * np.ptp(ref)
    assert res.n_transitions <= 2


def test_tabulated_load_from_zero_on_an_elastic_contact_does_not_chatter():
    """Regression: a normal load ramping up from exactly 0 N (film rupture) on an elastic contact.

    Before the fix the zero-load stick phase switched to slip, which ended at once (friction grows
    faster than the drive force), and the loop was reported as chattering at t = 0.
    """
    import numpy as np

    from tribolmp.models.macro.friction import ConstantFriction
    from tribolmp.models.macro.rigid_body import StickSlipParams, stick_slip

    k, V, mu, N, kc = 1e6, 0.01, 0.1, 10.0, 1e9
    p = StickSlipParams(
        mass=0.1,
        drive_stiffness=k,
        drive_velocity=V,
        normal_force=N,
        duration=2e-3,
        contact_stiffness=kc,
    )
    t = np.linspace(0.0, 2e-3, 201)
    load = N * np.minimum(t / 2.5e-5, 1.0)  # reaches N long before the drive force reaches mu N
    res = stick_slip(p, ConstantFriction(mu), normal_load=(t, load))
    first = res.events[0]
    assert first["from_phase"] == "stick" and first["to_phase"] == "slip+"
    # Slip starts when the contact force reaches mu N: drive stretch mu N / k plus the contact's
    # elastic deformation mu N / kc; the contact damping shifts it by < 1e-3 relative.
    t_exact = mu * N / (k * V) * (1.0 + k / kc)
    assert abs(first["t"] / t_exact - 1.0) < 1e-3
    assert abs(first["force_N"] / (mu * N) - 1.0) < 1e-3
