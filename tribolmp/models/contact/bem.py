"""3D elastic half-space boundary-element reference: FFT + constrained CG.

A rigid surface with heights ``h`` (m; larger = closer to the elastic body)
is pressed on a flat elastic half-space of effective modulus ``E*`` (Pa).
The frictionless contact problem (non-negative pressure, non-negative gap,
complementarity) is solved for a prescribed mean pressure by the constrained
conjugate-gradient method of Polonsky & Keer (1999), with the surface
displacement ``u = K * p`` evaluated by FFT:

* ``periodic=True``: the periodic half-space, ``u(q) = 2 p(q) / (E* |q|)``
  (the mean of u is undetermined and set to 0; the approach is measured from
  the mean plane, i.e. as the interfacial separation change);
* ``periodic=False``: a non-periodic rigid punch of side ``n dx`` on an
  infinite half-space; the pressure is constant on each pixel and the exact
  influence coefficients (Love 1929) are convolved on a zero-padded ``2n``
  grid, so there are no periodic images and the error is O(dx^2).

Wall time per iteration is one real FFT convolution (``K t`` of the search direction)
while the contact set is unchanged, and two when pixels leave or enter it (the
displacement ``K p`` is otherwise updated by linearity).  SI units throughout.

References
----------
I. A. Polonsky, L. M. Keer, Wear 231, 206 (1999). doi:10.1016/S0043-1648(99)00113-1
A. E. H. Love, Phil. Trans. R. Soc. A 228, 377 (1929). doi:10.1098/rsta.1929.0009
H. M. Stanley, T. Kato, J. Tribol. 119, 481 (1997). doi:10.1115/1.2833523
"""

from __future__ import annotations

import math
import os
import time

import numpy as np

from ...errors import ConvergenceError, ParameterError
from ..base import Result, check_int, check_positive

__all__ = ["HalfSpace", "solve_bem", "love_influence", "sphere_heights", "KERNEL_CACHE_SIZE"]

KERNEL_CACHE_SIZE = 8
_KERNELS: dict[tuple, np.ndarray] = {}


def _workers() -> int:
    """FFT threads: ``TRIBOLMP_FFT_WORKERS`` (default 1).

    Measured on the shared 2-core machine (scipy 1.17 pocketfft, one rfft2 + irfft2 pair):
    256^2 1.5 ms with 1 thread vs 2.3 ms with 2, 512^2 11 vs 15 ms, 1024^2 41 vs 61 ms, so
    threads only pay on an idle multi-core machine; there set the variable.
    """
    try:
        return max(1, int(os.environ.get("TRIBOLMP_FFT_WORKERS", "1")))
    except ValueError:
        return 1


def _dot(a: np.ndarray, b: np.ndarray, work: np.ndarray) -> float:
    """Sum of ``a * b`` through a work array, without BLAS.

    ``np.dot`` of float64 vectors calls BLAS ``ddot``, which OpenBLAS runs multithreaded
    above 10^4 elements: on a loaded machine its thread wake-ups cost more than the
    whole FFT-bound iteration (measured: 256^2 solve 2.0 s CPU with ``np.vdot`` against
    0.25 s with one BLAS thread).  A ufunc product and numpy's pairwise sum stay on
    one core and are as accurate.
    """
    np.multiply(a, b, out=work)
    return float(work.sum())


def love_influence(x, y, a, b, E_star):
    """Surface displacement (m) at (x, y) under unit pressure (1 Pa) on ``|x|<a, |y|<b``.

    Closed form of Love (1929) written with ``F(x, y) = x asinh(y/|x|) + y asinh(x/|y|)``
    (the double antiderivative of ``1/sqrt(x^2+y^2)``), which is free of the
    cancellations of the textbook logarithms:
    ``u = [F(x+a, y+b) - F(x+a, y-b) - F(x-a, y+b) + F(x-a, y-b)] / (pi E*)``.
    """

    def F(X, Y):
        with np.errstate(divide="ignore", invalid="ignore"):
            t1 = np.where(X != 0, X * np.arcsinh(Y / np.where(X != 0, np.abs(X), 1.0)), 0.0)
            t2 = np.where(Y != 0, Y * np.arcsinh(X / np.where(Y != 0, np.abs(Y), 1.0)), 0.0)
        return t1 + t2

    return (F(x + a, y + b) - F(x + a, y - b) - F(x - a, y + b) + F(x - a, y - b)) / (
        math.pi * E_star
    )


