"""Prescribed oscillation (Mindlin-Deresiewicz) and the multirate scheme against brute force."""

import numpy as np
import pytest

from tribolmp.models.macro import (
    ContactSprings,
    DriftParams,
    OscillationParams,
    drift_under_oscillation,
    oscillate,
    profile_from_geometry,
)
from tribolmp.models.macro.reference import mindlin_dissipation, mindlin_loading, mindlin_loop

E_STAR = 206e9 / (2 * (1 - 0.3**2))
G_STAR = 1.0 / (2 * (2 - 0.3) / (4 * 206e9 / 2.6))
N, R, MU = 5.0, 5e-3, 0.3


def _contact(n=801):
    x, g = profile_from_geometry("sphere", N, E_STAR, n_springs=n, radius=R)
    return ContactSprings(x, g, E_STAR, G_STAR, MU)


def test_oscillation_reproduces_mindlin_deresiewicz():
    c = _contact()
    d = c.indentation(N)
    u_s = MU * E_STAR * d / G_STAR  # full-slip displacement of Mindlin in MDR variables
    amp = 0.5 * u_s
    res = oscillate(
        OscillationParams(
            normal_force=N, amplitude=amp, frequency=65e3, cycles=3, steps_per_cycle=400
        ),
        c,
    )
    assert res.force_n[-1] == pytest.approx(N, rel=1e-10)
    # first quarter cycle: Mindlin's loading curve
    q = slice(0, 101)
    ref = mindlin_loading(res.u[q], MU * N, u_s)
    # 801 springs: spring-wise slip discretises the stick radius to O(dx/a) ~ 3e-3
    assert np.max(np.abs(res.force_x[q] - ref)) < 5e-3 * MU * N
    # steady loop (third cycle): Masing branches and the dissipated energy
    last = slice(800, 1201)
    u, f = res.u[last], res.force_x[last]
    du = np.gradient(u)
    unload = du < 0
    assert (
        np.max(np.abs(f[unload] - mindlin_loop(u[unload], amp, MU * N, u_s, "unload")))
        < 5e-3 * MU * N
    )
    assert (
        np.max(np.abs(f[~unload] - mindlin_loop(u[~unload], amp, MU * N, u_s, "reload")))
        < 5e-3 * MU * N
    )
    w_ref = mindlin_dissipation(amp, MU * N, u_s)
    # loop area: trapezoid with 400 steps per cycle (O(1/400^2)) plus the
    # spring discretisation of the slip annulus (O(dx/a) ~ 3e-3)
    assert res.dissipation_per_cycle_J[-1] == pytest.approx(w_ref, rel=5e-3)
    assert res.dissipation_per_cycle_J[-1] == pytest.approx(
        res.dissipation_per_cycle_J[-2], rel=1e-9
    )


def test_averaged_scheme_matches_brute_force_short_window():
    c = _contact(n=101)
    k = c.stiffness(N)
    L = MU * N / k
    for a in (0.4 * L, 1.0 * L):
        # drift per cycle V/f = 1.5 nm = 2.5 % (a = 0.4 L) of the amplitude
        p = DriftParams(
            normal_force=N,
            amplitude=a,
            frequency=65e3,
            sliding_velocity=1e-4,
            duration=0.6e-3,
            steps_per_cycle=32,
            slow_steps=40,
        )
        brute = drift_under_oscillation(p, c, scheme="brute")
        avg = drift_under_oscillation(p, c, scheme="averaged")
        f_avg = np.interp(brute.t, avg.t, avg.force)
        # the averaged error is O(V/(a w)) of the force scale 2 mu N
        assert np.max(np.abs(brute.force - f_avg)) < 0.01 * 2 * MU * N
        assert avg.steps < brute.steps / 20


def test_averaged_cost_is_independent_of_frequency():
    c = _contact(n=101)
    p = DriftParams(
        normal_force=N,
        amplitude=5e-8,
        frequency=65e3,
        sliding_velocity=1e-4,
        duration=1.0,
        slow_steps=400,
    )
    avg = drift_under_oscillation(p, c, scheme="averaged")
    # one second of drift at 65 kHz: brute force would take 65e3 * 32 = 2e6 steps
    assert avg.steps == 400
    # steady sliding force: the shakedown force of the two contacts
    from tribolmp.models.tribospectroscopy import microslip_force

    q, kk = c.springs(N)
    assert avg.force[-1] == pytest.approx(float(microslip_force(5e-8, q, kk, MU)), rel=1e-12)


