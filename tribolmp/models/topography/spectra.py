"""Theory and measurement of surface power spectra for Eq. 23.

Conventions (used everywhere in :mod:`tribolmp.models.topography`)
-------------------------------------------------------------------
A periodic surface of ``n`` points per side, spacing ``dx`` (m), side
``L = n dx`` and area ``A = L**dim``.  The power spectral density ``S(k)`` is
normalised so that the mean square height is the sum over *all* lattice
wavenumbers (both signs):

    <h^2> = (1/A) * sum_k S(k)                                   (A = L in 1D)

``S`` has units m^3 in 1D and m^4 in 2D.  With ``hat h = sum_j h_j
exp(-i k x_j)`` (numpy's forward DFT) the periodogram is
``S = dx**dim / n**dim * |hat h|**2``.  The estimators return positive
wavenumbers only; for a 1D profile the identity reads
``<h^2> = (S(0) + 2 sum_{0<k<k_N} S(k) + S(k_N)) / L``
(see :func:`mean_square_from_psd`).

Theory (PHYSICS.md section 4)
-----------------------------
Every Fourier mode of Eq. 23 is an Ornstein-Uhlenbeck process with rate
``gamma(k) = mu + D0 k^2`` and noise intensity ``(Dz + Dx l^2 k^2) F~(k)``, so

    S(k, t) = S(k, 0) exp(-2 gamma t) + (Dz + Dx l^2 k^2) F~(k) (1 - exp(-2 gamma t)) / gamma

which tends to the stationary ``S(k) = (Dz + Dx l^2 k^2) F~(k) / (mu + D0 k^2)``.
The lattice (finite-difference) form replaces ``k^2`` by
``kappa^2 = sum_i (2/dx sin(k_i dx/2))^2`` in both the operator and the
conserved noise.  ``F~`` is the Fourier transform of the unit-integral noise
correlation; a Gaussian of length ``l_c`` gives ``F~ = exp(-k^2 l_c^2 / 2)``
and ``l_c = 0`` the delta correlation ``F~ = 1``.

References
----------
.. [1] M. Schargott, V. L. Popov, "Diffusion as a model of formation and
   development of surface topography", Tribol. Int. 39 (2006) 431-436,
   doi:10.1016/j.triboint.2005.04.015.
.. [2] V. L. Popov et al., "Numerical simulation methods in tribology",
   Tribol. Int. 40 (2007) 916-923, doi:10.1016/j.triboint.2006.02.020.
"""

from __future__ import annotations

import math

import numpy as np

from ...errors import ParameterError
from ..base import Result

__all__ = [
    "noise_spectrum",
    "lattice_k2",
    "stationary_psd",
    "transient_psd",
    "euler_psd",
    "psd_consistency",
    "crossover_wavenumbers",
    "relaxation_time",
    "periodogram",
    "psd_1d",
    "psd_2d_radial",
    "psd_line_scans",
    "radial_average",
    "radial_bins",
    "line_scan_psd_theory",
    "mean_square_from_psd",
    "log_bin",
    "roughness",
    "hurst_fit",
]


# ------------------------------------------------------------------ theory


def noise_spectrum(k, correlation_length: float = 0.0):
    """Fourier transform F~(k) of the unit-integral Gaussian noise correlation.

    Parameters
    ----------
    k : array_like
        Wavenumber magnitude (1/m).
    correlation_length : float
        Correlation length l_c (m); 0 gives delta-correlated noise, F~ = 1.

    Returns
    -------
    ndarray
        Dimensionless F~(k) = exp(-k^2 l_c^2 / 2).
    """
    k = np.asarray(k, dtype=float)
    if correlation_length == 0.0:
        return np.ones_like(k)
    return np.exp(-0.5 * (k * correlation_length) ** 2)


def lattice_k2(k, dx: float):
    """Eigenvalue of the minus 3-point lattice Laplacian along one axis (1/m^2).

    ``(2/dx sin(k dx/2))^2``; tends to ``k^2`` for ``k dx << 1``.
    """
    k = np.asarray(k, dtype=float)
    return (2.0 / dx * np.sin(0.5 * k * dx)) ** 2


