"""Rough surfaces: 1D MDR profiles from a 2D isotropic PSD, ensembles, stiffness vs load.

The MDR for randomly rough surfaces (Geike & Popov 2007) is an
*approximation*: a random 1D profile with the 1D spectrum

    C1D(q) = pi q C2D(q)

keeps the height variance, the Hurst exponent and makes its rms slope equal
to the rms gradient magnitude of the 2D surface.  The 1D row (line length
``L1D``, springs ``E* dx``) then carries the same normal force as the 3D
nominal area ``L x L``.  Single realisations scatter by about +-40 %, so
results are ensemble medians with their 10 %/90 % quantiles.

The MDR contact length is **not** a contact area and is never reported as one.

PSD conventions (SI): ``<h^2> = int d^2q C2D(q) = 2 pi int q C2D dq``
(m^4) and ``<h^2> = int_{-inf}^{inf} C1D(q) dq`` (m^3), q in rad/m.

References
----------
T. Geike, V. L. Popov, Phys. Rev. E 76, 036710 (2007). doi:10.1103/PhysRevE.76.036710
L. Pastewka et al., Phys. Rev. E 87, 062809 (2013). doi:10.1103/PhysRevE.87.062809
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence

import numpy as np

from ...errors import ParameterError
from ..base import Result, check_int, check_positive

__all__ = [
    "self_affine_psd",
    "generate_surface",
    "measure_psd_2d",
    "psd_1d_from_2d",
    "mdr_profiles_from_psd",
    "mdr_profiles_from_heightmap",
    "stiffness_vs_load",
    "check_heightmap",
    "fourier_coefficients",
    "surface_from_coefficients",
    "rms_gradient",
    "rms_gradient_of_psd",
    "CLOSED_FRACTION_LIMIT",
]

#: Above this fraction of fully closed MDR lines the ensemble stiffness is the punch limit
#: ``E* L`` of those lines, not a roughness prediction (issue 17).
CLOSED_FRACTION_LIMIT = 0.10


def self_affine_psd(
    rms_height: float, hurst: float, rolloff_wavelength: float, short_cutoff_wavelength: float
) -> Callable:
    """Isotropic self-affine 2D PSD with a roll-off, normalised to ``rms_height``.

    ``C2D(q) = C0`` for ``q < q_r``, ``C0 (q/q_r)^(-2(1+H))`` for
    ``q_r <= q <= q_s``, 0 beyond, with ``q_r = 2 pi / rolloff_wavelength``
    and ``q_s = 2 pi / short_cutoff_wavelength`` (rad/m).

    Returns
    -------
    callable
        ``C2D(q)`` in m^4 for q in rad/m.
    """
    h = check_positive("rms_height", rms_height, "m")
    H = check_positive("hurst", hurst)
    qr = 2 * math.pi / check_positive("rolloff_wavelength", rolloff_wavelength, "m")
    qs = 2 * math.pi / check_positive("short_cutoff_wavelength", short_cutoff_wavelength, "m")
    if qs < qr:
        raise ParameterError(
            "short_cutoff_wavelength",
            f"a value <= rolloff_wavelength ({rolloff_wavelength:g} m)",
            short_cutoff_wavelength,
        )
    # 2 pi int q C dq = 2 pi C0 [qr^2/2 + qr^2 (1 - (qs/qr)^(-2H)) / (2H)]
    norm = 2 * math.pi * (qr * qr / 2 + qr * qr * (1 - (qs / qr) ** (-2 * H)) / (2 * H))
    C0 = h * h / norm

    def C2D(q):
        q = np.asarray(q, dtype=float)
        with np.errstate(divide="ignore"):
            out = np.where(q < qr, C0, C0 * (np.maximum(q, qr) / qr) ** (-2 * (1 + H)))
        return np.where(q <= qs, out, 0.0)

    return C2D


def generate_surface(
    n: int, pixel_size: float, psd2d: Callable, rng: np.random.Generator
) -> np.ndarray:
    """Periodic Gaussian random surface (m) on an ``n x n`` grid with the 2D PSD ``psd2d``.

    Fourier coefficients are complex Gaussian with ``<|B_q|^2> = 2 C2D(q) dq^2``;
    the real part gives ``<h^2> = sum_q C2D(q) dq^2``.
    """
    n = check_int("grid_points", n, 4)
    dx = check_positive("pixel_size", pixel_size, "m")
    dq = 2 * math.pi / (n * dx)
    qx = 2 * math.pi * np.fft.fftfreq(n, d=dx)
    q = np.hypot(qx[:, None], qx[None, :])
    amp = np.sqrt(psd2d(q) * dq * dq)
    amp[0, 0] = 0.0
    B = amp * (rng.standard_normal((n, n)) + 1j * rng.standard_normal((n, n)))
    return np.real(np.fft.ifft2(B) * n * n)


def fourier_coefficients(
    psd2d: Callable, side: float, k_max: int, rng: np.random.Generator
) -> np.ndarray:
    """Random Fourier coefficients (m) of a band-limited periodic surface of side ``side``.

    The coefficients ``B[kx + k_max, ky + k_max]`` of the wave vectors
    ``2 pi (kx, ky) / side`` with ``|kx|, |ky| <= k_max`` are drawn as in
    :func:`generate_surface` (``<|B|^2> = 2 C2D(q) dq^2``); with ``psd2d``
    zero beyond ``2 pi k_max / side`` the surface ``Re sum B e^{i q.x}`` is a
    smooth function that :func:`surface_from_coefficients` samples on any grid
    finer than ``2 k_max + 1`` points: the same surface at every resolution,
    which is what a resolution study needs.
    """
    L = check_positive("side", side, "m")
    k_max = check_int("k_max", k_max, 1)
    k = np.arange(-k_max, k_max + 1)
    dq = 2 * math.pi / L
    q = np.hypot(k[:, None], k[None, :]) * dq
    amp = np.sqrt(psd2d(q) * dq * dq)
    amp[k_max, k_max] = 0.0
    return amp * (rng.standard_normal(q.shape) + 1j * rng.standard_normal(q.shape))


def surface_from_coefficients(B: np.ndarray, n: int) -> np.ndarray:
    """Heights (m) on an ``n x n`` grid of the surface ``Re sum B e^{i q.x}``.

    See :func:`fourier_coefficients`.
    """
    B = np.asarray(B)
    k_max = (B.shape[0] - 1) // 2
    n = check_int("grid_points", n, 2 * k_max + 2)
    F = np.zeros((n, n), dtype=complex)
    idx = np.arange(-k_max, k_max + 1) % n
    F[np.ix_(idx, idx)] = B
    return np.real(np.fft.ifft2(F) * n * n)


def rms_gradient(heights, pixel_size: float) -> float:
    """Rms gradient magnitude (1) of a periodic height map, by spectral differentiation.

    Exact for a band-limited surface sampled above its Nyquist rate; the
    Nyquist row/column (no defined derivative) is left out.
    """
    h = check_heightmap(heights, pixel_size)
    ny, nx = h.shape
    H = np.fft.fft2(h - h.mean())
    qx = 2 * math.pi * np.fft.fftfreq(nx, d=pixel_size)
    qy = 2 * math.pi * np.fft.fftfreq(ny, d=pixel_size)
    if nx % 2 == 0:
        qx[nx // 2] = 0.0
    if ny % 2 == 0:
        qy[ny // 2] = 0.0
    q2 = qy[:, None] ** 2 + qx[None, :] ** 2
    return float(math.sqrt(np.sum(q2 * np.abs(H) ** 2) / (nx * ny) ** 2))


def rms_gradient_of_psd(
    rms_height: float, hurst: float, rolloff_wavelength: float, short_cutoff_wavelength: float
) -> float:
    """Rms gradient (1) of :func:`self_affine_psd`: ``sqrt(2 pi int q^3 C2D dq)`` in closed form."""
    h = check_positive("rms_height", rms_height, "m")
    H = check_positive("hurst", hurst)
    qr = 2 * math.pi / check_positive("rolloff_wavelength", rolloff_wavelength, "m")
    qs = 2 * math.pi / check_positive("short_cutoff_wavelength", short_cutoff_wavelength, "m")
    norm = qr * qr / 2 + qr * qr * (1 - (qs / qr) ** (-2 * H)) / (2 * H)
    # int_qr^qs q^3 (q/qr)^(-2-2H) dq = qr^4 [(qs/qr)^(2-2H) - 1] / (2 - 2H)  (log for H = 1)
    x = qs / qr
    tail = qr**4 * (math.log(x) if abs(1 - H) < 1e-12 else (x ** (2 - 2 * H) - 1) / (2 - 2 * H))
    return h * math.sqrt((qr**4 / 4 + tail) / norm)


def check_heightmap(heights, pixel_size=None) -> np.ndarray:
    """Validate a height map: a finite, square-or-rectangular 2D array with >= 4 points per side."""
    h = np.asarray(heights)
    if h.ndim != 2:
        raise ParameterError(
            "surface", "a 2D array of heights (m)", f"a {h.ndim}D array of shape {h.shape}"
        )
    if min(h.shape) < 4:
        raise ParameterError("surface", "at least 4 points per side", f"shape {h.shape}")
    if not np.issubdtype(h.dtype, np.number) or np.iscomplexobj(h):
        raise ParameterError("surface", "real numeric heights", str(h.dtype))
    h = np.asarray(h, dtype=float)
    if not np.isfinite(h).all():
        raise ParameterError(
            "surface", "finite heights", f"{int(np.count_nonzero(~np.isfinite(h)))} NaN/inf values"
        )
    if pixel_size is not None:
        check_positive("pixel_size", pixel_size, "m")
    return h


def measure_psd_2d(heights, pixel_size: float) -> tuple[np.ndarray, np.ndarray]:
    """Radially averaged 2D PSD of a height map.

    Returns
    -------
    q : ndarray
        Bin centres (rad/m), multiples of ``2 pi / L``.
    C2D : ndarray
        PSD (m^4), with ``sum_q C2D dq^2 = <(h - <h>)^2>`` over the full grid.
    """
    return _measure_psd_2d(check_heightmap(heights, pixel_size), pixel_size)


def _measure_psd_2d(h: np.ndarray, pixel_size: float) -> tuple[np.ndarray, np.ndarray]:
    from scipy import fft

    ny, nx = h.shape
    dqx, dqy = 2 * math.pi / (nx * pixel_size), 2 * math.pi / (ny * pixel_size)
    # Real FFT: the half plane, each column except 0 (and Nyquist) standing for two wave vectors.
    H = fft.rfft2(h - h.mean(), workers=2)
    C = (H.real**2 + H.imag**2) / (nx * ny) ** 2 / (dqx * dqy)
    qx = 2 * math.pi * np.fft.rfftfreq(nx, d=pixel_size)
    qy = 2 * math.pi * np.fft.fftfreq(ny, d=pixel_size)
    q = np.hypot(qy[:, None], qx[None, :])
    mult = np.full(qx.size, 2.0)
    mult[0] = 1.0
    if nx % 2 == 0:
        mult[-1] = 1.0
    wgt = np.broadcast_to(mult, C.shape).ravel()
    dq = min(dqx, dqy)
    k = np.rint(q / dq).astype(int).ravel()
    sums = np.bincount(k, weights=C.ravel() * wgt)
    counts = np.bincount(k, weights=wgt)
    kk = np.nonzero(counts)[0]
    kk = kk[kk > 0]
    return kk * dq, sums[kk] / counts[kk]


def psd_1d_from_2d(q, C2D) -> np.ndarray:
    """Geike-Popov rule ``C1D(q) = pi q C2D(q)`` (m^3)."""
    return math.pi * np.asarray(q, dtype=float) * np.asarray(C2D, dtype=float)


def _profiles_from_c1d(
    c1d_of_q: Callable, n: int, dx: float, n_realizations: int, rng: np.random.Generator
):
    """Random 1D profiles (m) with two-sided PSD ``C1D``.

    On a line of ``n`` points, spacing ``dx``.
    """
    n = check_int("n_points", n, 4)
    R = check_int("n_realizations", n_realizations, 1)
    L = n * dx
    dq = 2 * math.pi / L
    q = dq * np.arange(n // 2 + 1)
    c = np.asarray(c1d_of_q(q), dtype=float)
    c[0] = 0.0
    # <h^2> = sum_k 2 C1D(q_k) dq  ->  <|A_k|^2> = 4 C1D dq for h = Re sum A_k e^{i q x}
    amp = np.sqrt(2.0 * c * dq)
    A = amp * (rng.standard_normal((R, q.size)) + 1j * rng.standard_normal((R, q.size)))
    if n % 2 == 0:
        # The Nyquist mode is real and appears once in the two-sided sum (variance C1D dq, half
        # that of a +-q pair): a real amplitude with <A^2> = 4 C1D dq, which irfft weights by 1/2.
        A[:, -1] = amp[-1] * math.sqrt(2.0) * rng.standard_normal(R)
    # irfft doubles the 0 < k < n/2 modes and weights Nyquist once: times n/2 this is
    # Re sum_{0<k<n/2} A_k e^{iqx} + A_{n/2} cos(pi j) / 2, i.e. every mode with its PSD share.
    h = np.fft.irfft(A, n=n, axis=1) * n / 2.0
    x = (np.arange(n) - (n - 1) / 2.0) * dx
    g = h.max(axis=1, keepdims=True) - h
    return x, g


def mdr_profiles_from_psd(
    psd2d: Callable,
    n_points: int,
    pixel_size: float,
    n_realizations: int,
    rng: np.random.Generator,
) -> tuple[np.ndarray, np.ndarray]:
    """Ensemble of 1D MDR profiles for a surface with the isotropic 2D PSD ``psd2d``.

    Parameters
    ----------
    psd2d : callable
        ``C2D(q)`` (m^4) for q in rad/m, e.g. :func:`self_affine_psd`.
    n_points : int
        Springs per profile; the line length is ``L1D = n_points * pixel_size``.
    pixel_size : float
        Spring spacing (m).
    n_realizations : int
        Number of independent profiles.
    rng : numpy.random.Generator
        Source of randomness (explicit; no global state).

    Returns
    -------
    x : ndarray, shape (n_points,)
        Spring positions (m), uniform.
    g : ndarray, shape (n_realizations, n_points)
        Gaps to the highest point of each profile (m); ``g.min(axis=1) == 0``.
    """
    dx = check_positive("pixel_size", pixel_size, "m")
    return _profiles_from_c1d(
        lambda q: psd_1d_from_2d(q, psd2d(q)), n_points, dx, n_realizations, rng
    )


def mdr_profiles_from_heightmap(
    heights, pixel_size: float, n_realizations: int, rng: np.random.Generator
):
    """Ensemble of 1D MDR profiles whose spectrum is measured from a height map.

    2D map: the radially averaged ``C2D`` is turned into ``C1D = pi q C2D``
    and sampled on a line of the map's side ``L1D = n dx`` with the same
    spacing (``n`` the larger side).

    1D map (a line scan of an isotropic surface, e.g. a ``dim = 1``
    topography): its spectrum is the Abel projection of ``C2D``,
    ``C_line(q) = 2 int_q^inf C2D(k) k / sqrt(k^2 - q^2) dk``; the inverse
    Abel transform gives ``C1D = pi q C2D = -q int_0^T C_line'(q cosh t) dt``
    (``T = acosh(q_max/q)``), evaluated on the log-binned periodogram.

    Returns ``(x, g)`` as :func:`mdr_profiles_from_psd`.
    """
    h = np.asarray(heights)
    if h.ndim == 1:
        return _profiles_from_line_scan(h, pixel_size, n_realizations, rng)
    h = check_heightmap(heights, pixel_size)
    q, C2 = _measure_psd_2d(h, pixel_size)
    C1 = psd_1d_from_2d(q, C2)

    def c1d(qq):
        return np.interp(qq, q, C1, left=0.0, right=0.0)

    return _profiles_from_c1d(c1d, max(h.shape), float(pixel_size), n_realizations, rng)


def _profiles_from_line_scan(h, pixel_size, n_realizations, rng):
    """MDR ensemble from a 1D line scan through the inverse Abel transform of its PSD."""
    h = np.asarray(h)
    if h.size < 16 or not np.issubdtype(h.dtype, np.number) or np.iscomplexobj(h):
        raise ParameterError(
            "surface", "a 2D height map or a real 1D line scan of >= 16 points", f"shape {h.shape}"
        )
    h = np.asarray(h, dtype=float)
    if not np.isfinite(h).all():
        raise ParameterError(
            "surface", "finite heights", f"{int(np.count_nonzero(~np.isfinite(h)))} NaN/inf values"
        )
    dx = check_positive("pixel_size", pixel_size, "m")
    n = h.size
    dq = 2 * math.pi / (n * dx)
    H = np.fft.rfft(h - h.mean())
    k = np.arange(1, H.size)
    # two-sided line PSD: sum over +-q of C dq = <h^2>
    C = (np.abs(H[1:]) ** 2) / (n * n * dq)
    if n % 2 == 0:
        C[-1] /= 2.0
    # log-binned periodogram (about 8 bins per decade) -> smooth log-log interpolant
    edges = np.unique(
        np.round(np.geomspace(1, k[-1] + 1, 8 * max(1, int(np.log10(k[-1]) + 1)) + 1)).astype(int)
    )
    idx = np.clip(np.searchsorted(edges, k, side="right") - 1, 0, edges.size - 2)
    cnt = np.bincount(idx, minlength=edges.size - 1)
    Cb = np.bincount(idx, weights=C, minlength=edges.size - 1)
    kb = np.bincount(idx, weights=np.log(k), minlength=edges.size - 1)
    ok = (cnt > 0) & (Cb > 0)
    lq = kb[ok] / cnt[ok] + math.log(dq)
    lC = np.log(Cb[ok] / cnt[ok])
    if lq.size < 2:
        raise ParameterError("surface", "a line scan with a resolvable spectrum", "a flat profile")
    slope = (
        np.gradient(lC, lq) if lq.size > 2 else np.full_like(lq, (lC[1] - lC[0]) / (lq[1] - lq[0]))
    )
    qmax = dq * k[-1]
    t_gl, w_gl = np.polynomial.legendre.leggauss(64)

    def c1d(qq):
        qq = np.asarray(qq, dtype=float)
        out = np.zeros_like(qq)
        m = (qq > 0) & (qq < qmax)
        qm = qq[m]
        T = np.arccosh(qmax / qm)
        tt = 0.5 * (t_gl[None, :] + 1.0) * T[:, None]
        kk = np.log(qm[:, None] * np.cosh(tt))
        Ck = np.exp(np.interp(kk, lq, lC))
        dC = Ck * np.interp(kk, lq, slope) / np.exp(kk)  # C_line'(k) from the log-log interpolant
        out[m] = -qm * 0.5 * T * np.sum(dC * w_gl[None, :], axis=1)
        return np.maximum(out, 0.0)

    return _profiles_from_c1d(c1d, n, dx, n_realizations, rng)


def _forces(g: np.ndarray, d: np.ndarray, dx: float) -> tuple[np.ndarray, np.ndarray]:
    """Force / E* (m^2) and contact length (m) of each profile row at its indentation.

    Same exact piecewise-linear integral as :func:`~tribolmp.models.contact.mdr.normal_force`,
    summed per cell in one pass (the ensemble solver calls this in its Newton loop).
    """
    f = d[:, None] - g
    fl, fr = f[:, :-1], f[:, 1:]
    hi, lo = np.maximum(fl, fr), np.minimum(fl, fr)
    both = lo > 0
    cut = (hi > 0) & ~both
    with np.errstate(invalid="ignore", divide="ignore"):
        t = np.where(cut, hi / (hi - lo), 0.0)  # in-contact fraction of a cut cell
    area = np.where(both, 0.5 * (fl + fr), 0.5 * hi * t).sum(axis=1) * dx
    length = (np.count_nonzero(both, axis=1) + t.sum(axis=1)) * dx
    ends = np.maximum(f[:, 0], 0.0) + np.maximum(f[:, -1], 0.0)  # half cells beyond the row
    area += 0.5 * dx * ends
    length += 0.5 * dx * ((f[:, 0] > 0).astype(float) + (f[:, -1] > 0))
    return area, length


def _indentation_for_force(g: np.ndarray, dx: float, target: np.ndarray) -> np.ndarray:
    """Indentation (m) of each profile carrying ``target`` (force / E*, m^2).

    A sorted-spring estimate is refined by Newton steps on the exact
    piecewise-linear row; the force is convex and increasing in d, so Newton
    from the spring-sum estimate converges in a few steps.
    """
    R, n = g.shape
    gs = np.sort(g, axis=1)
    cs = np.cumsum(gs, axis=1)
    k = np.arange(1, n + 1)
    # spring-sum force with the k lowest springs in contact: dx (k d - S_k),
    # valid for d in [g_k, g_{k+1}]
    Fk = dx * (k * gs - cs)
    j = np.count_nonzero(Fk < target[:, None], axis=1)
    jj = np.clip(j, 1, n)
    d = (target / dx + cs[np.arange(R), jj - 1]) / jj
    for _ in range(60):
        F, ln = _forces(g, d, dx)
        err = F - target
        if np.all(np.abs(err) <= 1e-12 * target):
            break
        d = d - err / np.maximum(ln, 1e-300)
        d = np.maximum(d, 0.0)
    return d


def stiffness_vs_load(
    x,
    g,
    E_star: float,
    pressures: Sequence[float],
    nominal_area: float | None = None,
) -> Result:
    """Compute stiffness, force and approach of an MDR profile ensemble against mean pressure.

    Each 1D profile of line length ``L1D = n dx`` carries the force
    ``F = p A`` of the nominal area ``A`` (default ``L1D^2``, the square of
    which the profile is a section).

    Parameters
    ----------
    x : ndarray, shape (n,)
        Spring positions (m).
    g : ndarray, shape (R, n) or (n,)
        Gaps of the profiles (m).
    E_star : float
        Effective modulus (Pa).
    pressures : sequence of float
        Nominal pressures (Pa).
    nominal_area : float, optional
        Nominal area A (m^2).

    Returns
    -------
    Result
        Per pressure: ``pressure`` (Pa), ``force`` (N), ``stiffness``
        (median dF/dd, N/m), ``stiffness_q10``/``stiffness_q90``,
        ``approach`` (median indentation from first touch of each profile, m)
        with ``approach_q10``/``approach_q90``, and the per-realisation arrays
        ``stiffness_all``/``approach_all`` (R x P), and
        ``closed_fraction`` (fraction of the lines whose whole row is in
        contact: a count of profiles, not an area; ``closed_realizations`` is
        the same array), and ``warnings``: one line per pressure whose
        ``closed_fraction`` exceeds :data:`CLOSED_FRACTION_LIMIT` (there the
        median is the punch limit ``E* L``).  No contact area.
    """
    t0 = time.perf_counter()
    x = np.asarray(x, dtype=float)
    g = np.asarray(g, dtype=float)
    g = g[None, :] if g.ndim == 1 else g
    if x.ndim != 1 or g.shape[1] != x.size or x.size < 2:
        raise ParameterError(
            "x, g", "x of shape (n,) and g of shape (R, n)", f"shapes {x.shape}, {g.shape}"
        )
    E = check_positive("modulus", E_star, "Pa")
    dx = float(x[1] - x[0])
    L = x.size * dx
    A = L * L if nominal_area is None else check_positive("nominal_area", nominal_area, "m^2")
    P = np.array([check_positive("pressure", p, "Pa") for p in pressures], dtype=float)
    R = g.shape[0]
    K = np.empty((R, P.size))
    D = np.empty((R, P.size))
    for j, p in enumerate(P):
        target = np.full(R, p * A / E)
        d = _indentation_for_force(g, dx, target)
        _, ln = _forces(g, d, dx)
        K[:, j] = E * ln
        D[:, j] = d
    kq = np.quantile(K, [0.1, 0.5, 0.9], axis=0)
    dq = np.quantile(D, [0.1, 0.5, 0.9], axis=0)
    # A line is closed when the indentation reaches its deepest point: every spring touches.
    closed = np.mean(D >= g.max(axis=1)[:, None], axis=0)
    warnings = [
        f"MDR: {c:.0%} of the lines are fully in contact "
        f"at {p:g} Pa (> {CLOSED_FRACTION_LIMIT:.0%}): "
        f"the stiffness is the punch limit E*L of those lines, not a roughness prediction"
        for p, c in zip(P, closed)
        if c > CLOSED_FRACTION_LIMIT
    ]
    res = Result(
        pressure=P,
        force=P * A,
        stiffness=kq[1],
        stiffness_q10=kq[0],
        stiffness_q90=kq[2],
        approach=dq[1],
        approach_q10=dq[0],
        approach_q90=dq[2],
        closed_fraction=closed,
        closed_realizations=closed,
        stiffness_all=K,
        approach_all=D,
        nominal_area=A,
        line_length=L,
        realizations=R,
        method="mdr",
        units={
            "pressure": "Pa",
            "force": "N",
            "stiffness": "N/m",
            "stiffness_q10": "N/m",
            "stiffness_q90": "N/m",
            "approach": "m",
            "approach_q10": "m",
            "approach_q90": "m",
            "nominal_area": "m^2",
            "line_length": "m",
            "closed_realizations": "1",
            "closed_fraction": "1",
        },
        warnings=warnings,
    )
    res["time_s"] = time.perf_counter() - t0
    res["message"] = (
        f"{R} realisations x {P.size} pressures; the MDR contact length is not a contact area"
    )
    return res
