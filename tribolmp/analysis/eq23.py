"""Eq. 23 coefficients measured from a surface profile h(x, t) (PHYSICS.md section 8).

Every Fourier mode of the 1D profile of Eq. 23 is an Ornstein-Uhlenbeck
process with relaxation rate and stationary PSD

    gamma(k) = mu + D0 k^2,      S(k) gamma(k) = Dz + Dx l^2 k^2

(``S`` in the convention of :mod:`tribolmp.models.topography.spectra`:
``S = dx/n |hat h|^2``, m^3).  :func:`fit_eq23` measures, per mode
``0 < k < k_Nyquist``, the autocovariance ``C_k(j)`` of ``hat h_k(t)`` at
lags ``j`` (frames), and from it

* ``gamma_k = ln(C(j1)/C(j2)) / ((j2 - j1) dt)``: a two-point log-slope of the
  autocovariance.  The first lag ``j1`` is 1, not 0, because measurement
  noise that is white in time (the column-mass shot noise of an MCA profile,
  vibrations) adds only to ``C(0)``; ``j2`` is the first lag where
  ``C(j)/C(j1)`` has fallen to ``1/e`` (about one relaxation time, close to
  the variance-optimal separation), at least ``j1 + 1``;
* ``S_k = C(j1) exp(gamma_k j1 dt)``: the autocovariance extrapolated to lag 0,
  i.e. the stationary variance of the process without the white noise;

with errors from a delete-one-block jackknife over ``n_blocks`` consecutive
time blocks (correlated samples are handled because whole blocks, each
several relaxation times long, are left out).  Then weighted least squares
over the usable modes gives ``mu, D0`` (intercept, slope of gamma against
k^2) and ``Dz, Dx l^2`` (of S gamma against k^2); parameter errors are the
WLS covariance scaled by the Birge ratio ``max(1, sqrt(chi2/dof))`` (errors
never shrink below the propagated ones; a model misfit widens them).

A mode is *usable* when it is resolved in time (``gamma dt <= max_gamma_dt``),
the run covers at least ``min_relaxations`` of its relaxation times (at the
2-sigma lower bound of gamma: a short run measures gamma poorly), its
autocovariance is positive at both lags in every jackknife sample, and its
relative jackknife error is below 1.  A coefficient is *valid* when at least
``min_modes`` modes are usable, the profile passed the stationarity test (the
mean power of each mode in the first and second half of the run agree, chi^2
over modes at significance ``stationarity_alpha``), and

* for the intercepts ``mu`` and ``Dz``: the slowest mode (k = 2 pi / L) is
  usable (the intercept is where the slowest modes are);
* for the slopes ``D0`` and ``Dx l^2``: the usable modes span at least a
  factor 2 in k.

An invalid coefficient is reported as ``None`` (the raw estimate is kept in
``raw`` for diagnosis only).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..errors import DataFileError, ParameterError

__all__ = [
    "fit_eq23",
    "mode_statistics",
    "write_profile",
    "read_profile",
    "EQ23_UNITS",
    "COEFFICIENTS",
]

#: The C1 coefficient names, in order.
COEFFICIENTS = ("mu_per_s", "d0_m2_s", "dz", "dx_l2")

#: Units of the fitted fields (1D profile).
EQ23_UNITS = {
    "mu_per_s": "1/s", "mu_per_s_err": "1/s",
    "d0_m2_s": "m^2/s", "d0_m2_s_err": "m^2/s",
    "dz": "m^3/s", "dz_err": "m^3/s",
    "dx_l2": "m^5/s", "dx_l2_err": "m^5/s",
    "k_per_m": "1/m", "gamma_per_s": "1/s", "gamma_err_per_s": "1/s",
    "psd_m3": "m^3", "psd_err_m3": "m^3", "s_gamma_m3_s": "m^3/s", "s_gamma_err_m3_s": "m^3/s",
    "dt_s": "s", "duration_s": "s", "length_m": "m",
}


# ------------------------------------------------------------------ profile.npz


def write_profile(path, x, t, h, **extra) -> Path:
    """Write ``profile.npz`` (contract C1): ``x`` [m] (nx,), ``t`` [s] (nt,), ``h`` [m] (nt, nx).

    Extra arrays or scalars (e.g. ``counts``) are stored alongside.
    The file is written to a temporary name and renamed, so a reader never
    sees a partial file.
    """
    x, t, h = _check_profile(x, t, h, source=str(path))
    path = Path(path)
    tmp = path.with_name(path.name + ".tmp.npz")
    np.savez(tmp, x=x, t=t, h=h, **extra)
    tmp.replace(path)
    return path


def read_profile(path) -> dict[str, np.ndarray]:
    """Read and check a ``profile.npz``.

    Returns a dict with ``x``, ``t``, ``h`` (SI) and any extras.
    """
    path = Path(path)
    if not path.exists():
        raise DataFileError(f"{path}: expected a profile.npz, got no such file")
    try:
        with np.load(path, allow_pickle=False) as z:
            data = {k: z[k] for k in z.files}
    except (ValueError, OSError) as exc:
        raise DataFileError(
            f"{path}: expected a numpy .npz archive, got "
            f"unreadable data ({' '.join(str(exc).split())[:80]})"
        ) from None
    for key in ("x", "t", "h"):
        if key not in data:
            raise DataFileError(
                f"{path}: {key}: expected arrays x [m], t [s], h [m], got keys {sorted(data)}"
            )
    data["x"], data["t"], data["h"] = _check_profile(
        data["x"], data["t"], data["h"], source=str(path)
    )
    return data


def _check_profile(x, t, h, source: str = "profile"):
    x = np.asarray(x, dtype=float)
    t = np.asarray(t, dtype=float)
    h = np.asarray(h, dtype=float)
    if x.ndim != 1 or x.size < 4:
        raise DataFileError(
            f"{source}: x: expected a 1D array of >= 4 positions (m), got shape {x.shape}"
        )
    if t.ndim != 1 or t.size < 2:
        raise DataFileError(
            f"{source}: t: expected a 1D array of >= 2 times (s), got shape {t.shape}"
        )
    if h.shape != (t.size, x.size):
        raise DataFileError(
            f"{source}: h: expected shape (nt, nx) = ({t.size}, {x.size}), got {h.shape}"
        )
    for name, a in (("x", x), ("t", t), ("h", h)):
        if not np.all(np.isfinite(a)):
            raise DataFileError(f"{source}: {name}: expected finite numbers, got NaN/inf")
    for name, a in (("x", x), ("t", t)):
        d = np.diff(a)
        if not np.all(d > 0) or not np.allclose(d, d.mean(), rtol=1e-6, atol=0):
            raise DataFileError(
                f"{source}: {name}: expected uniformly spaced increasing values, got spacings "
                f"{d.min():.6g} ... {d.max():.6g}"
            )
    return x, t, h


# ------------------------------------------------------------------ per-mode statistics


def _lag_sums(z: np.ndarray, lags, n_blocks: int):
    """Block sums of Re(z[n+j] conj z[n]) by origin block, and their counts.

    Returns arrays of shape (n_blocks, n_lags, n_modes) (sums) and (n_blocks, n_lags) (counts).
    ``lags`` may be an int array of shape (n_lags, n_modes) (a lag per mode).
    """
    nt, nm = z.shape
    lags = np.asarray(lags)
    nl = lags.shape[0]
    block = np.minimum((np.arange(nt) * n_blocks) // nt, n_blocks - 1)
    sums = np.zeros((n_blocks, nl, nm))
    counts = np.zeros((n_blocks, nl, nm))
    cols = np.arange(nm)
    for a in range(nl):
        for j in np.unique(lags[a]):
            sel = cols[lags[a] == j]
            prod = (z[j:, sel] * np.conj(z[: nt - j, sel])).real
            bl = block[: nt - j]
            np.add.at(sums[:, a, :], (bl[:, None], sel[None, :]), prod)
            counts[:, a, sel] += np.bincount(bl, minlength=n_blocks)[:, None]
    return sums, counts


def _autocov_fft(z: np.ndarray, max_lag: int) -> np.ndarray:
    """Autocovariance Re <z(t+j) z*(t)> for j = 0..max_lag, per column (unbiased normalisation)."""
    nt = z.shape[0]
    nfft = 1 << (2 * nt - 1).bit_length()
    f = np.fft.fft(z, n=nfft, axis=0)
    ac = np.fft.ifft(f * np.conj(f), axis=0)[: max_lag + 1].real
    return ac / (nt - np.arange(max_lag + 1))[:, None]


def mode_statistics(
    t, hk, *, dx: float, n_points: int, first_lag: int = 1, n_blocks: int = 10
) -> dict:
    """gamma(k), S(k) and S gamma per mode, with jackknife errors.

    Parameters
    ----------
    t : ndarray, shape (nt,)
        Uniform times (s).
    hk : ndarray, shape (nt, n_modes)
        Complex Fourier amplitudes ``rfft(h)`` of the modes to analyse.
    dx : float
        Profile spacing (m).
    n_points : int
        Points of the profile (the DFT length), for the PSD normalisation.
    first_lag : int
        ``j1``: first autocovariance lag used (1 discards white measurement noise).
    n_blocks : int
        Jackknife blocks.

    Returns
    -------
    dict of ndarray (per mode)
        ``gamma``, ``gamma_err`` (1/s), ``psd``, ``psd_err`` (m^3), ``s_gamma``,
        ``s_gamma_err`` (m^3/s), ``lag2`` (frames), ``ok`` (estimable in every
        jackknife sample), ``power_halves`` (2, n_modes) mean |hat h|^2 per half
        (m^3) and ``power_halves_rel_sd`` (2, n_modes) their relative standard
        deviations expected for a stationary OU process.
    """
    nt, nm = hk.shape
    dt = float(t[1] - t[0])
    norm = dx / n_points
    z = hk.astype(complex)
    j1 = int(first_lag)
    max_lag = max(j1 + 1, nt // 3)
    ac = _autocov_fft(z, max_lag) * norm  # (max_lag+1, nm)
    # j2: first lag where C(j)/C(j1) <= 1/e, at least j1 + 1
    ratio = ac[j1 + 1:] / np.where(ac[j1] > 0, ac[j1], np.nan)
    below = ratio <= math.exp(-1.0)
    j2 = np.where(below.any(axis=0), np.argmax(below, axis=0) + j1 + 1, max_lag)
    lags = np.vstack([np.full(nm, 0), np.full(nm, j1), j2])
    sums, counts = _lag_sums(z, lags, n_blocks)
    sums *= norm
    tot_s, tot_c = sums.sum(axis=0), counts.sum(axis=0)

    def estimate(s, c):
        with np.errstate(divide="ignore", invalid="ignore"):
            C = s / c  # (3, nm): lags 0, j1, j2
            g = np.log(C[1] / C[2]) / ((j2 - j1) * dt)
            S = C[1] * np.exp(g * j1 * dt)
        return g, S, S * g, (C[1] > 0) & (C[2] > 0)

    g, S, Sg, ok = estimate(tot_s, tot_c)
    jk = [estimate(tot_s - sums[b], tot_c - counts[b]) for b in range(n_blocks)]
    ok = ok & np.all([o for *_, o in jk], axis=0)

    def jk_err(idx):
        vals = np.array([r[idx] for r in jk])
        with np.errstate(invalid="ignore"):
            return np.sqrt(
                (n_blocks - 1) / n_blocks * ((vals - vals.mean(axis=0)) ** 2).sum(axis=0)
            )

    # stationarity: mean |hat h|^2 of each half, and its relative sd for a
    # stationary OU process sampled at dt: var(mean |z|^2) = (C0^2 + 2
    # sum_{j>=1} |C(j)|^2) / N, with C(j) = S a^j (j >= 1)
    half = nt // 2
    p = (np.abs(z) ** 2) * norm
    powers = np.vstack([p[:half].mean(axis=0), p[half:].mean(axis=0)])
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        a = np.exp(-np.clip(g, 0, None) * dt)
        c0 = ac[0]
        tail = 2 * np.where(np.isfinite(S), S, 0.0) ** 2 * a**2 / np.maximum(1 - a**2, 1e-300)
        rel = np.vstack([np.sqrt((c0**2 + tail) / n) / c0 for n in (half, nt - half)])
    return {
        "gamma": g,
        "gamma_err": jk_err(0),
        "psd": S,
        "psd_err": jk_err(1),
        "s_gamma": Sg,
        "s_gamma_err": jk_err(2),
        "lag2": j2,
        "ok": ok,
        "power_halves": powers,
        "power_halves_rel_sd": rel,
    }


# ------------------------------------------------------------------ the fit


def _wls(k2, y, err):
    """Weighted least squares y = a + b k2; returns (a, b, cov, chi2, dof)."""
    w = 1.0 / err**2
    A = np.vstack([np.ones_like(k2), k2]).T
    # scale k2 for conditioning
    s = k2.max()
    As = A / np.array([1.0, s])
    M = As.T @ (As * w[:, None])
    cov_s = np.linalg.inv(M)
    coef_s = cov_s @ (As.T @ (w * y))
    resid = y - As @ coef_s
    chi2 = float((w * resid**2).sum())
    scale = np.array([1.0, 1.0 / s])
    return (
        float(coef_s[0] * scale[0]),
        float(coef_s[1] * scale[1]),
        cov_s * np.outer(scale, scale),
        chi2,
        k2.size - 2,
    )


def _smooth_errors(k, err):
    """Per-mode errors smoothed as a power law in k (least squares in log-log).

    A mode's jackknife error is itself a noisy estimate correlated with the
    mode's value; weighting a fit by it pulls the fit toward the modes whose
    errors came out small.  A two-parameter power law through all the modes'
    errors keeps their trend and averages out that noise.
    """
    if k.size < 3:
        return err
    c = np.polyfit(np.log(k), np.log(err), 1)
    return np.exp(np.polyval(c, np.log(k)))


def fit_eq23(x, t, h, *, start_s: float | None = None, first_lag: int = 1, n_blocks: int = 20,
             min_relaxations: float = 10.0, max_gamma_dt: float = 0.6, min_modes: int = 3,
             stationarity_alpha: float = 1e-3, max_modes: int | None = None) -> dict:
    """Fit gamma = mu + D0 k^2 and S gamma = Dz + Dx l^2 k^2 on a profile h(x, t).

    Parameters
    ----------
    x : array_like, shape (nx,)
        Uniform positions along the profile (m); the profile is periodic with
        length ``nx * dx``.
    t : array_like, shape (nt,)
        Uniform times (s).
    h : array_like, shape (nt, nx)
        Heights (m).
    start_s : float, optional
        Analyse only frames with ``t >= start_s`` (e.g. the steady start).
    first_lag : int
        First autocovariance lag (frames); 1 removes white measurement noise.
    n_blocks : int
        Jackknife blocks (>= 4).
    min_relaxations : float
        A mode is usable only if the analysed duration is at least this many
        of its relaxation times 1/gamma, at the 2-sigma lower bound of gamma.
    max_gamma_dt : float
        A mode is usable only if gamma dt is at most this (resolved in time).
    min_modes : int
        Usable modes needed for any coefficient to be valid (>= 3: two
        parameters and one degree of freedom).
    stationarity_alpha : float
        Significance level of the stationarity test.
    max_modes : int, optional
        Analyse only the lowest ``max_modes`` modes.

    Returns
    -------
    dict
        C1 fields ``mu_per_s``, ``d0_m2_s``, ``dz``, ``dx_l2`` (None when not
        valid), their ``*_err``, ``valid`` (per coefficient), ``reasons`` (per
        invalid coefficient), ``modes_used`` (indices m of the modes k = 2 pi m / L
        used, contract C1 ``[int]``), ``n_modes_used``,
        ``stationary``, ``stationarity_p``, ``raw`` (estimates regardless of
        validity), ``modes`` (per-mode table), ``settings``, ``units``.
    """
    x, t, h = _check_profile(x, t, h)
    if start_s is not None:
        keep = t >= float(start_s)
        if keep.sum() < 2 * max(4, n_blocks):
            raise DataFileError(
                f"profile: t: expected >= {2 * max(4, n_blocks)} "
                f"frames after start_s = {start_s:g} s, "
                f"got {int(keep.sum())}"
            )
        t, h = t[keep], h[keep]
    if not (isinstance(first_lag, (int, np.integer)) and first_lag >= 0):
        raise ParameterError("first_lag", "an integer >= 0 (frames)", first_lag)
    if not (isinstance(n_blocks, (int, np.integer)) and n_blocks >= 4):
        raise ParameterError("n_blocks", "an integer >= 4", n_blocks)
    if not (isinstance(min_modes, (int, np.integer)) and min_modes >= 3):
        raise ParameterError("min_modes", "an integer >= 3", min_modes)
    nt, nx = h.shape
    if nt < 4 * n_blocks:
        raise DataFileError(
            f"profile: t: expected >= {4 * n_blocks} frames "
            f"for {n_blocks} jackknife blocks, got {nt}"
        )
    dx = float(x[1] - x[0])
    L = nx * dx
    dt = float(t[1] - t[0])
    T = float(t[-1] - t[0]) + dt
    m = np.arange(1, (nx + 1) // 2)  # 0 < k < k_Nyquist: independent complex modes
    if max_modes is not None:
        m = m[: int(max_modes)]
    k = 2 * np.pi * m / L
    hk = np.fft.rfft(h, axis=1)[:, m]
    st = mode_statistics(
        t, hk, dx=dx, n_points=nx, first_lag=int(first_lag), n_blocks=int(n_blocks)
    )
    g, ge = st["gamma"], st["gamma_err"]
    se = st["s_gamma_err"]
    base_bad = ~st["ok"] | ~np.isfinite(g) | (g <= 0)

    def select(rate, rate_err):
        # rate +- rate_err: the relaxation rate each mode is judged by.  "Enough relaxation
        # times" must hold at the 2-sigma lower bound of the rate: a short run measures gamma
        # poorly, and its noisy estimate alone would pass the test about half of the time.
        reason = np.full(m.size, "", dtype=object)
        with np.errstate(invalid="ignore"):
            lower = rate - 2 * rate_err
            checks = [
                (base_bad, "autocovariance not positive at both lags (no decay measured)"),
                (rate * dt > max_gamma_dt, f"faster than the frames: gamma dt > {max_gamma_dt:g}"),
                (
                    ~(lower * T >= min_relaxations),
                    f"run shorter than {min_relaxations:g} relaxation "
                    "times (at the 2-sigma lower bound of gamma)",
                ),
                (
                    ~(ge < np.abs(g)) | ~(se < np.abs(st["s_gamma"])),
                    "relative jackknife error >= 1",
                ),
            ]
        for bad, why in checks:
            reason[(reason == "") & bad] = why
        return reason

    # Pass 1 judges each mode by its own gamma; pass 2 by the fitted gamma(k) = mu + D0 k^2, so
    # that the selection does not depend on each mode's own noise (selecting on the noisy estimate
    # keeps, near the cut-offs, the modes whose gamma happened to come out low, and biases D0 low).
    reason = select(g, ge)
    used = reason == ""
    if used.sum() >= 3:
        e1 = _smooth_errors(k[used], ge[used])
        a0, b0, cov0, chi0, dof0 = _wls(k[used] ** 2, g[used], e1)
        birge0 = max(1.0, math.sqrt(chi0 / dof0)) if dof0 > 0 else 1.0
        model = a0 + b0 * k**2
        model_err = birge0 * np.sqrt(
            np.clip(cov0[0, 0] + 2 * cov0[0, 1] * k**2 + cov0[1, 1] * k**4, 0, None)
        )
        if np.all(np.isfinite(model)) and np.all(model > 0):
            reason2 = select(model, model_err)
            if (reason2 == "").sum() >= 2:
                reason, used = reason2, reason2 == ""
    # stationarity over the usable modes (all modes if none is usable)
    sel = used if used.sum() else np.isfinite(st["power_halves"][0])
    ph, rs = st["power_halves"][:, sel], st["power_halves_rel_sd"][:, sel]
    with np.errstate(invalid="ignore", divide="ignore"):
        zst = np.log(ph[0] / ph[1]) / np.sqrt(rs[0] ** 2 + rs[1] ** 2)
    zst = zst[np.isfinite(zst)]
    from scipy.stats import chi2 as _chi2

    p_stat = float(_chi2.sf(float((zst**2).sum()), zst.size)) if zst.size else 0.0
    stationary = bool(p_stat >= stationarity_alpha)
    n_used = int(used.sum())
    raw = dict.fromkeys(COEFFICIENTS)
    raw.update({f"{c}_err": None for c in COEFFICIENTS})
    fit_info = {}
    if n_used >= 2:
        k2 = k[used] ** 2
        for (c0, c1), yk, ek in (
            (("mu_per_s", "d0_m2_s"), g, ge),
            (("dz", "dx_l2"), st["s_gamma"], st["s_gamma_err"]),
        ):
            e_used = _smooth_errors(k[used], ek[used])
            a, b, cov, chi2, dof = _wls(k2, yk[used], e_used)
            birge = max(1.0, math.sqrt(chi2 / dof)) if dof > 0 else 1.0
            raw[c0], raw[c1] = a, b
            raw[f"{c0}_err"] = float(math.sqrt(cov[0, 0]) * birge)
            raw[f"{c1}_err"] = float(math.sqrt(cov[1, 1]) * birge)
            fit_info[f"{c0}/{c1}"] = {"chi2": chi2, "dof": dof, "birge_ratio": birge}
    common = []
    if n_used < min_modes:
        common.append(f"only {n_used} usable modes (need {min_modes})")
    if not stationary:
        common.append(
            "profile not stationary (mode power of the two halves "
            f"differ, p = {p_stat:.2g} < {stationarity_alpha:g})"
        )
    slow_ok = bool(used[0]) if used.size else False
    span_ok = bool(n_used >= 2 and k[used].max() >= 2 * k[used].min())
    valid, reasons = {}, {}
    for c in COEFFICIENTS:
        why = list(common)
        if c in ("mu_per_s", "dz") and not slow_ok:
            why.append(
                f"slowest mode k = 2 pi/L not usable ({reason[0] if reason.size else 'no modes'})"
            )
        if c in ("d0_m2_s", "dx_l2") and not span_ok:
            why.append("usable modes span less than a factor 2 in k")
        valid[c] = not why
        if why:
            reasons[c] = "; ".join(why)
    out: dict = {}
    for c in COEFFICIENTS:
        out[c] = raw[c] if valid[c] else None
        out[f"{c}_err"] = raw[f"{c}_err"] if valid[c] else None
    out.update(
        valid=valid,
        reasons=reasons,
        modes_used=[int(v) for v in m[used]],
        n_modes_used=n_used,
        stationary=stationary,
        stationarity_p=p_stat,
        raw=raw,
        fits=fit_info,
        modes={
            "index": [int(v) for v in m],
            "k_per_m": k.tolist(),
            "gamma_per_s": _list(g),
            "gamma_err_per_s": _list(ge),
            "psd_m3": _list(st["psd"]),
            "psd_err_m3": _list(st["psd_err"]),
            "s_gamma_m3_s": _list(st["s_gamma"]),
            "s_gamma_err_m3_s": _list(st["s_gamma_err"]),
            "relaxations": _list(g * T),
            "used": [bool(v) for v in used],
            "reason": [str(r) for r in reason],
        },
        settings={
            "first_lag": int(first_lag),
            "n_blocks": int(n_blocks),
            "min_relaxations": float(min_relaxations),
            "max_gamma_dt": float(max_gamma_dt),
            "min_modes": int(min_modes),
            "stationarity_alpha": float(stationarity_alpha),
            "start_s": start_s,
        },
        dt_s=dt,
        duration_s=T,
        length_m=L,
        n_frames=int(nt),
        n_points=int(nx),
        method=(
            "per-mode OU: gamma from the log-slope of the "
            "autocovariance between lags j1 and j2 (~1/gamma), "
            "S extrapolated to lag 0; delete-one-block "
            "jackknife errors; WLS against k^2 with Birge-ratio "
            "scaled errors"
        ),
        units=dict(EQ23_UNITS),
    )
    return out


def _list(a) -> list:
    return [float(v) if np.isfinite(v) else None for v in np.asarray(a, dtype=float)]
