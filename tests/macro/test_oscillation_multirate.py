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
    res = oscillate(OscillationParams(normal_force=N, amplitude=amp, frequency=65e3, cycles=3, steps_per_cycle=400), c)
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
    assert np.max(np.abs(f[unload] - mindlin_loop(u[unload], amp, MU * N, u_s, "unload"))) < 5e-3 * MU * N
    assert np.max(np.abs(f[~unload] - mindlin_loop(u[~unload], amp, MU * N, u_s, "reload"))) < 5e-3 * MU * N
    w_ref = mindlin_dissipation(amp, MU * N, u_s)
    # loop area: trapezoid with 400 steps per cycle (O(1/400^2)) plus the
    # spring discretisation of the slip annulus (O(dx/a) ~ 3e-3)
    assert res.dissipation_per_cycle_J[-1] == pytest.approx(w_ref, rel=5e-3)
    assert res.dissipation_per_cycle_J[-1] == pytest.approx(res.dissipation_per_cycle_J[-2], rel=1e-9)


def test_averaged_scheme_matches_brute_force_short_window():
    c = _contact(n=101)
    k = c.stiffness(N)
    L = MU * N / k
    for a in (0.4 * L, 1.0 * L):
        # drift per cycle V/f = 1.5 nm = 2.5 % (a = 0.4 L) of the amplitude
        p = DriftParams(normal_force=N, amplitude=a, frequency=65e3, velocity=1e-4, duration=0.6e-3, steps_per_cycle=32,
                        slow_steps=40)
        brute = drift_under_oscillation(p, c, scheme="brute")
        avg = drift_under_oscillation(p, c, scheme="averaged")
        f_avg = np.interp(brute.t, avg.t, avg.force)
        # the averaged error is O(V/(a w)) of the force scale 2 mu N
        assert np.max(np.abs(brute.force - f_avg)) < 0.01 * 2 * MU * N
        assert avg.steps < brute.steps / 20


def test_averaged_cost_is_independent_of_frequency():
    c = _contact(n=101)
    p = DriftParams(normal_force=N, amplitude=5e-8, frequency=65e3, velocity=1e-4, duration=1.0, slow_steps=400)
    avg = drift_under_oscillation(p, c, scheme="averaged")
    # one second of drift at 65 kHz: brute force would take 65e3 * 32 = 2e6 steps
    assert avg.steps == 400
    # steady sliding force: the shakedown force of the two contacts
    from tribolmp.models.tribospectroscopy import microslip_force

    q, kk = c.springs(N)
    assert avg.force[-1] == pytest.approx(float(microslip_force(5e-8, q, kk, MU)), rel=1e-12)