def _k2(k, dx: float | None):
    return np.asarray(k, dtype=float) ** 2 if dx is None else lattice_k2(k, dx)


def stationary_psd(k, *, d0, dx_noise, dz, mu, l, correlation_length=0.0, lattice_dx=None, k2=None):
    """Stationary PSD of Eq. 23, S(k) = (Dz + Dx l^2 k^2) F~(k) / (mu + D0 k^2).

    Parameters
    ----------
    k : array_like
        Wavenumber magnitude (1/m).
    d0 : float
        Surface diffusion coefficient D0 (m^2/s).
    dx_noise, dz : float
        Conserved and non-conserved noise intensities Dx, Dz (m^3/s in 1D,
        m^4/s in 2D).
    mu : float
        Wear rate constant (1/s).
    l : float
        Step length of the stochastic flux (m).
    correlation_length : float
        Noise correlation length l_c (m); 0 = delta-correlated.
    lattice_dx : float, optional
        Grid spacing (m): use the lattice form with ``kappa^2`` for a 1D
        lattice (or a wavevector along one axis of a 2D lattice).
    k2 : array_like, optional
        Operator eigenvalue to use instead of ``k^2`` (e.g. the 2D lattice
        ``kappa_x^2 + kappa_y^2``); overrides ``lattice_dx``.

    Returns
    -------
    ndarray
        S(k) in m^3 (1D) or m^4 (2D); ``inf`` where ``mu + D0 k^2 = 0`` and
        the noise is non-zero (no stationary state).
    """
    return transient_psd(k, math.inf, d0=d0, dx_noise=dx_noise, dz=dz, mu=mu, l=l,
                         correlation_length=correlation_length, lattice_dx=lattice_dx, k2=k2)


def _phi(gamma, t):
    """(1 - exp(-2 gamma t)) / (2 gamma), continuous at gamma = 0 (value t)."""
    gamma = np.asarray(gamma, dtype=float)
    if math.isinf(t):
        with np.errstate(divide="ignore"):
            return np.where(gamma > 0, 0.5 / np.where(gamma > 0, gamma, 1.0), math.inf)
    safe = np.where(gamma > 0, gamma, 1.0)
    return np.where(gamma > 0, -np.expm1(-2.0 * safe * t) / (2.0 * safe), t)


def transient_psd(
    k, t, *, d0, dx_noise, dz, mu, l, correlation_length=0.0, lattice_dx=None, k2=None, s0=None
):
    """Transient PSD S(k, t) of Eq. 23 from an initial spectrum ``s0`` (default flat start).

    ``S(k,t) = s0 exp(-2 gamma t) + 2 (Dz + Dx l^2 k^2) F~ (1 - exp(-2 gamma t)) / (2 gamma)``
    with ``gamma = mu + D0 k^2``; for ``gamma = 0`` (mu = 0 at k = 0) the
    noise term grows linearly, ``2 Dz t``.  Same arguments as
    :func:`stationary_psd` plus ``t`` (s) and ``s0`` (initial S, same units).
    """
    k = np.asarray(k, dtype=float)
    kk = np.asarray(k2, dtype=float) if k2 is not None else _k2(k, lattice_dx)
    gamma = mu + d0 * kk
    intensity = (dz + dx_noise * l**2 * kk) * noise_spectrum(k, correlation_length)
    with np.errstate(invalid="ignore"):
        noise = np.where(intensity > 0, 2.0 * intensity * _phi(gamma, t), 0.0)
    if s0 is None:
        return noise
    return noise + np.asarray(s0, dtype=float) * np.exp(-2.0 * gamma * t)


