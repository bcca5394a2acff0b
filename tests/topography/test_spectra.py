"""Analytic spectra, PSD estimators, roughness metrics and the Hurst fit."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tribolmp.errors import ParameterError
from tribolmp.models.topography import spectra

KW = dict(d0=1.0, dx_noise=1.0, dz=1.0, mu=1e-6, l=1e-3)  # k1 = 1e-3, k2 = 1e3: six decades of k^-2


def test_stationary_psd_plateaus_slope_and_crossovers():
    k1, k2 = spectra.crossover_wavenumbers(**KW)
    assert (k1, k2) == pytest.approx((1e-3, 1e3), rel=1e-12)
    k = np.array([1e-6, 1.0, 1e6])
    s = spectra.stationary_psd(k, **KW)
    # Plateaus to O((k/k1)^2) and O((k2/k)^2) = 1e-6.
    assert s[0] == pytest.approx(KW["dz"] / KW["mu"], rel=1e-5)
    assert s[2] == pytest.approx(KW["dx_noise"] * KW["l"] ** 2 / KW["d0"], rel=1e-5)
    # k^-2 in between: local log slope at the geometric mean of k1, k2.
    kk = np.array([0.99, 1.01])
    ss = spectra.stationary_psd(kk, **KW)
    slope = np.diff(np.log(ss)) / np.diff(np.log(kk))
    assert slope[0] == pytest.approx(-2.0, abs=1e-5)
    assert spectra.crossover_wavenumbers(d0=0.0, dx_noise=0.0, dz=1.0, mu=1.0, l=1.0) == (
        math.inf,
        math.inf,
    )


def test_transient_limits_and_relaxation_time():
    k = np.logspace(-4, 2, 13)
    s_inf = spectra.stationary_psd(k, **KW)
    assert np.all(spectra.transient_psd(k, 0.0, **KW) == 0)
    np.testing.assert_allclose(spectra.transient_psd(k, 1e9, **KW), s_inf, rtol=1e-12)
    tau = spectra.relaxation_time(k, d0=KW["d0"], mu=KW["mu"])
    # At t = tau/2 a flat start holds 1 - e^-1 of the stationary power.
    t_half = tau / 2
    got = np.array([spectra.transient_psd(kk, tt, **KW) for kk, tt in zip(k, t_half)])
    np.testing.assert_allclose(got / s_inf, 1 - math.exp(-1), rtol=1e-12)
    # An initial spectrum decays as exp(-2 gamma t).
    s0 = np.full_like(k, 5.0)
    decayed = 5.0 * np.exp(-2 * (KW["mu"] + KW["d0"] * k**2))
    np.testing.assert_allclose(spectra.transient_psd(k, 1.0, s0=s0, **KW),
                               decayed + spectra.transient_psd(k, 1.0, **KW), rtol=1e-12)
    # mu = 0, k = 0: random walk of the mean, S = 2 Dz t.
    kw0 = dict(KW, mu=0.0)
    assert spectra.transient_psd(0.0, 3.0, **kw0) == pytest.approx(6.0 * KW["dz"])
    assert spectra.stationary_psd(0.0, **kw0) == math.inf
    assert spectra.relaxation_time(0.0, d0=1.0, mu=0.0) == math.inf


def test_lattice_form_tends_to_continuum():
    dx = 0.01
    k = np.array([1e-2, 1.0, 10.0])
    lat = spectra.stationary_psd(k, lattice_dx=dx, **KW)
    cont = spectra.stationary_psd(k, **KW)
    # kappa^2 = k^2 (1 - (k dx)^2/12 + ...): relative difference < (k dx)^2/12 = 8e-4 at k dx = 0.1.
    np.testing.assert_allclose(lat, cont, rtol=1e-3)
    assert spectra.lattice_k2(np.pi / dx, dx) == pytest.approx(4 / dx**2)


def test_euler_psd_limits():
    k = np.array([0.5, 2.0])
    kw = dict(KW, mu=0.1)
    dt = 0.2
    # Stationary Euler PSD = continuum / (1 - gamma dt / 2).
    gamma = kw["mu"] + kw["d0"] * k**2
    np.testing.assert_allclose(spectra.euler_psd(k, math.inf, dt, **kw),
                               spectra.stationary_psd(k, **kw) / (1 - gamma * dt / 2), rtol=1e-12)
    # One step from flat: exactly the noise increment 2 I dt.
    np.testing.assert_allclose(
        spectra.euler_psd(k, 1, dt, **kw),
        2 * (kw["dz"] + kw["dx_noise"] * kw["l"] ** 2 * k**2) * dt,
    )


def test_psd_1d_parseval_and_sinusoid(rng):
    n, dx = 128, 0.5
    h = rng.normal(0.2, 1.0, n)
    k, s = spectra.psd_1d(h, dx)
    s0 = spectra.periodogram(h, dx, 1)[0]
    assert spectra.mean_square_from_psd(k, s, n * dx, s0=s0) == pytest.approx(
        np.mean(h**2), rel=1e-12
    )
    # A sinusoid of amplitude a at k0 puts L a^2 / 4 at +-k0.
    L = n * dx
    m, a = 5, 0.3
    x = np.arange(n) * dx
    k, s = spectra.psd_1d(a * np.cos(2 * np.pi * m * x / L), dx)
    assert k[m - 1] == pytest.approx(2 * np.pi * m / L)
    assert s[m - 1] == pytest.approx(L * a**2 / 4, rel=1e-12)
    assert np.delete(s, m - 1).max() < 1e-25


def test_2d_normalisation_radial_and_line_scans(rng):
    n, dx = 32, 2.0
    h = rng.normal(size=(3, n, n))
    s = spectra.periodogram(h, dx, 2)
    w = np.full(s.shape[-2:], 2.0)
    w[:, 0] = w[:, -1] = 1.0
    # <h^2> = (1/A) sum over the full plane (rfft half-plane with mirror weights).
    np.testing.assert_allclose(
        (w * s).sum(axis=(-2, -1)) / (n * dx) ** 2, np.mean(h**2, axis=(-2, -1)), rtol=1e-12
    )
    # Line scans of the surface equal (1/L) sum_ky of its 2D periodogram, exactly.
    k, s_line = spectra.psd_line_scans(h, dx)
    k2, s_line_th = spectra.line_scan_psd_theory(s.mean(axis=0), n, dx)
    np.testing.assert_allclose(k, k2)
    np.testing.assert_allclose(s_line, s_line_th, rtol=1e-12)
    # Radial average of an isotropic function of |k| returns it at the bin's mean |k|
    # to first order: exact for a linear function.
    kmag, idx, _, nb = spectra.radial_bins(n, dx)
    kb, avg, counts = spectra.radial_average(3.0 * kmag + 1.0, n, dx)
    np.testing.assert_allclose(avg, 3.0 * kb + 1.0, rtol=1e-12)
    assert counts[0] == 4 + 4  # |k| = dk: (+-1, 0), (0, +-1); |k| = sqrt(2) dk rounds to bin 0 too
    with pytest.raises(ParameterError, match="h"):
        spectra.psd_2d_radial(np.zeros((4, 8)), dx)


def test_line_scan_of_k2_surface_goes_as_k_minus_1():
    """PHYSICS.md section 4: a 2D S ~ |k|^-2 seen by a profilometer falls as k^-1."""
    n, dx = 1024, 1.0
    kx = 2 * np.pi * np.fft.fftfreq(n, dx)[:, None]
    ky = 2 * np.pi * np.fft.rfftfreq(n, dx)[None, :]
    kw = dict(
        d0=1.0, dx_noise=1.0, dz=1.0, mu=1e-6, l=1e-3
    )  # k1 = 1e-3 < 2 pi/L, k2 = 1000 > pi/dx
    s2 = spectra.stationary_psd(np.hypot(kx, ky), **kw)
    k, s_line = spectra.line_scan_psd_theory(s2, n, dx)
    # (1/L) sum_q Dz/(D0 (k^2 + q^2)) over |q| < pi/dx -> (Dz/D0) atan(pi/(k dx)) / (pi k):
    # a k^-1 law, bent by the band limit near Nyquist.  Riemann-sum error < 1 % for k >= 10 dk.
    ref = kw["dz"] / kw["d0"] * np.arctan(np.pi / (k * dx)) / (np.pi * k)
    sel = (k > 10 * 2 * np.pi / (n * dx)) & (k < 1.0)
    np.testing.assert_allclose(s_line[sel], ref[sel], rtol=0.01)
    fit = spectra.hurst_fit(k, s_line, kmin=0.06, kmax=0.2, dim=1)
    assert fit.alpha == pytest.approx(1.0, abs=0.05)  # atan factor steepens by < 4 % here
    k_r, s_r, _ = spectra.radial_average(s2, n, dx)
    assert spectra.hurst_fit(k_r, s_r, kmin=0.06, kmax=1.0, dim=2).alpha == pytest.approx(
        2.0, abs=0.01
    )


def test_roughness_of_a_sinusoid():
    n, dx, a, m = 256, 0.1, 0.7, 3
    x = np.arange(n) * dx
    k0 = 2 * np.pi * m / (n * dx)
    h = 2.0 + a * np.sin(k0 * x)
    r = spectra.roughness(h, dx)
    assert r.rq == pytest.approx(a / math.sqrt(2), rel=1e-12)
    assert r.ra == pytest.approx(2 * a / math.pi, rel=1e-3)  # Riemann sum of |sin|: O((m/n)^2)
    # Forward differences see the lattice wavenumber 2/dx sin(k0 dx/2), exactly.
    slope = a * (2 / dx) * math.sin(k0 * dx / 2) / math.sqrt(2)
    assert r.rms_slope == pytest.approx(slope, rel=1e-12)
    assert r.rms_gradient == r.rms_slope
    # 2D: a plane wave along x: gradient = slope; along the diagonal both add.
    H = np.tile(h, (n, 1))
    r2 = spectra.roughness(H, dx)
    assert r2.rms_gradient == pytest.approx(slope, rel=1e-12)
    r3 = spectra.roughness(H + H.T - 2.0, dx)
    assert r3.rms_gradient == pytest.approx(math.sqrt(2) * slope, rel=1e-12)


def test_hurst_fit_power_law():
    k = np.logspace(0, 3, 50)
    for dim, H in ((1, 0.8), (2, 0.3)):
        fit = spectra.hurst_fit(k, 7.0 * k ** -(dim + 2 * H), kmin=1, kmax=1e3, dim=dim)
        assert fit.hurst == pytest.approx(H, abs=1e-10)
        assert fit.alpha_err < 1e-10
    with pytest.raises(ParameterError, match="kmin/kmax"):
        spectra.hurst_fit(k, k**-2, kmin=1e5, kmax=1e6)


def test_psd_consistency_false_alarm_rate():
    """Under the null the test rejects at most ~alpha of the time.

    Here 0 of 200 at alpha = 0.01.
    """
    rng = np.random.default_rng(0)
    rejections = sum(
        not spectra.psd_consistency(rng.exponential(size=(4, 400)), alpha=0.01).passed
        for _ in range(200)
    )
    # Expected <= 2 rejections (Bonferroni is conservative); P(>= 8 | p=0.01) < 1e-3.
    assert rejections < 8
    assert not spectra.psd_consistency(1.2 * rng.exponential(size=(4, 400)), alpha=0.01).passed