class HalfSpace:
    """FFT convolution operator ``p (Pa) -> u (m)`` of the elastic half-space.

    Parameters
    ----------
    n : int
        Grid points per side.
    dx : float
        Pixel size (m).
    E_star : float
        Effective modulus (Pa).
    periodic : bool
        Periodic cell (True) or isolated ``n dx`` square on an infinite
        half-space (False, zero-padded to ``2n``).
    """

    def __init__(self, n: int, dx: float, E_star: float, periodic: bool = True):
        self.n = check_int("n", n, 2)
        self.dx = check_positive("pixel_size", dx, "m")
        self.E_star = check_positive("modulus", E_star, "Pa")
        self.periodic = bool(periodic)
        key = (self.n, self.dx, self.E_star, self.periodic)
        kernel = _KERNELS.get(key)
        if kernel is None:
            kernel = self._build()
            if len(_KERNELS) >= KERNEL_CACHE_SIZE:
                _KERNELS.pop(next(iter(_KERNELS)))
            _KERNELS[key] = kernel
        self.kernel = kernel
        # Displacement of a pixel under its own unit pressure (m/Pa): the scale of a
        # pressure correction that closes a local overlap.
        self.self_compliance = float(
            love_influence(0.0, 0.0, self.dx / 2, self.dx / 2, self.E_star)
        )

    def _build(self) -> np.ndarray:
        from scipy import fft

        n, dx = self.n, self.dx
        if self.periodic:
            qx = 2 * math.pi * np.fft.fftfreq(n, d=dx)
            qy = 2 * math.pi * np.fft.rfftfreq(n, d=dx)
            q = np.hypot(qx[:, None], qy[None, :])
            with np.errstate(divide="ignore"):
                k = 2.0 / (self.E_star * q)
            k[0, 0] = 0.0  # the mean displacement is undetermined in a periodic cell
            return k
        m = 2 * n
        i = np.arange(m)
        c = np.where(i < n, i, i - m) * dx
        inf = love_influence(c[:, None], c[None, :], dx / 2, dx / 2, self.E_star)
        return fft.rfft2(inf, workers=_workers())

    @property
    def shape(self) -> tuple[int, int]:
        """Shape of the pressure grid."""
        return (self.n, self.n)

    def __call__(self, p: np.ndarray) -> np.ndarray:
        """Displacement (m) due to the pressure field ``p`` (Pa) on the grid.

        One real forward and one real inverse FFT; the spectrum is multiplied by the
        precomputed kernel in place and handed to the inverse transform to overwrite.
        """
        from scipy import fft

        w = _workers()
        if self.periodic:
            f = fft.rfft2(p, workers=w)
            f *= self.kernel
            return fft.irfft2(f, s=p.shape, workers=w, overwrite_x=True)
        m = 2 * self.n
        f = fft.rfft2(p, s=(m, m), workers=w)
        f *= self.kernel
        return fft.irfft2(f, s=(m, m), workers=w, overwrite_x=True)[: self.n, : self.n]


