"""Time-series and profile statistics used by the MCA analyses (pure numpy).

* :func:`mser_truncation` -- steady-state detection by the Marginal Standard
  Error Rule (White 1997; MSER-5 of Franklin & White 2008);
* :func:`block_standard_error` -- error bar of a correlated series' mean by
  Flyvbjerg-Petersen blocking;
* :func:`isotonic_fit` and :func:`crossing_heights` -- the monotone fit of a
  noisy profile and the heights where it crosses given levels (used for the
  10 %-90 % widths of the velocity and composition profiles);
* :func:`msd_fft` -- all-origins mean-squared displacement in O(T log T).

References
----------
White, K. P. (1997). An effective truncation heuristic for bias reduction in
simulation output. Simulation 69(6), 323-334.
https://doi.org/10.1177/003754979706900601
Flyvbjerg, H. & Petersen, H. G. (1989). Error estimates on averages of
correlated data. J. Chem. Phys. 91, 461. https://doi.org/10.1063/1.457480
Calandrini, V. et al. (2011). nMoldyn: the MSD via FFT. Collection SFN 12,
201-232. https://doi.org/10.1051/sfn/201112010
"""

from __future__ import annotations

import math

import numpy as np

__all__ = [
    "mser_truncation",
    "block_standard_error",
    "isotonic_fit",
    "crossing_heights",
    "msd_fft",
    "linear_fit",
]


def mser_truncation(y, batch: int = 5, max_fraction: float = 0.5) -> tuple[int, bool]:
    """Return number of initial samples to discard so that the rest is steady (MSER-m).

    The truncation point ``d`` minimises the marginal standard error
    ``var(y[d:]) / (n - d)`` over batch means of ``batch`` samples, searched in
    the first ``max_fraction`` of the series (a minimum in the second half means
    the run is too short to call it steady).

    Parameters
    ----------
    y : array_like
        The series (any unit).
    batch : int
        Batch size m of MSER-m.
    max_fraction : float
        Largest truncation considered, as a fraction of the series.

    Returns
    -------
    d : int
        Samples to discard (a multiple of ``batch``).
    steady : bool
        False when the minimum sits at the search limit, i.e. no steady
        state was detected within the series.
    """
    y = np.asarray(y, dtype=float)
    nb = y.size // batch
    if nb < 4:
        return 0, False
    z = y[: nb * batch].reshape(nb, batch).mean(axis=1)
    # suffix sums give mean and variance of z[j:] for every j in O(n)
    s1 = np.cumsum(z[::-1])[::-1]
    s2 = np.cumsum((z * z)[::-1])[::-1]
    m = nb - np.arange(nb)
    var = s2 / m - (s1 / m) ** 2
    jmax = max(1, int(max_fraction * nb))
    crit = var[:jmax] / m[:jmax]
    j = int(np.argmin(crit))
    steady = j < jmax - 1
    return j * batch, steady


