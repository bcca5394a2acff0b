"""Film resistance of a rough apparent contact.

Flow factor against a resolved 2D rough Reynolds solve.
"""

from __future__ import annotations

import numpy as np
import pytest

from tribolmp.models.lubrication import flow_factor as ff

ETA = 0.1


def test_square_constant_is_the_fourier_series():
    # the shipped constant against its double series (terms ~ m^-6: 2000 odd terms leave < 1e-12)
    assert ff.SQUARE_POISSON == pytest.approx(ff.square_poisson_integral(), rel=1e-11)


@pytest.mark.parametrize("n, tol", [(32, 4.5e-3), (64, 1.2e-3)])
def test_rough_reynolds_solver_on_a_uniform_gap_is_the_plate_squeeze_film(n, tol):
    # uniform gap: the exact squeeze film of a square plate, F = 12 eta V I / h^3; the
    # cell-centred scheme is second order: measured errors 3.76e-3 (n = 32) and 9.4e-4 (n = 64)
    L, h = 1e-3, 1e-6
    res = ff.rough_reynolds_squeeze(np.full((n, n), h), L / n, ETA)
    exact = 12 * ETA * ff.SQUARE_POISSON * L**4 / h**3
    assert abs(res.resistance / exact - 1) < tol


def _surfaces(n, dx, sigma, seeds, hurst=0.8):
    from tribolmp.models.contact.rough import generate_surface, self_affine_psd

    psd = self_affine_psd(
        sigma, hurst, 16 * dx, 4 * dx
    )  # 8 roll-off wavelengths across, cut-off 4 pixels
    for s in seeds:
        z = generate_surface(n, dx, psd, np.random.default_rng(s))
        yield z - z.mean()


@pytest.mark.parametrize("hurst", [0.8, 0.5])
@pytest.mark.parametrize("method, expect_pass", [("bruggeman", True), ("smooth", False)])
def test_flow_factor_film_matches_resolved_rough_reynolds(method, expect_pass, hurst):
    """The nominal film with the Bruggeman conductance against 2D Reynolds on the rough gap.

    Four 128^2 surfaces per class (H = 0.8 or 0.5, roll-off 16 px, cut-off 4 px),
    rigid flat at u/sigma = 4.5, 5 and 6 (no contact).  Measured ratio
    rough/nominal, H = 0.8: Bruggeman 0.997 at all three (seed scatter 0.7 %),
    Patir-Cheng 0.987 / 0.995 / 1.004, the smooth nominal film u^3 (roughness
    ignored) 1.064 / 1.052 / 1.037; H = 0.5: Bruggeman 1.000 / 0.999 / 0.998,
    smooth 1.067 / 1.054 / 1.038.  A 2 % band on the 4-seed mean is 2.5 seed
    standard errors plus the solver's 0.1 % grid error; it rejects the smooth film.
    """
    n, dx, sigma = 128, 1e-6, 0.5e-6
    zs = list(_surfaces(n, dx, sigma, range(4), hurst))
    ok = []
    for us in (4.5, 5.0, 6.0):
        ratios = []
        for z in zs:
            u = us * z.std()
            h = np.clip(u - z, 0.0, None)
            assert (
                h.min() > 0
            )  # the comparison is in the open-film regime (see docs/lubrication.md)
            ref = ff.rough_reynolds_squeeze(h, dx, ETA)
            c, _, closed = ff.film_resistance(
                h.ravel(), ETA, "square", n * dx, method=method, separation=u
            )
            ratios.append(ref.resistance / float(c))
        ok.append(abs(np.mean(ratios) - 1) < 0.02)
    assert all(ok) is expect_pass


def test_bruggeman_limits():
    # uniform gap: k_eff = h^3 exactly; half the samples closed: sealed (k_eff = 0)
    assert ff.bruggeman_conductance(np.full(10, 2e-6)) == pytest.approx(8e-18, rel=1e-12)
    assert ff.bruggeman_conductance(np.array([0.0, 0.0, 1e-6, 2e-6])) == 0.0
    # two-phase 50/50 open medium: the 2D Bruggeman (Keller/Dykhne) result is the geometric mean
    k = ff.bruggeman_conductance(np.array([1e-6, 2e-6] * 5))
    assert k == pytest.approx(np.sqrt(1e-18 * 8e-18), rel=1e-10)