def sphere_heights(n: int, dx: float, radius: float) -> np.ndarray:
    """Heights (m) of a paraboloid of radius R centred on pixel (n//2, n//2): ``-r^2/(2R)``."""
    c = (np.arange(n) - n // 2) * dx
    return -(c[:, None] ** 2 + c[None, :] ** 2) / (2.0 * radius)


def solve_bem(
    heights: np.ndarray,
    pixel_size: float,
    E_star: float,
    pressure: float,
    *,
    periodic: bool = True,
    tol: float = 1e-10,
    maxiter: int = 10000,
    stiffness: bool = True,
    stiffness_tol: float = 1e-8,
    p0: np.ndarray | None = None,
) -> Result:
    """Frictionless contact of a rigid rough surface with a half-space at a given mean pressure.

    Parameters
    ----------
    heights : ndarray, shape (n, n)
        Rigid surface heights (m); larger values touch first.
    pixel_size : float
        Grid spacing (m).
    E_star : float
        Effective modulus (Pa).
    pressure : float
        Mean (nominal) pressure over the ``(n dx)^2`` area (Pa).
    periodic : bool
        Periodic cell or isolated square punch (zero padding).
    tol : float
        Stop when the relative L1 change of the pressure in one iteration is
        below ``tol`` (Polonsky-Keer criterion).
    maxiter : int
        Iteration cap; :class:`ConvergenceError` when reached.
    stiffness : bool
        Also compute the incremental normal stiffness ``dF/d(approach)`` by a
        linear CG solve with unit rigid displacement on the contact set.
    p0 : ndarray, optional
        Initial pressure (warm start); rescaled to the target load.

    Returns
    -------
    Result
        ``force`` (N), ``pressure`` (Pa), ``approach`` (m, from first touch of
        the highest point; periodic: relative to the mean plane of the
        elastic surface), ``mean_gap`` (m), ``area_fraction`` (real contact
        area / nominal area), ``contact_area`` (m^2), ``stiffness`` (N/m,
        ``inf`` for complete contact of a periodic cell),
        ``max_pressure`` (Pa), ``p`` (pressure field, Pa), ``u``
        (displacement field, m), ``nit``, ``nit_stiffness``, ``time_s``.
    """
    t0 = time.perf_counter()
    h = np.asarray(heights, dtype=float)
    if h.ndim != 2 or h.shape[0] != h.shape[1] or h.shape[0] < 2:
        raise ParameterError("heights", "a square 2D array (n, n) with n >= 2", f"shape {h.shape}")
    if not np.all(np.isfinite(h)):
        raise ParameterError("heights", "finite values", "NaN or inf")
    n = h.shape[0]
    dx = check_positive("pixel_size", pixel_size, "m")
    check_positive("pressure", pressure, "Pa")
    op = HalfSpace(n, dx, E_star, periodic)
    area_px = dx * dx
    W = pressure * n * n * area_px
    total = pressure * n * n  # sum of pixel pressures that carries W

    if p0 is not None and p0.shape == h.shape and np.sum(p0) > 0:
        p = np.maximum(p0, 0.0) * (total / np.sum(p0))
    else:
        p = np.full(h.shape, pressure)
    # Penetrations below round-off of the height range do not count as overlaps
    # (otherwise the "no overlap" convergence condition could never be met).
    gap_tol = 1e-12 * max(float(np.ptp(h)), float(np.abs(h).max()), 1e-300)
    # Work arrays, allocated once: every pass below is an in-place ufunc (dots: :func:`_dot`)
    # (the solver is FFT-bound; fresh n^2 temporaries per iteration cost as much again).
    u = np.ascontiguousarray(op(p))
    g = np.empty_like(p)
    gS = np.empty_like(p)
    t = np.zeros_like(p)
    tmp = np.empty_like(p)
    tS = np.empty_like(p)
    p_new = np.empty_like(p)
    S = np.empty(h.shape, dtype=bool)
    S2 = np.empty(h.shape, dtype=bool)
    Sf = np.empty_like(p)
    G_old = 1.0
    delta = 0.0
    converged = False
    nit = 0
    n_linear = 0  # consecutive displacement updates by linearity (no FFT), see below
    eps = float("inf")
    for nit in range(1, maxiter + 1):
        np.subtract(u, h, out=g)
        np.greater(p, 0.0, out=S)
        nS = np.count_nonzero(S)
        np.copyto(Sf, S)
        g -= _dot(g, Sf, tmp) / nS  # the rigid offset: mean gap over the contact = 0
        np.multiply(g, Sf, out=gS)
        G = _dot(gS, gS, tmp)
        if delta:
            # conjugate direction on the current contact set only (Polonsky-Keer: t = 0 off
            # I_g); a direction left on pixels that dropped out would push them below zero
            # at every step, and each such clip costs a displacement FFT
            t *= delta * G / G_old
            t *= Sf
            t += gS
        else:
            np.copyto(t, gS)
        G_old = G
        r = op(t)  # K t: the one convolution of an iteration without active-set change
        # tau = <gS, t> / <(K t - mean_S K t), t>_S
        rbar = _dot(r, Sf, tmp) / nS
        np.multiply(t, Sf, out=tS)
        rt = _dot(r, tS, tmp) - rbar * float(tS.sum())
        tau = _dot(gS, t, tmp) / rt if rt > 0 else 0.0
        if tau <= 0.0:
            # The current contact set is solved exactly (t == 0, e.g. a warm start
            # scaled to a new load): only overlaps remain, closed with the local compliance.
            tau = 1.0 / op.self_compliance
        np.multiply(t, -tau, out=p_new)
        p_new += p
        np.less(p_new, 0.0, out=S)
        clipped = bool(S.any())
        if clipped:
            np.maximum(p_new, 0.0, out=p_new)
        np.equal(p_new, 0.0, out=S)
        np.less(g, -gap_tol, out=S2)
        S &= S2
        overlap = bool(S.any())
        if overlap:
            delta = 0.0
            np.multiply(g, -tau, out=tmp)
            np.add(p_new, tmp, out=p_new, where=S)
        else:
            delta = 1.0
        scale = total / float(p_new.sum())
        p_new *= scale
        np.subtract(p_new, p, out=tmp)
        np.abs(tmp, out=tmp)
        eps = float(tmp.sum()) / total
        # Displacement of the new pressure.  Without clipping or overlap correction the
        # step is linear, p_new = scale (p - tau t), so u_new = scale (u - tau K t) needs no
        # FFT; otherwise (and every 32 linear updates, against round-off drift) u = K p_new.
        if clipped or overlap or n_linear >= 32:
            u = np.ascontiguousarray(op(p_new))
            n_linear = 0
        else:
            np.multiply(r, tau, out=tmp)
            u -= tmp
            u *= scale
            n_linear += 1
        p, p_new = p_new, p
        if eps < tol and delta:  # converged and no overlap left
            converged = True
            break
    if not converged:
        raise ConvergenceError(
            f"BEM did not converge in {maxiter} iterations "
            f"(relative change {eps:.3g} > tol {tol:g})"
        )

    if n_linear:
        u = np.ascontiguousarray(op(p))  # exact displacement of the returned pressure
    S = p > 0
    c = float(np.mean((h - u)[S]))  # rigid offset: gap = u - h + c = 0 on the contact
    approach = float(h.max()) - c
    mean_gap = float(np.mean(u - h)) + c
    frac = float(np.count_nonzero(S)) / (n * n)
    res = Result(
        force=W,
        pressure=float(pressure),
        approach=approach,
        mean_gap=mean_gap,
        area_fraction=frac,
        contact_area=frac * n * n * area_px,
        max_pressure=float(p.max()),
        p=p,
        u=u,
        method="bem",
        periodic=bool(periodic),
        nit=nit,
        units={
            "force": "N", "pressure": "Pa", "approach": "m", "mean_gap": "m", "area_fraction": "1",
            "contact_area": "m^2", "max_pressure": "Pa", "p": "Pa", "u": "m", "stiffness": "N/m",
        },
    )
    res["stiffness"], res["nit_stiffness"] = (
        _stiffness(op, S, area_px, stiffness_tol) if stiffness else (float("nan"), 0)
    )
    res["time_s"] = time.perf_counter() - t0
    res["message"] = f"converged in {nit} iterations, contact fraction {frac:.4g}"
    return res


def _stiffness(op: HalfSpace, S: np.ndarray, area_px: float, tol: float) -> tuple[float, int]:
    """dF/d(approach) (N/m): pressure increment for a unit rigid displacement of the contact set.

    For frictionless contact the contact set changes only at second order,
    so the tangent stiffness is the linear response ``K_SS dp = 1`` on the
    current contact set, solved by conjugate gradients.
    """
    if op.periodic and S.all():
        return float("inf"), 0
    Sf = S.astype(float)
    x = np.zeros_like(Sf)
    r = Sf.copy()
    z = Sf.copy()
    Az = np.empty_like(Sf)
    work = np.empty_like(Sf)
    rr = _dot(r, r, work)
    rr0 = rr
    nit = 0
    for nit in range(1, 10 * S.size + 1):
        np.multiply(op(z), Sf, out=Az)
        alpha = rr / _dot(z, Az, work)
        np.multiply(z, alpha, out=work)
        x += work
        np.multiply(Az, alpha, out=work)
        r -= work
        rr_new = _dot(r, r, work)
        if rr_new < tol * tol * rr0:
            break
        z *= rr_new / rr
        z += r
        rr = rr_new
    return float(x.sum() * area_px), nit
