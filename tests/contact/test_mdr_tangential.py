"""Tangential MDR (per-spring Coulomb friction with memory) against Mindlin's closed forms."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from tribolmp.models.contact import reference as ref
from tribolmp.models.contact.mdr import TangentialMDR, axisymmetric_profile

E, G, MU, R, D = 1.0e11, 4.0e10, 0.3, 1.0e-3, 1.0e-6
A = math.sqrt(R * D)
US = ref.mindlin_slip_displacement(D, MU, E, G)
FN = float(ref.hertz_force(D, R, E))


@pytest.fixture
def model():
    x, g = axisymmetric_profile("sphere", 2001, 1.25 * A, radius=R)
    return TangentialMDR(x, g, E, G, MU)


def test_cattaneo_mindlin_monotonic(model):
    Fn, Fx = model.step(D, 0.0)
    assert Fx == 0.0 and Fn == pytest.approx(FN, rel=1e-6)
    # Initial tangential stiffness of the sticking contact: G* 2a (MDR G*).
    assert model.stiffness_x == pytest.approx(G * 2 * A, rel=1e-5)
    us = np.linspace(0, 1.2 * US, 61)[1:]
    Fx = np.array([model.step(D, u)[1] for u in us])
    Fref = ref.mindlin_force(us, D, R, MU, E, G)
    # Spring-row discretisation with a sub-grid edge: measured error ~1e-6 of mu F_N;
    # 1e-4 leaves room without hiding a wrong law (a factor-4 G* error gives ~30 %).
    assert np.max(np.abs(Fx - Fref)) <= 1e-4 * MU * FN
    # Full sliding: every spring at its Coulomb limit, F_x = mu F_N.
    assert Fx[-1] == pytest.approx(MU * Fn, rel=1e-12)
    assert model.stiffness_x == 0.0


def test_unloading_and_oscillation_loop(model):
    ua = 0.6 * US
    model.step(D, 0.0)
    for u in np.linspace(0, ua, 80)[1:]:
        model.step(D, u)
    down = np.linspace(ua, -ua, 161)[1:]
    Fdown = np.array([model.step(D, u)[1] for u in down])
    # Mindlin-Deresiewicz unloading branch (Masing rule, exact for Hertz at constant F_N).
    Fref = ref.mindlin_unloading_force(down, ua, D, R, MU, E, G)
    assert np.max(np.abs(Fdown - Fref)) <= 2e-4 * MU * FN
    # A full cycle: the loop closes and its area is Mindlin's dissipation.
    up = np.linspace(-ua, ua, 161)[1:]
    Fup = np.array([model.step(D, u)[1] for u in up])
    # Loop area: integral of the upper (loading) minus the lower (unloading) branch.
    u_dn, F_dn = np.concatenate([[ua], down]), np.concatenate([[Fup[-1]], Fdown])
    u_up, F_up = np.concatenate([[-ua], up]), np.concatenate([[Fdown[-1]], Fup])
    W = np.trapezoid(F_up, u_up) + np.trapezoid(F_dn, u_dn)
    Wref = ref.mindlin_dissipation(ua, D, R, MU, E, G)
    assert Wref > 0
    # Trapezoidal loop area with 160 steps per branch: O(du^2) on a smooth loop -> 1e-3.
    assert W == pytest.approx(Wref, rel=1e-3)
    # Second cycle repeats the first (steady loop after the virgin branch).
    Fdown2 = np.array([model.step(D, u)[1] for u in down])
    assert np.max(np.abs(Fdown2 - Fdown)) <= 1e-9 * MU * FN


def test_normal_unloading_releases_tangential_force(model):
    model.step(D, 0.0)
    model.step(D, 0.5 * US)
    # Reduce the normal load at fixed u: the Coulomb limits shrink, outer springs slip or leave.
    Fn, Fx = model.step(0.5 * D, 0.5 * US)
    assert Fn == pytest.approx(float(ref.hertz_force(0.5 * D, R, E)), rel=1e-5)
    assert abs(Fx) <= MU * Fn * (1 + 1e-12)
    # Lifting off forgets everything; the next contact starts unstretched.
    assert model.step(-D, 0.5 * US) == (0.0, 0.0)
    Fn, Fx = model.step(D, 0.5 * US)
    assert Fx == 0.0
    model.reset()
    assert model.step(D, 0.0)[1] == 0.0


def test_mindlin_dissipation_closed_form():
    # Independent check of the closed form by direct integration of the two Masing branches,
    # below and beyond the gross-slip amplitude u_s.
    for ua in (0.3 * US, 0.95 * US, 1.5 * US):
        u = np.linspace(-ua, ua, 200001)
        up = -ref.mindlin_unloading_force(-u, ua, D, R, MU, E, G)
        down = ref.mindlin_unloading_force(u, ua, D, R, MU, E, G)
        W = np.trapezoid(up - down, u)
        # trapezoid on 2e5 points of a loop with a (1 - u/u_s)^(3/2) cusp: 1e-6
        assert ref.mindlin_dissipation(ua, D, R, MU, E, G) == pytest.approx(W, rel=1e-6)
    # Small amplitudes: W = mu F_N u*^3 / (2 u_s^2) ... leading term of the series, i.e. W ~ u*^3.
    w1, w2 = (ref.mindlin_dissipation(f * US, D, R, MU, E, G) for f in (1e-3, 2e-3))
    assert w2 / w1 == pytest.approx(8.0, rel=1e-2)


@settings(max_examples=40, deadline=None)
@given(st.lists(st.tuples(st.floats(-0.2, 1.5), st.floats(-2.0, 2.0)), min_size=1, max_size=30))
def test_any_history_respects_coulomb(history):
    # Invariants of the per-spring model for arbitrary quasi-static histories:
    # the normal force is that of the row, |F_x| <= mu F_n, and sticking springs add stiffness only.
    from tribolmp.models.contact.mdr import normal_force

    x, g = axisymmetric_profile("sphere", 201, 1.5 * A, radius=R)
    m = TangentialMDR(x, g, E, G, MU)
    for fd, fu in history:
        Fn, Fx = m.step(fd * D, fu * US)
        assert Fn == pytest.approx(normal_force(x, g, fd * D, E), rel=1e-12, abs=1e-300)
        assert abs(Fx) <= MU * Fn * (1 + 1e-12) + 1e-300
        assert (
            0.0 <= m.stiffness_x <= G * 2 * math.sqrt(R * max(fd * D, 0.0)) * (1 + 1e-12) + 1e-300
        )