# ------------------------------------------------ spring-pulled body (multirate)


def test_tabulated_cycle_mean_force_limits():
    from tribolmp.models.macro import jenkins_mean_force
    from tribolmp.models.macro.reference import vibrated_coulomb_mean_force

    nu = np.linspace(0.0, 0.99, 23)
    # rigid-plastic limit (kappa -> inf): (2/pi) arcsin(nu).  2048 phase points per cycle place each
    # of the two slip reversals to 1/2048 of a cycle, so the mean is off by < 2 * 2/2048 = 2e-3
    assert np.max(np.abs(jenkins_mean_force(nu, 1e8) - vibrated_coulomb_mean_force(nu))) < 2e-3
    # vanishing drift: the shakedown limit max(0, 1 - kappa) of the imposed-drift scheme
    kappa = np.linspace(0.0, 3.0, 31)
    assert np.max(np.abs(jenkins_mean_force(1e-9, kappa) - np.maximum(0.0, 1.0 - kappa))) < 1e-6
    # nu >= 1: the drive never reverses, the spring slides all the time
    assert np.all(jenkins_mean_force(np.array([1.0, 1.5]), np.array([[0.3], [50.0]])) == 1.0)


@pytest.mark.parametrize("amp_frac", [0.5, 1.5])
def test_pulled_body_averaged_matches_brute_force_short_window(amp_frac):
    from tribolmp.models.macro import PulledParams, pulled_under_oscillation

    c = _contact(n=101)
    L = MU * N / c.stiffness(N)
    # 3 ms: the body goes from rest through its first slip (drive force reaches mu N at ~1.5 ms)
    # and slides at nu = v/(a w) ~ 0.2-0.6, where the velocity dependence of the mean force matters
    p = PulledParams(
        mass=0.1,
        drive_stiffness=1e6,
        drive_velocity=1e-2,
        normal_force=N,
        amplitude=amp_frac * L,
        frequency=65e3,
        duration=3e-3,
        steps_per_cycle=32,
    )
    brute = pulled_under_oscillation(p, c, scheme="brute")
    avg = pulled_under_oscillation(p, c, scheme="averaged")
    f_avg = np.interp(brute.t, avg.t, avg.friction)
    x_avg = np.interp(brute.t, avg.t, avg.x)
    # measured 0.7 % (a = 0.5 L) and 1.6 % (a = 1.5 L) of mu N; brute force itself changes by 0.2 %
    # from 32 to 64 steps per cycle.  The shakedown limits alone (no velocity table) would give a
    # sliding force ~0 at a = 1.5 L: measured errors 39 % (a = 0.5 L) and 33 % (a = 1.5 L) of mu N.
    assert np.max(np.abs(brute.friction - f_avg)) < 0.03 * MU * N
    # position: measured 6e-4 / 7e-4 of the travel, the O(dt) phase error of semi-implicit Euler at
    # 32 steps per body-contact period (1e-4 / 3e-4 at 64); deterministic, so no noise margin needed
    assert np.max(np.abs(brute.x - x_avg)) < 1e-3 * np.max(np.abs(brute.x))
    assert brute.friction.max() > 0.2 * MU * N  # the window really reaches sliding
    assert avg.steps < brute.steps / 15


def test_pulled_body_averaged_cost_is_independent_of_frequency():
    from tribolmp.models.macro import PulledParams, pulled_under_oscillation

    c = _contact(n=101)
    steps = {}
    for f in (65e3, 650e3):
        p = PulledParams(
            mass=0.1,
            drive_stiffness=1e6,
            drive_velocity=1e-2,
            normal_force=N,
            amplitude=5e-8,
            frequency=f,
            duration=0.05,
        )
        steps[f] = pulled_under_oscillation(p, c, scheme="averaged").steps
    # 0.05 s of drift; brute force would take 65e3 * 0.05 * 32 = 1e5 (resp. 1e6) steps
    assert steps[65e3] == steps[650e3] < 0.05 * 65e3 * 32 / 20