def block_standard_error(y, min_blocks: int = 8) -> tuple[float, bool]:
    """Estimate the standard error of the mean of a correlated series by blocking.

    Consecutive pairs are averaged repeatedly; the naive standard error of the
    block means rises with block size until blocks are longer than the
    correlation time, then stays flat within its own uncertainty
    ``SE / sqrt(2 (n_blocks - 1))``.  The first level whose successor is
    within that uncertainty is taken (Flyvbjerg & Petersen 1989).

    Parameters
    ----------
    y : array_like
        The series.
    min_blocks : int
        Levels with fewer blocks are not used.

    Returns
    -------
    se : float
        Standard error of ``mean(y)`` (same unit as ``y``).
    converged : bool
        False when no plateau was found (then ``se`` is the largest estimate,
        a lower bound).
    """
    x = np.asarray(y, dtype=float)
    ses, errs = [], []
    while x.size >= min_blocks:
        n = x.size
        se = math.sqrt(np.var(x, ddof=1) / n) if n > 1 else 0.0
        ses.append(se)
        errs.append(se / math.sqrt(2.0 * (n - 1)))
        x = x[: (n // 2) * 2].reshape(-1, 2).mean(axis=1)
    if not ses:
        return float("nan"), False
    for k in range(len(ses) - 1):
        if ses[k + 1] - ses[k] <= errs[k]:
            # plateau from level k on; the larger of the two is the safer bar
            return float(max(ses[k], ses[k + 1])), True
    return float(max(ses)), False


def isotonic_fit(y, w=None, increasing: bool = True) -> np.ndarray:
    """Weighted least-squares monotone fit (pool-adjacent-violators).

    Parameters
    ----------
    y : array_like
        Values along an ordered axis.
    w : array_like, optional
        Non-negative weights (e.g. counts per bin); default all ones.
    increasing : bool
        Fit a non-decreasing (True) or non-increasing (False) sequence.

    Returns
    -------
    ndarray
        The monotone sequence closest to ``y`` in weighted least squares.
    """
    y = np.asarray(y, dtype=float)
    w = np.ones_like(y) if w is None else np.asarray(w, dtype=float)
    if not increasing:
        return -isotonic_fit(-y, w, True)
    vals: list[float] = []
    wts: list[float] = []
    lens: list[int] = []
    for yi, wi in zip(y, w):
        vals.append(yi)
        wts.append(wi)
        lens.append(1)
        while len(vals) > 1 and vals[-2] > vals[-1]:
            wsum = wts[-2] + wts[-1]
            v = (
                (vals[-2] * wts[-2] + vals[-1] * wts[-1]) / wsum
                if wsum > 0
                else 0.5 * (vals[-2] + vals[-1])
            )
            ln = lens[-2] + lens[-1]
            del vals[-1], wts[-1], lens[-1]
            vals[-1], wts[-1], lens[-1] = v, wsum, ln
    return np.repeat(vals, lens)


def crossing_heights(z, f, levels) -> np.ndarray:
    """Heights where a non-decreasing profile ``f(z)`` first reaches each level.

    Linear interpolation between the two samples around the crossing; NaN
    when the profile never reaches the level (or starts above it).

    Parameters
    ----------
    z : array_like
        Increasing sample positions (m).
    f : array_like
        Non-decreasing values at ``z`` (e.g. from :func:`isotonic_fit`).
    levels : array_like
        Levels to find.

    Returns
    -------
    ndarray
        One height per level (m).
    """
    z = np.asarray(z, dtype=float)
    f = np.asarray(f, dtype=float)
    out = []
    for lev in np.atleast_1d(levels):
        idx = np.nonzero(f >= lev)[0]
        if idx.size == 0 or idx[0] == 0:
            out.append(np.nan)
            continue
        i = idx[0]
        f0, f1 = f[i - 1], f[i]
        t = 0.5 if f1 == f0 else (lev - f0) / (f1 - f0)
        out.append(z[i - 1] + t * (z[i] - z[i - 1]))
    return np.asarray(out)


def msd_fft(x) -> np.ndarray:
    """All-time-origins mean-squared displacement of each trajectory.

    Parameters
    ----------
    x : array_like, shape (T, N) or (T, N, k)
        Unwrapped positions of N particles at T equally spaced times
        (k spatial components are summed).

    Returns
    -------
    ndarray, shape (T,)
        ``msd[l] = < |x(t+l) - x(t)|^2 >`` averaged over all origins t and
        particles; ``msd[0] == 0``.
    """
    x = np.asarray(x, dtype=float)
    if x.ndim == 2:
        x = x[:, :, None]
    T = x.shape[0]
    # S2: autocorrelation via FFT (zero-padded to avoid circular wrap)
    nfft = 1 << (2 * T - 1).bit_length()
    fx = np.fft.rfft(x, n=nfft, axis=0)
    ac = np.fft.irfft(fx * np.conj(fx), n=nfft, axis=0)[:T]
    ac = ac / (T - np.arange(T))[:, None, None]
    s2 = ac.sum(axis=2)  # (T, N)
    # S1: recursion over the squared norms
    d = (x**2).sum(axis=2)  # (T, N)
    dpad = np.vstack([d, np.zeros((1, d.shape[1]))])
    q = 2.0 * d.sum(axis=0)
    s1 = np.zeros_like(s2)
    for m in range(T):
        q = q - dpad[m - 1] - dpad[T - m]
        s1[m] = q / (T - m)
    return (s1 - 2.0 * s2).mean(axis=1)


def linear_fit(t, y) -> tuple[float, float, float]:
    """Least-squares line ``y = a t + b``.

    Returns
    -------
    slope, intercept, slope_stderr : float
        The fit and the ordinary standard error of the slope (which
        underestimates the error for correlated points such as MSD lags).
    """
    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    if t.size < 2:
        return float("nan"), float("nan"), float("nan")
    A = np.vstack([t, np.ones_like(t)]).T
    coef, *_ = np.linalg.lstsq(A, y, rcond=None)
    if t.size > 2:
        resid = y - A @ coef
        s2 = float(resid @ resid) / (t.size - 2)
        se = math.sqrt(s2 / float(((t - t.mean()) ** 2).sum()))
    else:
        se = float("nan")
    return float(coef[0]), float(coef[1]), se
