"""Forward models of tribospectroscopy against independent references."""

import numpy as np
import pytest

from tribolmp.models.macro.contact import ContactSprings, profile_from_geometry
from tribolmp.models.tribospectroscopy import models as M

E_STAR = 206e9 / (2 * (1 - 0.3**2))
G_STAR = 1.0 / (2 * (2 - 0.3) / (4 * 206e9 / 2.6))


@pytest.mark.parametrize("s", [0.05, 0.5, 1.0, 2.0, 5.0, 20.0, 60.0])
def test_pinning_shape_matches_direct_k_quadrature(s):
    # Two independent evaluations (Neumann/closed-form vs oscillatory k-quadrature
    # resolved to a quarter period): both are converged to ~1e-13, so 1e-10 is a
    # check of the formula, not of the quadrature noise.
    assert M.pinning_shape(s) == pytest.approx(M.pinning_shape_kspace(s), rel=1e-10)


def test_pinning_shape_limits_and_physics_notes():
    assert M.pinning_shape(0.0) == pytest.approx(1.0, abs=1e-14)
    # small s: G = 1F1-series 1 - 3 s^2/2 + O(s^4)
    assert M.pinning_shape(1e-3) == pytest.approx(1 - 1.5e-6, abs=1e-11)
    # PHYSICS.md section 5: F^2 falls ~70 % by a = lambda, then ~ lambda/a
    drop = 1 - M.pinning_shape(1.0)
    assert 0.65 < drop < 0.72
    for s in (1e3, 1e4, 1e5):
        # the asymptote's first correction is O(s^-2) relative (oscillating J0^2 tail)
        assert M.pinning_shape(s) == pytest.approx(
            M.pinning_shape_asymptote(s), rel=10 / s**2 + 1e-9
        )


def test_fast_table_matches_exact():
    s = np.geomspace(1e-5, 1e6, 3001)
    # table of s*G(s) with 1600 cubic nodes in ln s: interpolation error ~h^4 ~ 1e-9
    assert np.max(np.abs(M.pinning_shape_fast(s) / M.pinning_shape(s) - 1)) < 1e-8


def test_shakedown_force_exactly_zero_at_the_limit():
    mu_n, k = 1.5, 1e7
    a_lim = M.shakedown_limit(mu_n, k)
    a = np.array([0.0, 0.5 * a_lim, a_lim, np.nextafter(a_lim, 1.0), 2 * a_lim])
    f = M.shakedown_force(a, mu_n, k)
    assert f[0] == 2 * mu_n
    assert f[1] == pytest.approx(mu_n, rel=1e-14)
    assert f[2] == 0.0 and f[3] == 0.0 and f[4] == 0.0
    assert np.all(f >= 0)


def test_convention_factor_two():
    assert M.to_per_contact(2e-7, "probe") == pytest.approx(1e-7)
    assert M.to_per_contact(2e-7, "per-contact") == pytest.approx(2e-7)
    from tribolmp.errors import ParameterError

    with pytest.raises(ParameterError, match="convention"):
        M.to_per_contact(1e-7, "end")


def test_microslip_hertz_closed_form():
    # Hertz on MDR: each spring shakes down while G* l_i a < mu q_i, which gives
    # F = 2 mu N (1 - a/a_s)^{3/2}, a_s = mu E* d / G* (derived in models.py).
    N, R, mu = 5.0, 5e-3, 0.3
    x, g = profile_from_geometry("sphere", N, E_STAR, n_springs=2001, radius=R)
    c = ContactSprings(x, g, E_STAR, G_STAR, mu)
    q, k = c.springs(N)
    d = c.indentation(N)
    a_s = mu * E_STAR * d / G_STAR
    a = np.linspace(0, 1.2 * a_s, 25)
    f = M.microslip_force(a, q, k, mu)
    ref = 2 * mu * N * np.clip(1 - a / a_s, 0, None) ** 1.5
    # 2001 springs over 1.5 contact radii: the edge cells are resolved sub-grid
    # in the normal force but the shakedown rule acts per spring: O(dx/a) = 1e-3
    assert np.max(np.abs(f - ref)) < 3e-3 * 2 * mu * N
    # initial slope equals the linear model's -2 mu N / (mu N / k_total)
    k_tot = c.stiffness(N)
    slope = (M.microslip_force(1e-3 * a_s, q, k, mu) - 2 * mu * N) / (1e-3 * a_s)
    assert slope == pytest.approx(-2 * k_tot, rel=2e-3)
    # exactly at (and beyond) the micro-slip shakedown limit: no mean force left
    assert M.microslip_force(a_s * 1.0005, q, k, mu) == pytest.approx(0.0, abs=1e-12)
