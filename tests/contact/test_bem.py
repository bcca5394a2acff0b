"""3D half-space BEM against Love's solution, Hertz (both forms) and the MDR."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import integrate

from tribolmp.errors import ParameterError
from tribolmp.models.contact import AxisymmetricParams, solve
from tribolmp.models.contact import reference as ref
from tribolmp.models.contact.bem import love_influence, solve_bem, sphere_heights

E, R = 1.0, 1.0


@pytest.mark.parametrize("x,y", [(0.3, 0.1), (2.3, -1.7), (-0.5, 0.5), (0.0, -7.0)])
def test_love_influence_against_quadrature(x, y):
    a = 0.5
    num = integrate.dblquad(
        lambda yy, xx: 1 / (math.pi * E * np.hypot(x - xx, y - yy)),
        -a,
        a,
        -a,
        a,
        epsabs=1e-12,
        epsrel=1e-10,
    )[0]
    assert love_influence(x, y, a, a, E) == pytest.approx(num, rel=1e-8)


def test_nonperiodic_hertz_second_order():
    a_t = 0.2
    d = a_t**2 / R
    F = float(ref.hertz_force(d, R, E))
    errs = []
    for n in (32, 64):
        dx = 1.0 / n
        res = solve_bem(sphere_heights(n, dx, R), dx, E, F, periodic=False)
        errs.append(abs(res.approach / d - 1))
        # complementarity: no tension, no penetration
        gap = res.u - sphere_heights(n, dx, R) + (sphere_heights(n, dx, R).max() - res.approach)
        assert res.p.min() >= 0 and gap.min() >= -1e-9 * d
        assert np.max(np.abs(gap[res.p > 0])) <= 1e-8 * d
    # Piecewise-constant pressure with exact influence coefficients: O(dx^2) -> halving dx must
    # reduce the error by about 4 (measured at 64 -> 128 -> 256: 1.6e-4 -> 7.6e-5 -> 1.7e-5, ratios
    # 2.1, 4.4 because the contact edge is resolved by few pixels; >= 1.8 still excludes O(dx)).
    assert errs[1] < errs[0] / 1.8
    assert errs[1] < 3e-4  # measured 1.6e-4 at 64^2 (12.8 pixels per contact radius)
    # Contact stiffness of Hertz: 2 a E*; pixelated edge -> 1 %.
    assert res.stiffness == pytest.approx(2 * a_t * E, rel=1e-2)


def test_periodic_hertz_with_image_correction():
    n, L = 128, 1.0
    dx = L / n
    a_t = 0.05  # a/L = 0.05 as required by the correction
    d = a_t**2 / R
    F = float(ref.hertz_force(d, R, E))
    res = solve_bem(sphere_heights(n, dx, R), dx, E, F / L**2, periodic=True)
    image = ref.PERIODIC_IMAGE_COEFF * F / (math.pi * E * L)
    # Without the image term the indentation is off by 8 %; with it the error is
    # the discretisation error of a 6.4-pixel contact radius (measured 4e-4).
    assert abs(res.approach / d - 1) > 0.05
    assert abs((res.approach + image) / d - 1) < 2e-3
    # Interfacial stiffness and Hertz compliance are in series with the image compliance.
    k_corr = 1 / (1 / res.stiffness + ref.PERIODIC_IMAGE_COEFF / (math.pi * E * L))
    assert k_corr == pytest.approx(2 * a_t * E, rel=2e-2)


def test_bem_against_mdr_axisymmetric():
    for kw in (dict(profile="cone", half_angle_deg=70.0), dict(profile="sphere", radius=1e-3)):
        p = AxisymmetricParams(E_star=1e11, indentation=1e-6, grid_points=64, **kw)
        mdr, bem = solve(p, method="mdr"), solve(p, method="bem")
        # 64 grid points over 2.5 contact radii: measured 1e-4; the MDR is exact to 1e-6.
        assert bem.force == pytest.approx(mdr.force, rel=1e-3)
        assert bem.contact_radius == pytest.approx(mdr.contact_radius, rel=5e-2)


def test_flat_punch_bem_edge_singularity():
    p = AxisymmetricParams(
        profile="flat", radius=1e-3, E_star=1e11, indentation=1e-6, grid_points=64
    )
    bem = solve(p, method="bem")
    # The 1/sqrt edge singularity is poorly resolved by pixels: first-order error, 1 % at 64^2.
    assert bem.force == pytest.approx(float(ref.flat_punch_force(1e-6, 1e-3, 1e11)), rel=1e-2)


def test_full_contact_and_bad_input():
    n, dx = 32, 1.0 / 32
    rng = np.random.default_rng(3)
    h = 1e-4 * rng.standard_normal((n, n))
    res = solve_bem(h, dx, E, 0.5, periodic=True)
    # A load far above the closing pressure closes the cell: no gap, infinite interfacial stiffness.
    assert res.area_fraction == 1.0 and math.isinf(res.stiffness)
    assert res.mean_gap == pytest.approx(0.0, abs=1e-12)
    punch = solve_bem(h, dx, E, 0.5, periodic=False)
    # A closed rigid square punch: stiffness of a flat square punch, 2 E* sqrt(A/pi) x 1.01-1.02
    # (circular punch of equal area + shape factor); pixel edge adds ~1 %.
    assert punch.area_fraction == 1.0
    assert punch.stiffness / (2 * E * math.sqrt(1.0 / math.pi)) == pytest.approx(1.0, abs=0.04)
    with pytest.raises(ParameterError, match="heights"):
        solve_bem(np.zeros((4, 5)), dx, E, 0.1)
    bad = h.copy()
    bad[0, 0] = np.nan
    with pytest.raises(ParameterError, match="finite"):
        solve_bem(bad, dx, E, 0.1)