def euler_psd(
    k,
    steps,
    dt,
    *,
    d0,
    dx_noise,
    dz,
    mu,
    l,
    correlation_length=0.0,
    lattice_dx=None,
    k2=None,
    s0=None,
):
    """Exact expected PSD after ``steps`` explicit Euler-Maruyama steps of ``dt`` (s).

    Per mode the scheme is ``X <- r X + sqrt(2 I dt) xi`` with
    ``r = 1 - gamma dt`` and ``I = (Dz + Dx l^2 k^2) F~``, so
    ``S_n = s0 r^(2n) + 2 I dt (1 - r^(2n)) / (1 - r^2)``; for
    ``n -> inf`` this is the continuum value inflated by ``1/(1 - gamma dt/2)``.
    Pass the lattice eigenvalue (``lattice_dx`` or ``k2``) to describe the
    finite-difference scheme.
    """
    k = np.asarray(k, dtype=float)
    kk = np.asarray(k2, dtype=float) if k2 is not None else _k2(k, lattice_dx)
    gamma = mu + d0 * kk
    intensity = (dz + dx_noise * l**2 * kk) * noise_spectrum(k, correlation_length)
    r2 = (1.0 - gamma * dt) ** 2
    r2n = r2**steps
    denom = gamma * dt * (2.0 - gamma * dt)  # 1 - r^2, written to stay exact for small gamma dt
    safe = np.where(denom != 0, denom, 1.0)
    growth = np.where(
        denom != 0, -np.expm1(steps * np.log(np.where(r2 > 0, r2, 1.0))) / safe, steps
    )
    growth = np.where((r2 == 0) & (denom != 0), 1.0 / safe, growth)
    out = 2.0 * intensity * dt * growth
    if s0 is not None:
        out = out + np.asarray(s0, dtype=float) * r2n
    return out


def psd_consistency(ratios, *, bands: int = 8, alpha: float = 1e-3, pooled: bool = True) -> Result:
    """Test periodogram/theory ratios of independent complex modes against sampling error.

    Under the hypothesis that every mode is a complex Gaussian with the
    predicted variance, each ratio ``I_k / E[I_k]`` is Exp(1) distributed, so
    the mean of the ``M`` ratios in a band is Gamma(M, 1/M) exactly.  The
    modes (last axis, ordered by |k|; leading axes are replicas) are split into
    ``bands`` contiguous bands; each band gets a two-sided p-value, and so
    does the pooled mean of all ratios (``pooled=True``: the most powerful of
    these tests against a bias common to all modes, e.g. a wrong amplitude).
    The test fails when any p < alpha / (number of tests) (Bonferroni), so the
    false-alarm rate of the whole test is at most ``alpha``.

    Parameters
    ----------
    ratios : array_like
        Shape ``(..., modes)``; only complex (not self-conjugate) modes whose
        partners are not also included.
    bands : int
        Number of bands.
    alpha : float
        Family-wise false-alarm rate.
    pooled : bool
        Add the pooled test of all modes (default).

    Returns
    -------
    Result
        ``passed``, ``band_mean`` (per band), ``band_dof`` (ratios per band),
        ``p_values`` (per band), ``p_min``, ``threshold`` (alpha / tests),
        ``rel_sigma`` (1/sqrt(dof) per band), ``pooled_mean``, ``pooled_p``.
    """
    from scipy import stats

    r = np.asarray(ratios, dtype=float)
    r = r.reshape(-1, r.shape[-1])
    chunks = np.array_split(np.arange(r.shape[-1]), bands)
    means, dofs, pvals = [], [], []
    for idx in chunks:
        m = r[:, idx].size
        mean = float(r[:, idx].mean())
        cdf = stats.gamma.cdf(mean, a=m, scale=1.0 / m)
        means.append(mean)
        dofs.append(m)
        pvals.append(float(2 * min(cdf, 1 - cdf)))
    n_tests = bands + (1 if pooled else 0)
    threshold = alpha / n_tests
    m_all = r.size
    pooled_mean = float(r.mean())
    c_all = stats.gamma.cdf(pooled_mean, a=m_all, scale=1.0 / m_all)
    pooled_p = float(2 * min(c_all, 1 - c_all))
    p_all = min(pvals) if not pooled else min(min(pvals), pooled_p)
    return Result(
        passed=bool(p_all >= threshold),
        pooled_mean=pooled_mean,
        pooled_p=pooled_p if pooled else float("nan"),
        band_mean=np.array(means),
        band_dof=np.array(dofs),
        p_values=np.array(pvals),
        p_min=float(p_all),
        threshold=threshold,
        rel_sigma=1.0 / np.sqrt(dofs),
        method="gamma_band_test",
        message=f"min p = {p_all:.3g} vs threshold {threshold:.3g}",
    )


