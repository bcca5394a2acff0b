"""Adhesive MDR (JKR through Heß's rule) against the JKR closed forms."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tribolmp.errors import NoContactError
from tribolmp.models.contact import AxisymmetricParams, solve
from tribolmp.models.contact import reference as ref
from tribolmp.models.contact.mdr import AxisymmetricMDR, axisymmetric_profile

E, R, W = 1.0e9, 1.0e-3, 0.05


@pytest.fixture
def jkr():
    a0 = (9 * math.pi * W * R * R / (2 * E)) ** (1 / 3)  # JKR radius at zero load
    x, g = axisymmetric_profile("sphere", 401, 3 * a0, radius=R)
    return AxisymmetricMDR(x, g, E, W), a0


def test_force_indentation_curve_with_unstable_branch(jkr):
    m, a0 = jkr
    curve = m.jkr_curve(300, a_max=2.5 * a0)
    # Spline of a quadratic: the curve equals the JKR parametric curve to round-off.
    Fref = ref.jkr_force(curve.a, R, E, W)
    dref = ref.jkr_indentation(curve.a, R, E, W)
    scale_F, scale_d = 1.5 * math.pi * W * R, a0 * a0 / R
    assert np.max(np.abs(curve.force - Fref)) <= 1e-9 * scale_F
    assert np.max(np.abs(curve.d - dref)) <= 1e-9 * scale_d
    # The curve contains the unstable branch: d decreases with a below the fixed-grips point.
    assert np.any(np.diff(curve.d) < 0) and np.any(np.diff(curve.d) > 0)


@pytest.mark.parametrize(
    "control,reference",
    [
        ("force", ref.jkr_pull_off_force_control),
        ("displacement", ref.jkr_pull_off_displacement_control),
    ],
)
def test_pull_off_within_1e4(jkr, control, reference):
    m, _ = jkr
    po = m.pull_off(control)
    # Issue target 1e-4; the stationary point is a root of the analytic slope, so we get ~1e-12.
    assert po["force"] == pytest.approx(reference(R, W), rel=1e-4)
    assert po["force"] == pytest.approx(reference(R, W), rel=1e-9)


def test_pull_off_of_a_profile_the_spline_does_not_reproduce():
    # g = x^2/R (1 + |x|/c)^(1/2) is not a piecewise cubic, so the spline adds an
    # interpolation error.  The sub-grid (continuous) edge keeps the pull-off of a
    # 101-spring row within the 1e-4 of the converged (8001-spring) value;
    # a whole-spring edge would be off by O(dx/a) ~ 1e-2 here.
    def pull(n, control):
        x = np.linspace(-3e-4, 3e-4, n)
        g = x * x / R * (1 + np.abs(x) / 3e-4) ** 0.5
        return AxisymmetricMDR(x, g, E, W).pull_off(control)["force"]

    for control in ("force", "displacement"):
        fine = pull(8001, control)
        assert abs(pull(101, control) / fine - 1) <= 1e-4


def test_jkr_next_to_pull_off(jkr):
    m, _ = jkr
    crit = m.pull_off("displacement")
    d_c = crit["indentation"]
    # Just above the fixed-grips instability there is still a (stable) contact whose
    # force is the JKR force at the larger root of d(a) = d.
    d = d_c + 1e-6 * abs(d_c)
    a, F = m.jkr_at_indentation(d)
    assert a > crit["contact_radius"]
    assert F == pytest.approx(float(ref.jkr_force(a, R, E, W)), rel=1e-9)
    assert float(ref.jkr_indentation(a, R, E, W)) == pytest.approx(d, rel=1e-9)
    # Near the fold, a - a_c ~ sqrt(d - d_c): a tiny step in d moves a by ~1e-3 a_c.
    assert 1e-4 < (a - crit["contact_radius"]) / crit["contact_radius"] < 1e-2
    with pytest.raises(NoContactError, match="below the pull-off"):
        m.jkr_at_indentation(d_c - 1e-6 * abs(d_c))


def test_flat_punch_adhesion_kendall():
    res = solve(
        AxisymmetricParams(profile="flat", radius=R, E_star=E, indentation=1e-7, work_of_adhesion=W)
    )
    # Kendall (1971): F = -sqrt(8 pi R^3 w E*)
    assert res.pull_off_force == pytest.approx(-math.sqrt(8 * math.pi * R**3 * W * E), rel=1e-12)
    assert res.force == pytest.approx(2 * E * R * 1e-7, rel=1e-12)


def test_solver_pull_off_through_params():
    res = solve(
        AxisymmetricParams(
            profile="sphere", radius=R, E_star=E, indentation=0.0, work_of_adhesion=W, springs=201
        )
    )
    assert res.pull_off_force == pytest.approx(ref.jkr_pull_off_force_control(R, W), rel=1e-4)
    assert res.pull_off_force_displacement_control == pytest.approx(
        ref.jkr_pull_off_displacement_control(R, W), rel=1e-4
    )
    # d = 0 with adhesion: a = (2 pi w R^2 / E*)^(1/3)
    assert res.contact_radius == pytest.approx((2 * math.pi * W * R * R / E) ** (1 / 3), rel=1e-9)
