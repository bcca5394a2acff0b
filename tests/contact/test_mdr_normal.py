"""Axisymmetric normal MDR against the analytic references."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tribolmp.errors import NoContactError, ParameterError
from tribolmp.models.contact import reference as ref
from tribolmp.models.contact.mdr import (
    AxisymmetricMDR,
    axisymmetric_profile,
    contact_length,
    contact_radius,
    kappa,
    normal_force,
    normal_stiffness,
    profile_transform,
    profile_transform_tabulated,
)

E = 1.0e11
R = 1.0e-3


def test_profile_transform_closed_forms():
    x = np.linspace(-2e-4, 2e-4, 41)
    # Gauss-Legendre on a smooth (polynomial/constant) integrand: exact to round-off.
    assert np.allclose(profile_transform(lambda r: r / R, x), x**2 / R, rtol=1e-13, atol=1e-22)
    t = math.tan(math.radians(70))
    assert np.allclose(
        profile_transform(lambda r: np.full_like(r, 1 / t), x),
        0.5 * math.pi * np.abs(x) / t,
        rtol=1e-13,
    )
    n, c = 3.0, 2.0
    g = profile_transform(lambda r: n * c * r ** (n - 1), x)
    assert np.allclose(g, kappa(n) * c * np.abs(x) ** n, rtol=1e-12, atol=1e-30)
    # kappa_2 = 2 (sphere), kappa_1 = pi/2 (cone)
    assert kappa(2.0) == pytest.approx(2.0, rel=1e-14) and kappa(1.0) == pytest.approx(
        math.pi / 2, rel=1e-14
    )


def test_profile_transform_tabulated_sphere():
    r = np.linspace(0, 1e-4, 200)
    x = np.linspace(-9e-5, 9e-5, 31)
    # A cubic spline reproduces a quadratic exactly, so only round-off remains.
    assert np.allclose(
        profile_transform_tabulated(r, r**2 / (2 * R), x), x**2 / R, rtol=1e-10, atol=1e-20
    )
    with pytest.raises(ParameterError, match="f: expected finite"):
        profile_transform_tabulated(r, np.full_like(r, np.nan), x)


@pytest.mark.parametrize("kind", ["sphere", "cone"])
def test_force_within_1e6_with_at_most_2000_springs(kind):
    d = 1e-6
    if kind == "sphere":
        a, F = math.sqrt(R * d), float(ref.hertz_force(d, R, E))
        kw = dict(radius=R)
    else:
        a, F = float(ref.cone_radius(d, 70.0)), float(ref.cone_force(d, 70.0, E))
        kw = dict(half_angle_deg=70.0)
    x, g = axisymmetric_profile(kind, 1999, 1.5 * a, **kw)
    # Target of the issue: relative error <= 1e-6 (measured 5.6e-7 sphere, 1e-15 cone).
    assert abs(normal_force(x, g, d, E) / F - 1) <= 1e-6
    assert abs(contact_radius(x, g, d) / a - 1) <= 1e-6
    assert normal_stiffness(x, g, d, E) == pytest.approx(2 * a * E, rel=1e-6)


def test_sphere_force_converges_as_dx_squared():
    d = 1e-6
    a = math.sqrt(R * d)
    errs = []
    for n in (101, 201, 401, 801):
        x, g = axisymmetric_profile("sphere", n, 1.5 * a, radius=R)
        errs.append(abs(normal_force(x, g, d, E) / float(ref.hertz_force(d, R, E)) - 1))
    orders = np.log2(np.array(errs[:-1]) / np.array(errs[1:]))
    # Exact integration of the piecewise-linear row with a sub-grid edge: second order
    # (a cell-counting spring sum would be first order).
    assert np.all(orders > 1.9), orders
    # and the constant is the trapezoid one: err = dx^2/(4 a^2)
    dx = 3 * a / 800
    assert errs[-1] == pytest.approx(dx**2 / (4 * a * a), rel=0.02)


def test_power_law_and_large_indentation():
    n, c = 4.0, 3e6  # f = c r^4 (m^-3)
    d = 1e-6
    a = (d / (kappa(n) * c)) ** (1 / n)
    x, g = axisymmetric_profile("power", 1999, 1.5 * a, exponent=n, coefficient=c)
    # O(dx^2) with curvature larger than the sphere's near the edge: 1e-5 is ~20x the measured error
    assert normal_force(x, g, d, E) == pytest.approx(
        float(ref.power_law_force(d, n, c, E)), rel=1e-5
    )
    # Very large indentation (d = 10 R, contact radius 3 R): the paraboloid law is scale-free,
    # so the relative accuracy of the row must not change.
    d = 10 * R
    a = math.sqrt(R * d)
    x, g = axisymmetric_profile("sphere", 1999, 1.5 * a, radius=R)
    assert abs(normal_force(x, g, d, E) / float(ref.hertz_force(d, R, E)) - 1) <= 1e-6
    # A contact larger than the row is an error, not a silently truncated force.
    m = AxisymmetricMDR(*axisymmetric_profile("sphere", 201, 0.5 * a, radius=R), E)
    with pytest.raises(NoContactError, match="exceeds the spring row"):
        m.force(d)


def test_contact_spanning_fewer_than_three_springs():
    # Only the central spring is compressed: a < dx.
    x, g = axisymmetric_profile("sphere", 101, 1e-4, radius=R)
    dx = x[1] - x[0]
    d = 0.5 * dx**2 / R  # a = dx / sqrt(2)
    # Exact integral of the linear row: triangle on each side with root t = d R / dx.
    t = d * R / dx
    assert normal_force(x, g, d, E) == pytest.approx(E * d * t, rel=1e-12)
    assert contact_length(x, g, d) == pytest.approx(2 * t, rel=1e-12)
    # The force is continuous through first touch of the neighbours (no jump at d = g_1):
    g1 = dx**2 / R
    lo, hi = normal_force(x, g, g1 * (1 - 1e-9), E), normal_force(x, g, g1 * (1 + 1e-9), E)
    assert abs(hi - lo) <= 1e-7 * hi
    # The high-level solver refines the row to the contact and stays at 1e-6.
    from tribolmp.models.contact import AxisymmetricParams, solve

    res = solve(
        AxisymmetricParams(profile="sphere", radius=R, E_star=E, indentation=1e-15, springs=1999)
    )
    assert abs(res.force / float(ref.hertz_force(1e-15, R, E)) - 1) <= 1e-6


def test_pressure_and_displacement_hertz():
    d = 1e-6
    a = math.sqrt(R * d)
    x, g = axisymmetric_profile("sphere", 1001, 1.5 * a, radius=R)
    m = AxisymmetricMDR(x, g, E)
    r = np.linspace(0, 1.4 * a, 57)
    p0 = float(ref.hertz_pressure(0.0, d, R, E))
    # Inverse transform of the spline (exact for the quadratic) by Gauss-Legendre: the 1e-4
    # target relative to p0 is met with orders of magnitude to spare.
    assert np.max(np.abs(m.pressure(r, d) - ref.hertz_pressure(r, d, R, E))) <= 1e-4 * p0
    r = np.linspace(0, 3 * a, 61)
    # Outside the contact, the (2/pi) int w1D / sqrt(r^2 - x^2) form must
    # give Hertz's exterior solution.
    assert np.max(np.abs(m.displacement(r, d) - ref.hertz_displacement(r, d, R))) <= 1e-6 * d


def test_pressure_cone():
    d = 1e-6
    a = float(ref.cone_radius(d, 70.0))
    x, g = axisymmetric_profile("cone", 1001, 1.5 * a, half_angle_deg=70.0)
    m = AxisymmetricMDR(x, g, E)
    r = np.linspace(0.01 * a, 0.99 * a, 50)
    p = ref.cone_pressure(r, d, 70.0, E)
    # log-singular tip excluded (r >= 0.01 a); relative 1e-4 target
    assert np.max(np.abs(m.pressure(r, d) / p - 1)) <= 1e-4


def test_flat_punch_edge_singularity():
    R0 = 1e-3
    n = 1001
    m_half = (n - 1) // 2
    dx = R0 / 400.5  # the punch edge sits halfway between springs 400 and 401
    x, g = axisymmetric_profile("flat", n, m_half * dx, radius=R0)
    d = 1e-6
    # The exact integral of the row with a wall at the cell middle is exact for the punch.
    assert normal_force(x, g, d, E) == pytest.approx(
        float(ref.flat_punch_force(d, R0, E)), rel=1e-12
    )
    m = AxisymmetricMDR(x, g, E)
    assert m.x_edge == pytest.approx(R0, rel=1e-12)
    # The jump of q = E* d at the edge gives p ~ 1/sqrt(R^2 - r^2); check right up to the edge,
    # where p grows by 3 orders of magnitude.
    r = R0 * (1 - np.geomspace(1e-6, 1, 30))
    p_ref = ref.flat_punch_pressure(r, d, R0, E)
    # 1e-8: the edge position carries ~1e-16 round-off, amplified 1e6x by
    # a^2 - r^2 at 1 - r/a = 1e-6.
    assert np.max(np.abs(m.pressure(r, d) / p_ref - 1)) <= 1e-8
    assert p_ref[0] / p_ref[-1] > 500


def test_bad_profile_inputs():
    with pytest.raises(ParameterError, match="profile: expected one of"):
        axisymmetric_profile("ellipse", 11, 1.0)
    with pytest.raises(ParameterError, match="radius"):
        axisymmetric_profile("sphere", 11, 1.0)
    with pytest.raises(ParameterError, match="half_angle_deg"):
        axisymmetric_profile("cone", 11, 1.0, half_angle_deg=95.0)
    with pytest.raises(ParameterError, match="n_springs"):
        axisymmetric_profile("sphere", 2, 1.0, radius=1.0)