def crossover_wavenumbers(*, d0, dx_noise, dz, mu, l) -> tuple[float, float]:
    """Crossover wavenumbers (1/m) bounding the k^-2 range of the stationary PSD.

    Returns
    -------
    k1, k2 : float
        ``k1 = sqrt(mu/D0)`` (low-k plateau Dz/mu ends; 0 when mu = 0, inf
        when D0 = 0) and ``k2 = sqrt(Dz/(Dx l^2))`` (high-k plateau
        Dx l^2/D0 begins; inf when Dx = 0).  The k^-2 range exists only for
        ``k1 << k2``.
    """
    k1 = math.sqrt(mu / d0) if d0 > 0 else math.inf
    k2 = math.sqrt(dz / (dx_noise * l**2)) if dx_noise > 0 else math.inf
    return k1, k2


def relaxation_time(k, *, d0, mu, lattice_dx=None):
    """Relaxation time (s) of the mode amplitude, 1/(mu + D0 k^2) (inf if zero rate).

    The PSD relaxes twice as fast (``exp(-2 gamma t)``).
    """
    gamma = mu + d0 * _k2(k, lattice_dx)
    with np.errstate(divide="ignore"):
        return np.where(gamma > 0, 1.0 / np.where(gamma > 0, gamma, 1.0), math.inf)


# ------------------------------------------------------------------ estimators


def _check_map(h, dim):
    h = np.asarray(h, dtype=float)
    if h.ndim < dim or any(s < 4 for s in h.shape[-dim:]):
        raise ParameterError(
            "h", f"an array with >= 4 points along each of its last {dim} axes", h.shape
        )
    if not np.all(np.isfinite(h)):
        raise ParameterError("h", "finite heights", "non-finite values")
    return h


def periodogram(h, dx: float, dim: int):
    """Periodogram on the real-FFT grid, S = dx^dim / n^dim |hat h|^2 (m^(dim+2)).

    Leading axes of ``h`` (beyond the last ``dim``) are kept (replicas).
    """
    h = _check_map(h, dim)
    if dim == 1:
        hk = np.fft.rfft(h, axis=-1)
    else:
        hk = np.fft.rfft2(h, axes=(-2, -1))
    npts = math.prod(h.shape[-dim:])
    return (dx**dim / npts) * (hk.real**2 + hk.imag**2)


def psd_1d(h, dx: float, *, average: bool = True):
    """PSD of 1D profiles (last axis), one-sided in k with two-sided normalisation.

    Parameters
    ----------
    h : array_like
        Heights (m), shape ``(..., n)``; leading axes are replicas.
    dx : float
        Sampling interval (m).
    average : bool
        Average over the leading axes.

    Returns
    -------
    k : ndarray
        Positive wavenumbers 2 pi m / L, m = 1 ... n//2 (1/m).
    S : ndarray
        PSD (m^3) at ``k``, normalised so ``<h^2> = (1/L) sum_{all k} S``.
    """
    s = periodogram(h, dx, 1)
    n = np.shape(h)[-1]
    k = 2 * np.pi * np.fft.rfftfreq(n, dx)[1:]
    s = s[..., 1:]
    if average and s.ndim > 1:
        s = s.reshape(-1, s.shape[-1]).mean(axis=0)
    return k, s


def radial_bins(n: int, dx: float):
    """Radial bins of the 2D real-FFT grid: (|k| grid, bin index grid, weights, nbins).

    Bins have width 2 pi / L, centred on multiples of it, from 2 pi / L up to
    the Nyquist wavenumber pi/dx; modes beyond (the corners) get index -1.
    Weights count each rfft column once for its mirrored partner (columns 1 ...
    n/2-1 stand for two modes), so averages equal full-plane averages.
    """
    kx = 2 * np.pi * np.fft.fftfreq(n, dx)[:, None]
    ky = 2 * np.pi * np.fft.rfftfreq(n, dx)[None, :]
    kmag = np.hypot(kx, ky)
    dk = 2 * np.pi / (n * dx)
    idx = np.rint(kmag / dk).astype(np.int64) - 1
    nbins = n // 2
    idx[(idx < 0) | (idx >= nbins)] = -1
    w = np.full(kmag.shape, 2.0)
    w[:, 0] = 1.0
    w[:, -1] = 1.0
    return kmag, idx, w, nbins


