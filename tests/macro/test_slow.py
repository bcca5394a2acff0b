"""Longer physics runs (pytest -m slow): convergence of the multirate scheme, stiff cost scaling."""

import numpy as np
import pytest

from tribolmp.models.macro import (
    ConstantFriction,
    ContactSprings,
    DriftParams,
    StickSlipParams,
    drift_under_oscillation,
    profile_from_geometry,
    stick_slip,
)

E_STAR = 206e9 / (2 * (1 - 0.3**2))
G_STAR = 1.0 / (2 * (2 - 0.3) / (4 * 206e9 / 2.6))


@pytest.mark.slow
def test_averaged_error_vanishes_with_the_drift_per_cycle():
    N, mu = 5.0, 0.3
    x, g = profile_from_geometry("sphere", N, E_STAR, n_springs=101, radius=5e-3)
    c = ContactSprings(x, g, E_STAR, G_STAR, mu)
    L = mu * N / c.stiffness(N)
    errs = []
    for frac in (0.02, 0.005):  # drift per cycle as a fraction of mu N / k
        n_cyc = int(2.5 / frac)  # drift 2.5 L: well into steady sliding
        p = DriftParams(
            normal_force=N,
            amplitude=0.5 * L,
            frequency=65e3,
            sliding_velocity=frac * L * 65e3,
            duration=n_cyc / 65e3,
            steps_per_cycle=16,
            slow_steps=n_cyc,
        )
        b = drift_under_oscillation(p, c, scheme="brute")
        a = drift_under_oscillation(p, c, scheme="averaged")
        errs.append(np.max(np.abs(b.force - np.interp(b.t, a.t, a.force))) / (2 * mu * N))
    # the averaging error is O(V/(a w)): a 4x smaller drift per cycle must shrink it by > 2x
    assert errs[1] < errs[0] / 2
    assert errs[1] < 5e-3


@pytest.mark.slow
def test_implicit_cost_flat_explicit_cost_grows_with_contact_stiffness():
    law = ConstantFriction(0.4, 0.3)
    nfev = {}
    for method in ("radau-rk45", "rk45"):
        for kc in (1e9, 1e12):
            p = StickSlipParams(
                mass=0.1,
                drive_stiffness=1e5,
                drive_velocity=0.01,
                normal_force=10.0,
                duration=0.01,
                contact_stiffness=kc,
                rtol=1e-8,
            )
            nfev[method, kc] = stick_slip(p, law, method=method).nfev
    # explicit RK is stability-limited by omega_c ~ sqrt(k_c): 1000x stiffer -> ~30x more work
    assert nfev["rk45", 1e12] > 10 * nfev["rk45", 1e9]
    # the implicit stick phase does not care
    assert nfev["radau-rk45", 1e12] < 1.5 * nfev["radau-rk45", 1e9]


@pytest.mark.slow
def test_pulled_body_averaged_matches_brute_force_over_20_ms():
    from tribolmp.models.macro import PulledParams, pulled_under_oscillation

    N, mu = 5.0, 0.3
    x, g = profile_from_geometry("sphere", N, E_STAR, n_springs=101, radius=5e-3)
    c = ContactSprings(x, g, E_STAR, G_STAR, mu)
    L = mu * N / c.stiffness(N)
    # 20 ms = 1300 cycles: first slip, then a long stretch of steady sliding with the body-contact
    # mode ringing down; drift 0.2 mm
    p = PulledParams(
        mass=0.1,
        drive_stiffness=1e6,
        drive_velocity=1e-2,
        normal_force=N,
        amplitude=0.5 * L,
        frequency=65e3,
        duration=0.02,
        steps_per_cycle=32,
    )
    b = pulled_under_oscillation(p, c, scheme="brute")
    a = pulled_under_oscillation(p, c, scheme="averaged")
    # same bound as the 3 ms default test (averaging error 0.7 % of mu N
    # there); it must not grow with time
    assert np.max(np.abs(b.friction - np.interp(b.t, a.t, a.friction))) < 0.03 * mu * N
    assert np.max(np.abs(b.x - np.interp(b.t, a.t, a.x))) < 1e-3 * np.max(np.abs(b.x))
    assert a.steps < b.steps / 15
