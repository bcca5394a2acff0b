"""Squeeze-film damper in the body's normal direction: exact solutions, positivity, contact engagement."""

import math

import numpy as np
import pytest

from tribolmp.errors import ParameterError
from tribolmp.models.macro import ContactSprings, SqueezeParams, profile_from_geometry, squeeze_approach
from tribolmp.models.macro.reference import squeeze_approach_gap

E_STAR = 206e9 / (2 * (1 - 0.3**2))
G_STAR = 1.0 / (2 * (2 - 0.3) / (4 * 206e9 / 2.6))
W, R, ETA, H0 = 10.0, 5e-3, 0.1, 1e-6
ALPHA = 6 * math.pi * ETA * R**2


def test_massless_constant_load_is_exponential_and_never_negative():
    dur = 200 * ALPHA / W  # h falls by e^-200 (to ~1e-93 m): an explicit step in h would cross zero
    res = squeeze_approach(SqueezeParams(load=W, radius=R, viscosity=ETA, gap=H0, duration=dur))
    assert res.alpha == pytest.approx(ALPHA, rel=1e-14)  # the lubrication model's damper is 6 pi eta R^2
    assert np.all(res.gap > 0)
    exact = squeeze_approach_gap(res.t, H0, W, R, ETA)
    # ln h is linear in t here, which Radau integrates to round-off; 1e-9 = the requested rtol
    assert np.max(np.abs(res.log_gap - np.log(exact / H0))) < 1e-9 * 200
    assert np.max(np.abs(res.gap / exact - 1)) < 1e-9 * 200
    # overdamped: the film carries the whole load at every instant
    assert np.max(np.abs(res.film_force / W - 1)) < 1e-9
    assert np.all(res.contact_force == 0.0)


def test_with_mass_the_first_integral_holds():
    # m h'' = -W + alpha V/h  integrates to  m h' + alpha ln(h/h0) + W t = m h'(0)  (exact, any m)
    m, v0 = 0.02, 1e-4
    dur = 20 * ALPHA / W
    p = SqueezeParams(load=W, radius=R, viscosity=ETA, gap=H0, duration=dur, mass=m, approach_velocity=v0)
    res = squeeze_approach(p)
    assert np.all(res.gap > 0)
    inv = m * (-res.approach_velocity) + ALPHA * res.log_gap + W * res.t - m * (-v0)
    # rtol 1e-9 per step on (ln h, momentum); the invariant's terms are at most W*duration
    assert np.max(np.abs(inv)) < 1e-7 * W * dur
    # once the body has come to rest (V -> 0) the massless exponential is recovered, shifted by
    # the initial momentum: alpha ln(h/h0) = -W t - m v0 (+ m V, here < 1e-6 in ln h)
    assert m * res.approach_velocity[-1] / ALPHA < 1e-6
    assert res.log_gap[-1] == pytest.approx(-W * dur / ALPHA - m * v0 / ALPHA, abs=1e-5)


def test_contact_takes_over_the_load():
    x, g = profile_from_geometry("sphere", W, E_STAR, n_springs=201, radius=R)
    c = ContactSprings(x, g, E_STAR, G_STAR, 0.3)
    d_eq = c.indentation(W)
    hc = 2 * d_eq  # asperities touch at 2 d_eq: equilibrium gap h = d_eq > 0
    res = squeeze_approach(SqueezeParams(load=W, radius=R, viscosity=ETA, gap=3 * d_eq, duration=0.05, contact_gap=hc), c)
    assert np.all(res.gap > 0)
    # static equilibrium: the MDR contact carries W at the indentation d_eq = h_c - h
    assert res.gap[-1] == pytest.approx(hc - d_eq, rel=1e-6)
    assert res.contact_force[-1] == pytest.approx(W, rel=1e-6)
    assert res.contact_force[0] == 0.0 and res.film_force[-1] < 1e-6 * W


def test_bad_inputs_are_one_line_parameter_errors():
    with pytest.raises(ParameterError, match="gap"):
        SqueezeParams(gap=-1e-6)
    with pytest.raises(ParameterError, match="contact"):
        squeeze_approach(SqueezeParams(contact_gap=1e-7))