def radial_average(values, n: int, dx: float):
    """Weighted radial average of a quantity on the 2D real-FFT grid.

    Parameters
    ----------
    values : ndarray
        Shape ``(n, n//2 + 1)`` (e.g. a periodogram or the theory on the grid).
    n, dx : int, float
        Grid points per side and spacing (m).

    Returns
    -------
    k : ndarray
        Mean |k| of the modes in each bin (1/m).
    avg : ndarray
        Bin averages.
    counts : ndarray
        Number of (full-plane) modes per bin.
    """
    kmag, idx, w, nbins = radial_bins(n, dx)
    sel = idx >= 0
    ii = idx[sel]
    ww = w[sel]
    counts = np.bincount(ii, weights=ww, minlength=nbins)
    kmean = np.bincount(ii, weights=ww * kmag[sel], minlength=nbins) / counts
    avg = np.bincount(ii, weights=ww * np.asarray(values)[sel], minlength=nbins) / counts
    return kmean, avg, counts


def psd_2d_radial(h, dx: float):
    """Radially averaged PSD of 2D surfaces (replicas on leading axes are averaged).

    Parameters
    ----------
    h : array_like
        Heights (m), shape ``(..., n, n)``.
    dx : float
        Pixel size (m).

    Returns
    -------
    k : ndarray
        Mean |k| per annulus of width 2 pi / L (1/m).
    S : ndarray
        Radially averaged S(|k|) (m^4), normalisation ``<h^2> = (1/A) sum S``.
    """
    s = periodogram(h, dx, 2)
    s = s.reshape(-1, *s.shape[-2:]).mean(axis=0)
    n = np.shape(h)[-1]
    if np.shape(h)[-2] != n:
        raise ParameterError("h", "a square height map", np.shape(h)[-2:])
    k, avg, _ = radial_average(s, n, dx)
    return k, avg


def psd_line_scans(h, dx: float, axis: int = -1):
    """Average 1D PSD of the line scans of 2D surfaces along ``axis``.

    A line scan sees ``S_line(kx) = (1/L) sum_ky S_2D(kx, ky)`` (m^3): between
    the plateaus of Eq. 23 it falls as k^-1, not k^-2 (PHYSICS.md section 4).
    """
    h = np.moveaxis(_check_map(h, 2), axis, -1)
    return psd_1d(h.reshape(-1, h.shape[-1]), dx)


def line_scan_psd_theory(s_grid, n: int, dx: float):
    """Return the expected line-scan PSD (m^3) of a 2D spectrum given on the real-FFT grid.

    ``s_grid`` has shape ``(n, n//2 + 1)`` (``numpy.fft.rfft2`` layout); the
    scans run along the last axis, so ``S_line(k) = (1/L) sum_{k'} S(k', k)``.
    Returns (k, S_line) at k = 2 pi m / L, m = 1 ... n//2.
    """
    s_line = np.asarray(s_grid).sum(axis=-2) / (n * dx)
    k = 2 * np.pi * np.fft.rfftfreq(n, dx)[1:]
    return k, s_line[..., 1:]


def mean_square_from_psd(k, s, length: float, s0: float = 0.0) -> float:
    """Mean square height (m^2) of a 1D profile from its one-sided PSD.

    Inverts the normalisation of :func:`psd_1d`: ``(S(0) + 2 sum S(k) - S(k_N)) / L``
    for an even number of points (the Nyquist mode appears once).
    """
    s = np.asarray(s, dtype=float)
    return float((s0 + 2.0 * s.sum() - s[-1]) / length)


def log_bin(k, s, per_decade: int = 10):
    """Average a PSD in logarithmically spaced k bins (for plotting and fits).

    Returns (geometric-mean k of each non-empty bin, mean S in it, points per bin).
    """
    k = np.asarray(k, dtype=float)
    s = np.asarray(s, dtype=float)
    lo, hi = np.floor(np.log10(k.min()) * per_decade), np.ceil(np.log10(k.max()) * per_decade)
    edges = 10 ** (np.arange(lo, hi + 2) / per_decade)
    idx = np.digitize(k, edges) - 1
    counts = np.bincount(idx, minlength=len(edges))
    keep = counts > 0
    kb = np.exp(np.bincount(idx, weights=np.log(k), minlength=len(edges))[keep] / counts[keep])
    sb = np.bincount(idx, weights=s, minlength=len(edges))[keep] / counts[keep]
    return kb, sb, counts[keep]


