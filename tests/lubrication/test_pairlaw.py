"""The Eq. 13 pair law: quadrature, element-size rule, normal-only use."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tribolmp.errors import ParameterError
from tribolmp.models.lubrication import pairlaw
from tribolmp.models.lubrication import reference as ref

R, ETA, V = 1e-3, 0.1, 1e-3


@pytest.mark.parametrize("eps", [0.1, 1e-2, 1e-4])
def test_ring_quadrature_reproduces_sphere_plane_force(eps):
    res = pairlaw.sphere_plane_pair_force(R, ETA, eps * R, V, refine=0.5)
    # midpoint rule on rings no wider than half the local gap: measured <= 0.9 %
    assert abs(res.rel_error) < 0.01
    fine = pairlaw.sphere_plane_pair_force(R, ETA, eps * R, V, refine=0.125)
    assert abs(fine.rel_error) < abs(res.rel_error)  # converges under refinement
    assert abs(fine.rel_error) < 1e-3


def test_pair_law_integral_is_the_6pi_damper_not_eq11():
    eps = 1e-3
    exact = pairlaw.pairlaw_sphere_plane_exact(R, ETA, eps * R, V)
    assert exact == pytest.approx(ref.damper_force(R, ETA, eps * R, V) / (1 + eps / 2), rel=1e-14)
    assert exact / (3 * math.pi * ETA * R**2 * V / (eps * R)) == pytest.approx(2.0, rel=1e-3)


def test_element_size_rule_refuses_coarse_meshes():
    with pytest.raises(ParameterError, match="refine"):
        pairlaw.sphere_plane_pair_force(R, ETA, 1e-3 * R, V, refine=0.6)
    with pytest.raises(ParameterError, match="h/2"):
        pairlaw.check_element_size([1e-7, 3e-7], [1e-6, 4e-7])
    pairlaw.check_element_size([1e-7, 2e-7], [1e-6, 4e-7])  # exactly h/2 is allowed


def test_tiny_gap_is_refused_not_run_forever():
    with pytest.raises(ParameterError, match="ring pairs"):
        pairlaw.sphere_plane_pair_force(R, ETA, 1e-8 * R, V)


def test_point_elements_need_size_below_half_gap():
    # One element at height z above a plane of square elements of side s; the exact
    # plane integral is (6 eta R / pi) * pi V / (2 z^2) = 3 eta R V / z^2.
    z = 1e-6
    exact = 3 * ETA * R * V / z**2

    def plane_sum(s):
        half = 40 * z
        c = np.arange(-half + s / 2, half, s)
        X, Y = np.meshgrid(c, c)
        pos_b = np.stack([X.ravel(), Y.ravel(), np.zeros(X.size)], 1)
        area_b = np.full(X.size, s * s)
        f = pairlaw.pair_forces([[0, 0, z]], [1.0], [0, 0, -V], pos_b, area_b, [0, 0, 0], ETA, R)
        return f[0, 2] / (
            1 - 1 / (1 + 1600)
        )  # remove the plane-truncation share (z/40z)^2 exactly to O(1e-7)

    good = plane_sum(z / 2) / exact - 1
    bad = plane_sum(2 * z) / exact - 1
    assert abs(good) < 0.02  # elements of h/2: a few 1e-3 off
    assert abs(bad) > 0.10  # elements of 2h: tens of per cent off (PHYSICS.md: 10-160 %)
    f = pairlaw.pair_forces([[0, 0, z]], [1.0], [0, 0, -V], [[0, 0, 0]], [1.0], [0, 0, 0], ETA, R)
    assert f[0, 2] > 0  # approach -> repulsion


def test_pair_law_is_central_so_pure_sliding_at_equal_height_gives_no_normal_force():
    # Two elements side by side sliding perpendicular to their separation do not approach:
    # the central law gives zero -- it cannot represent the tangential drag (use GCB for that).
    f = pairlaw.pair_forces(
        [[0, 0, 1e-6]], [1e-12], [1.0, 0, 0], [[0, 1e-6, 1e-6]], [1e-12], [0, 0, 0], ETA, R
    )
    assert np.allclose(f, 0.0)