# ------------------------------------------------------------------ roughness


def roughness(h, dx: float, dim: int | None = None) -> Result:
    """Roughness metrics of a periodic profile or surface.

    Parameters
    ----------
    h : array_like
        Heights (m), shape ``(n,)`` or ``(n, n)`` (``dim`` defaults to ``h.ndim``).
    dx : float
        Pixel size (m).

    Returns
    -------
    Result
        ``rq`` (rms height about the mean, m), ``ra`` (mean absolute deviation, m),
        ``rms_slope`` (rms of the x-derivative, forward differences, 1), and
        ``rms_gradient`` (rms of |grad h|, equal to ``rms_slope`` in 1D), plus
        ``mean`` (m).
    """
    h = np.asarray(h, dtype=float)
    dim = h.ndim if dim is None else dim
    h = _check_map(h, dim)
    dev = h - h.mean()
    slope_x = (np.roll(h, -1, axis=-1) - h) / dx
    grad2 = slope_x**2
    if dim == 2:
        grad2 = grad2 + ((np.roll(h, -1, axis=-2) - h) / dx) ** 2
    res = Result(
        rq=float(np.sqrt(np.mean(dev**2))),
        ra=float(np.mean(np.abs(dev))),
        rms_slope=float(np.sqrt(np.mean(slope_x**2))),
        rms_gradient=float(np.sqrt(np.mean(grad2))),
        mean=float(h.mean()),
        method="roughness",
        units={"rq": "m", "ra": "m", "rms_slope": "1", "rms_gradient": "1", "mean": "m"},
    )
    res.message = "roughness metrics"
    return res


def hurst_fit(k, s, *, kmin: float, kmax: float, dim: int = 1) -> Result:
    """Fit S ~ k^-alpha over ``kmin <= k <= kmax`` and convert alpha to a Hurst exponent.

    For a self-affine surface alpha = 1 + 2H for a 1D profile (or line scan)
    and alpha = 2 + 2H for a radially averaged 2D PSD.  The Eq. 23 k^-2 range
    therefore gives H = 1/2 in 1D (Brownian profile) and H = 0 for a 2D
    surface (its line scans, k^-1, also give H = 0).

    Parameters
    ----------
    k, s : array_like
        Wavenumbers (1/m) and PSD values.
    kmin, kmax : float
        Fit range (1/m); needs at least 3 points.
    dim : {1, 2}
        1 for profiles / line scans, 2 for radially averaged 2D PSDs.

    Returns
    -------
    Result
        ``alpha`` (decay exponent), ``alpha_err`` (standard error from the
        log-log least squares), ``hurst`` and ``points``.
    """
    k = np.asarray(k, dtype=float)
    s = np.asarray(s, dtype=float)
    sel = (k >= kmin) & (k <= kmax) & (s > 0) & np.isfinite(s)
    if sel.sum() < 3:
        raise ParameterError("kmin/kmax", "a range holding >= 3 positive PSD points", (kmin, kmax))
    x, y = np.log(k[sel]), np.log(s[sel])
    A = np.vstack([x, np.ones_like(x)]).T
    coef, *_ = np.linalg.lstsq(A, y, rcond=None)
    resid = y - A @ coef
    dof = max(len(x) - 2, 1)
    cov = np.linalg.inv(A.T @ A) * (resid @ resid) / dof
    alpha = -coef[0]
    return Result(
        alpha=float(alpha),
        alpha_err=float(np.sqrt(cov[0, 0])),
        hurst=float((alpha - dim) / 2.0),
        points=int(sel.sum()),
        method="hurst_fit",
        message=f"S ~ k^-{alpha:.3f} over [{kmin:.3g}, {kmax:.3g}] 1/m",
        units={"alpha": "1", "alpha_err": "1", "hurst": "1"},
    )
