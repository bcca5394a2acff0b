"""Solvers for the stochastic diffusion-wear equation of surface topography (Eq. 23).

    dh/dt = d/dx (D0 dh/dx + l f_x) + f_z - mu h,
    <f_a(x,t) f_a(x',t')> = 2 D_a F(x - x') delta(t - t'),   a = x, z,

on a periodic grid of ``n`` (1D) or ``n x n`` (2D) points of spacing ``dx``.
In 2D the flux term is ``div(D0 grad h + l f)`` with an independent noise
``f`` per direction.  ``F`` is a unit-integral Gaussian of length ``l_c``
(delta-correlated for ``l_c = 0``), so ``Dx`` and ``Dz`` have units m^3/s in
1D and m^4/s in 2D.

Two schemes, chosen by name (registry :data:`SCHEMES`):

``"exact"``
    Each real-FFT mode is an Ornstein-Uhlenbeck process, advanced with its
    exact transition law: ``hat h <- a hat h + b xi`` with
    ``a = exp(-gamma dt)``, ``b^2 = q (1 - a^2) / (2 gamma)`` (``q dt`` when
    ``gamma = 0``).  Exact in distribution for any ``dt``.  The state stays in
    Fourier space; the noise is drawn there directly (the real-FFT symmetry is
    respected: the k = 0 and Nyquist modes are real, the rest complex), so a
    step costs one vector of normal deviates and two in-place multiply-adds;
    heights are synthesised by one inverse FFT only when they are needed.
``"euler"``
    Explicit Euler-Maruyama on the lattice (3- or 5-point Laplacian, noise
    per cell, conserved noise as the lattice divergence of per-bond noise).
    The reference to compare against: biased by ``1/(1 - gamma dt/2)`` and
    refused for ``dt >= 2 / (mu + 4 dim D0 / dx^2)``.

The exact scheme uses the spectral operator ``k^2`` (``operator="spectral"``,
the continuum equation truncated at the Nyquist wavenumber) or the lattice
operator ``kappa^2`` (``operator="lattice"``, the same equation the Euler
scheme discretises).  ``psd_theory`` in the result is always the exact
expectation for the operator that was integrated.

References
----------
.. [1] M. Schargott, V. L. Popov, Tribol. Int. 39 (2006) 431-436,
   doi:10.1016/j.triboint.2005.04.015.
.. [2] D. T. Gillespie, "Exact numerical simulation of the Ornstein-Uhlenbeck
   process and its integral", Phys. Rev. E 54 (1996) 2084,
   doi:10.1103/PhysRevE.54.2084.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from ...errors import ParameterError
from ...params import param, renamed, validate_dataclass
from ...progress import call_progress
from ..base import MethodRegistry, Result
from . import spectra

__all__ = [
    "TopographyParams",
    "SCHEMES",
    "evolve",
    "solve",
    "euler_dt_limit",
    "expected_periodogram",
    "wavevectors",
    "mode_ratios",
    "make_stepper",
]

#: Largest grid (points in total) accepted: keeps memory of the 6 work arrays < ~3 GB.
MAX_POINTS = 1 << 26


@renamed(n="grid_points", dx="pixel_size")  # old names kept (docs/conventions.md)
@dataclass(frozen=True)
class TopographyParams:
    """Parameters of Eq. 23 on a periodic grid (all SI).

    Parameters
    ----------
    dim : {1, 2}
        Profile (1) or surface (2).
    grid_points : int
        Grid points per side, even, >= 4.
    pixel_size : float
        Grid spacing (m).
    d0 : float
        Surface diffusion coefficient D0 (m^2/s), >= 0.
    dx_noise : float
        Conserved (flux) noise intensity Dx (m^3/s in 1D, m^4/s in 2D), >= 0.
    dz : float
        Deposition/detachment noise intensity Dz (m^3/s in 1D, m^4/s in 2D), >= 0.
    mu : float
        Wear rate constant (1/s), >= 0; 0 means no low-k plateau.
    l : float
        Step length multiplying the stochastic flux (m), > 0.
    correlation_length : float
        Noise correlation length l_c (m); 0 = delta-correlated (F~ = 1).
    dt : float
        Time step (s), > 0.
    steps : int
        Number of steps, >= 1.
    operator : {"spectral", "lattice"}
        Operator used by the exact scheme (Euler always uses the lattice).
    precision : {"double", "single"}
        Floating-point precision of the exact scheme's state and noise.
    """

    dim: int = param(1, choices=(1, 2), doc="1D profile or 2D surface.")
    grid_points: int = param(1024, lo=4, hi=1 << 26, doc="Grid points per side (even); old name n.")
    pixel_size: float = param(
        10e-9, unit="m", lo=0.0, lo_open=True, doc="Grid spacing; old name dx."
    )
    d0: float = param(1e-12, unit="m^2/s", lo=0.0, doc="Surface diffusion D0.")
    dx_noise: float = param(2.5e-20, unit="m^(2+dim)/s", lo=0.0, doc="Flux-noise intensity Dx.")
    dz: float = param(5.6e-20, unit="m^(2+dim)/s", lo=0.0, doc="Transfer-noise intensity Dz.")
    mu: float = param(10.0, unit="1/s", lo=0.0, doc="Wear rate constant.")
    l: float = param(50e-9, unit="m", lo=0.0, lo_open=True, doc="Step length of the flux noise.")
    correlation_length: float = param(0.0, unit="m", lo=0.0, doc="Noise correlation length l_c.")
    dt: float = param(1e-2, unit="s", lo=0.0, lo_open=True, doc="Time step.")
    steps: int = param(100, lo=1, doc="Number of time steps.")
    operator: str = param("spectral", choices=("spectral", "lattice"), doc="Exact-scheme operator.")
    precision: str = param("double", choices=("double", "single"), doc="Exact-scheme precision.")

    def __post_init__(self) -> None:
        validate_dataclass(self)
        if self.grid_points % 2:
            raise ParameterError(
                "grid_points", "an even number of grid points >= 4", self.grid_points
            )
        if self.grid_points**self.dim > MAX_POINTS:
            raise ParameterError(
                "grid_points",
                f"at most {MAX_POINTS} grid points in total (grid_points**dim)",
                self.grid_points,
            )

    # ---- derived quantities
    @property
    def length(self) -> float:
        """Side length L = n dx (m)."""
        return self.grid_points * self.pixel_size

    @property
    def duration(self) -> float:
        """Total time steps * dt (s)."""
        return self.steps * self.dt

    @property
    def shape(self) -> tuple[int, ...]:
        """Real-space grid shape."""
        return (self.grid_points,) * self.dim

    def theory_kwargs(self) -> dict[str, float]:
        """Keyword arguments of the :mod:`.spectra` theory functions."""
        return dict(d0=self.d0, dx_noise=self.dx_noise, dz=self.dz, mu=self.mu, l=self.l,
                    correlation_length=self.correlation_length)

    def crossovers(self) -> tuple[float, float]:
        """Crossover wavenumbers (k1, k2) (1/m); see :func:`.spectra.crossover_wavenumbers`."""
        kw = self.theory_kwargs()
        kw.pop("correlation_length")
        return spectra.crossover_wavenumbers(**kw)


def euler_dt_limit(p: TopographyParams) -> float:
    """Explicit stability limit 2 / (mu + 4 dim D0 / dx^2) (s) of the Euler scheme."""
    rate = p.mu + 4.0 * p.dim * p.d0 / p.pixel_size**2
    return math.inf if rate == 0 else 2.0 / rate


def wavevectors(p: TopographyParams) -> list[np.ndarray]:
    """Wavevector components (1/m) on the real-FFT grid, broadcastable to its shape."""
    if p.dim == 1:
        return [2 * np.pi * np.fft.rfftfreq(p.grid_points, p.pixel_size)]
    return [
        2 * np.pi * np.fft.fftfreq(p.grid_points, p.pixel_size)[:, None],
        2 * np.pi * np.fft.rfftfreq(p.grid_points, p.pixel_size)[None, :],
    ]


def _modes(p: TopographyParams, lattice: bool):
    """(|k|, operator eigenvalue k^2 or kappa^2) on the real-FFT grid."""
    kv = wavevectors(p)
    kmag = np.sqrt(sum(k**2 for k in kv))
    if lattice:
        k2 = sum(spectra.lattice_k2(k, p.pixel_size) for k in kv)
    else:
        k2 = kmag**2
    return np.broadcast_to(kmag, _spec_shape(p)), np.broadcast_to(k2, _spec_shape(p))


def _spec_shape(p: TopographyParams) -> tuple[int, ...]:
    return (p.grid_points,) * (p.dim - 1) + (p.grid_points // 2 + 1,)


def expected_periodogram(p: TopographyParams, t: float, *, lattice: bool, s0=None) -> np.ndarray:
    """Exact expectation of the periodogram (m^(dim+2)) on the real-FFT grid at time t (s).

    ``s0`` is the periodogram of the initial surface (default flat).
    """
    kmag, k2 = _modes(p, lattice)
    return spectra.transient_psd(kmag, t, k2=k2, s0=s0, **p.theory_kwargs())


def _psd_summary(p: TopographyParams, s_grid: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Positive-k PSD from a grid quantity: 1D as is, 2D radially averaged."""
    if p.dim == 1:
        return 2 * np.pi * np.fft.rfftfreq(p.grid_points, p.pixel_size)[1:], s_grid[..., 1:]
    k, avg, _ = spectra.radial_average(s_grid, p.grid_points, p.pixel_size)
    return k, avg


def _mean_square_dev(p: TopographyParams, s_grid: np.ndarray) -> float:
    """Return the expected Rq^2 (m^2) = (1/A) sum_{k != 0} S over the plane, from the rfft grid."""
    w = np.full(s_grid.shape, 2.0)
    w[..., 0] = 1.0
    w[..., -1] = 1.0
    total = float((w * s_grid).sum() - s_grid[(0,) * p.dim])
    return total / p.length**p.dim


def mode_ratios(p: TopographyParams, h, expected: np.ndarray) -> np.ndarray:
    """Periodogram / expectation for the statistically independent complex modes.

    Keeps the real-FFT modes that are neither self-conjugate nor the mirror
    of another kept mode (1D: 0 < k < k_N; 2D: columns 1 ... n/2-1), ordered by
    |k|, so that each ratio is Exp(1) distributed under the theory (see
    :func:`.spectra.psd_consistency`).  Modes with zero expectation are dropped.

    Parameters
    ----------
    h : array_like
        Heights (m), shape ``(replicas, *p.shape)`` or ``p.shape``.
    expected : ndarray
        Expected periodogram on the real-FFT grid (e.g. :func:`expected_periodogram`).
    """
    s = spectra.periodogram(np.asarray(h).reshape((-1,) + p.shape), p.pixel_size, p.dim)
    kmag = np.broadcast_to(np.sqrt(sum(k**2 for k in wavevectors(p))), _spec_shape(p))
    keep = np.zeros(_spec_shape(p), dtype=bool)
    keep[..., 1 : p.grid_points // 2] = True
    keep &= expected > 0
    order = np.argsort(kmag[keep], kind="stable")
    return (s[:, keep] / expected[keep])[:, order]


# ------------------------------------------------------------------ schemes

SCHEMES = MethodRegistry("topography scheme")


class _ExactOU:
    """Exact OU stepper in Fourier space (state ``hk``, shape (R, *rfft_shape))."""

    def __init__(self, p: TopographyParams, replicas: int, rng: np.random.Generator):
        self.p = p
        self.rng = rng
        self.lattice = p.operator == "lattice"
        self.real_dtype = np.float32 if p.precision == "single" else np.float64
        self.cplx_dtype = np.complex64 if p.precision == "single" else np.complex128
        gamma, q = self._rates()
        self.decay = np.exp(-gamma * p.dt).astype(self.real_dtype)
        self.amp = self._amplitude(p.dt, gamma, q)
        del gamma, q  # only decay and amp are kept: memory stays at ~3 grid arrays
        shape = (replicas,) + _spec_shape(p)
        self.hk = np.zeros(shape, dtype=self.cplx_dtype)
        # Normal deviates are written in place into this buffer, viewed as complex.
        self._buf = np.empty(shape + (2,), dtype=self.real_dtype)
        self._noise = self._buf.view(self.cplx_dtype)[..., 0]

    def _rates(self):
        """(gamma, q): mode decay rate (1/s) and DFT variance rate of every mode.

        q = 2 (Dz + Dx l^2 k^2) F~ n^dim/dx^dim.
        """
        p = self.p
        kmag, k2 = _modes(p, self.lattice)
        gamma = p.mu + p.d0 * k2
        q = (
            2.0
            * (p.dz + p.dx_noise * p.l**2 * k2)
            * spectra.noise_spectrum(kmag, p.correlation_length)
        )
        q *= p.grid_points**p.dim / p.pixel_size**p.dim
        return gamma, q

    def _amplitude(self, t: float, gamma, q) -> np.ndarray:
        """Per-mode noise amplitude for an interval t, scaled for the complex deviates."""
        with np.errstate(invalid="ignore"):
            var = np.where(q > 0, q * spectra._phi(gamma, t), 0.0)
        amp = np.sqrt(var / 2.0)  # complex deviate: E|xi|^2 = 2 with unit-variance parts
        # Self-conjugate modes (k = 0 and Nyquist) are real: their real part alone
        # must carry the full variance.
        for idx in self._self_conjugate():
            amp[idx] *= math.sqrt(2.0)
        return amp.astype(self.real_dtype)

    def _self_conjugate(self):
        n2 = self.p.grid_points // 2
        if self.p.dim == 1:
            return [(0,), (n2,)]
        return [(0, 0), (0, n2), (n2, 0), (n2, n2)]

    def _hermitize(self, x: np.ndarray) -> None:
        """Impose the real-FFT symmetry on complex noise ``x`` (R, *rfft_shape) in place."""
        n2 = self.p.grid_points // 2
        if self.p.dim == 1:
            x.imag[:, 0] = 0.0
            x.imag[:, n2] = 0.0
            return
        for c in (0, n2):
            x.imag[:, 0, c] = 0.0
            x.imag[:, n2, c] = 0.0
            # hat h(-k) = conj(hat h(k)) inside the k_y = 0 and Nyquist columns.
            x[:, : n2 : -1, c] = np.conj(x[:, 1:n2, c])

    def draw(self, amp: np.ndarray) -> np.ndarray:
        """Fresh symmetric complex noise times ``amp`` (overwrites the internal buffer)."""
        self.rng.standard_normal(out=self._buf, dtype=self.real_dtype)
        self._noise *= amp
        self._hermitize(self._noise)
        return self._noise

    def set_state(self, h0) -> None:
        if isinstance(h0, str):  # "stationary"
            gamma, q = self._rates()
            if np.any((gamma == 0) & (q > 0)):
                raise ParameterError("h0", "a surface array when mu = 0 (no stationary state)", h0)
            self.hk[...] = self.draw(self._amplitude(math.inf, gamma, q))
        elif h0 is not None:
            self.hk[...] = _rfft(self.p, h0)

    def step(self) -> None:
        self.hk *= self.decay
        self.hk += self.draw(self.amp)

    def heights(self) -> np.ndarray:
        return _irfft(self.p, self.hk)

    def periodogram(self) -> np.ndarray:
        hk = self.hk
        return (self.p.pixel_size**self.p.dim / self.p.grid_points**self.p.dim) * (
            hk.real**2 + hk.imag**2
        )


class _EulerFD:
    """Explicit Euler-Maruyama on the lattice (state ``h``, shape (R, n[, n]))."""

    lattice = True

    def __init__(self, p: TopographyParams, replicas: int, rng: np.random.Generator):
        limit = euler_dt_limit(p)
        if p.dt >= limit:
            raise ParameterError(
                "dt",
                f"a step below the explicit stability limit 2/(mu + 4*dim*D0/dx^2) = {limit:.4g} s "
                "(use scheme='exact' for large steps)",
                p.dt,
            )
        self.p = p
        self.rng = rng
        self.h = np.zeros((replicas,) + p.shape)
        self.axes = tuple(range(-p.dim, 0))
        vol = p.pixel_size**p.dim
        self.sz = math.sqrt(2.0 * p.dz * p.dt / vol)
        self.sx = p.l * math.sqrt(2.0 * p.dx_noise * p.dt / vol) / p.pixel_size
        self.filt = None
        if p.correlation_length > 0:
            kmag, _ = _modes(p, lattice=False)
            self.filt = np.sqrt(spectra.noise_spectrum(kmag, p.correlation_length))

    def set_state(self, h0) -> None:
        if isinstance(h0, str):
            raise ParameterError("h0", "an array or None for scheme 'euler'", h0)
        if h0 is not None:
            self.h[...] = _check_h0(self.p, h0)

    def _lap(self, h):
        out = -2.0 * self.p.dim * h
        for ax in self.axes:
            out += np.roll(h, 1, axis=ax) + np.roll(h, -1, axis=ax)
        return out / self.p.pixel_size**2

    def step(self) -> None:
        p, h = self.p, self.h
        noise = self.sz * self.rng.standard_normal(h.shape) if p.dz > 0 else np.zeros_like(h)
        if p.dx_noise > 0:
            for ax in self.axes:
                eta = self.rng.standard_normal(h.shape)  # flux noise on bond (j, j+1)
                noise += self.sx * (eta - np.roll(eta, 1, axis=ax))  # exactly mass conserving
        if self.filt is not None:
            noise = _irfft(p, _rfft(p, noise) * self.filt)
        h += p.dt * (p.d0 * self._lap(h) - p.mu * h) + noise

    def heights(self) -> np.ndarray:
        return self.h

    def periodogram(self) -> np.ndarray:
        return spectra.periodogram(self.h, self.p.pixel_size, self.p.dim)


SCHEMES.register("exact")(_ExactOU)
SCHEMES.register("euler")(_EulerFD)


def make_stepper(params: TopographyParams, *, rng: np.random.Generator, scheme: str = "exact",
                 replicas: int = 1, h0: Any = None):
    """Return a low-level stepper for callers that drive the time loop themselves.

    Returns an object with ``step()`` (advance by ``params.dt``; the exact
    scheme keeps the state in Fourier space and synthesises nothing),
    ``heights()`` (m, shape ``(replicas, *params.shape)``; one inverse FFT for
    the exact scheme) and ``periodogram()`` (real-FFT grid, m^(dim+2)).
    ``params.steps`` is ignored.  Used by the benchmark to time one step.
    """
    if not isinstance(rng, np.random.Generator):
        raise ParameterError("rng", "a numpy.random.Generator", type(rng).__name__)
    st = SCHEMES.get(scheme, "scheme")(params, int(replicas), rng)
    st.set_state(h0 if h0 is None or isinstance(h0, str) else _check_h0(params, h0))
    return st


def _rfft(p, h):
    return np.fft.rfft(h, axis=-1) if p.dim == 1 else np.fft.rfft2(h, axes=(-2, -1))


def _irfft(p, hk):
    if p.dim == 1:
        return np.fft.irfft(hk, n=p.grid_points, axis=-1)
    return np.fft.irfft2(hk, s=(p.grid_points, p.grid_points), axes=(-2, -1))


def _check_h0(p: TopographyParams, h0) -> np.ndarray:
    h0 = np.asarray(h0, dtype=float)
    if h0.shape[-p.dim :] != p.shape or h0.ndim > p.dim + 1:
        raise ParameterError(
            "h0", f"heights of shape {p.shape} (or (replicas, *{p.shape}))", h0.shape
        )
    if not np.all(np.isfinite(h0)):
        raise ParameterError("h0", "finite heights", "non-finite values")
    return h0


# ------------------------------------------------------------------ driver


def evolve(
    params: TopographyParams,
    *,
    rng: np.random.Generator,
    h0: Any = None,
    scheme: str = "exact",
    replicas: int = 1,
    record_steps: Any = None,
    progress: Any = None,
) -> Result:
    """Evolve Eq. 23 for ``params.steps`` steps of ``params.dt``.

    Parameters
    ----------
    params : TopographyParams
        Grid, rates and time stepping (SI).
    rng : numpy.random.Generator
        Source of all randomness.
    h0 : array_like, "stationary" or None
        Initial heights (m), shape ``params.shape`` (shared by all replicas)
        or ``(replicas, *params.shape)``; ``None`` starts flat;
        ``"stationary"`` draws the exact stationary state (exact scheme,
        requires ``mu + D0 k^2 > 0`` for every noisy mode).
    scheme : {"exact", "euler"}
        Integrator (see module docstring).
    replicas : int
        Independent surfaces evolved together; PSDs are averaged over them.
    record_steps : sequence of int, optional
        Steps (1 ... steps) after which the PSD and roughness are recorded in
        ``history`` (the running-in series).
    progress : callable, optional
        ``progress(fraction, what)``, called ~200 times over the steps (e.g.
        :class:`tribolmp.progress.Progress` or the chain's bar).

    Returns
    -------
    Result
        ``h`` (final heights, m; shape ``params.shape`` or ``(replicas, ...)``),
        ``k`` (1/m, positive), ``psd`` (m^(dim+2); replica-averaged, radially
        averaged in 2D), ``psd_theory`` (exact expectation of ``psd`` at the
        final time for the integrated operator), ``psd_stationary``,
        ``line_k``/``line_psd``/``line_psd_theory`` (2D: line scans along x),
        ``rq`` (replica-mean rms roughness, m), ``rq_theory`` (m),
        ``mean`` (replica-mean height, m), ``roughness`` (metrics of the
        first replica), ``k1``/``k2`` (crossovers, 1/m), ``t_s`` (final time),
        ``steps_per_s``, ``time_s``, ``nit`` and ``history`` (list of dicts
        with ``t_s, step, k, psd, psd_theory, rq, rq_theory``).
    """
    if not isinstance(params, TopographyParams):
        raise ParameterError("params", "a TopographyParams", type(params).__name__)
    if not isinstance(rng, np.random.Generator):
        raise ParameterError("rng", "a numpy.random.Generator", type(rng).__name__)
    replicas = (
        int(replicas)
        if isinstance(replicas, (int, np.integer)) and not isinstance(replicas, bool)
        else replicas
    )
    if not isinstance(replicas, int) or replicas < 1:
        raise ParameterError("replicas", "an integer >= 1", replicas)
    record = sorted({int(s) for s in (record_steps or ())})
    if record and (record[0] < 1 or record[-1] > params.steps):
        raise ParameterError("record_steps", f"steps in [1, {params.steps}]", record_steps)
    cls = SCHEMES.get(scheme, "scheme")
    p = params
    h0_arr = None
    if h0 is not None and not isinstance(h0, str):
        h0_arr = _check_h0(p, h0)
        if h0_arr.ndim == p.dim + 1 and h0_arr.shape[0] != replicas:
            raise ParameterError(
                "h0", f"{replicas} initial surfaces (one per replica)", h0_arr.shape[0]
            )
    elif isinstance(h0, str) and h0 != "stationary":
        raise ParameterError("h0", "an array, None or 'stationary'", h0)

    t_start = time.perf_counter()
    stepper = cls(p, replicas, rng)
    stepper.set_state(h0 if h0_arr is None else h0_arr)
    lattice = stepper.lattice
    # Expected periodogram of the initial state (deterministic h0; stationary draw is exact).
    s0 = None
    stationary_start = isinstance(h0, str)
    if h0_arr is not None:
        s0 = spectra.periodogram(h0_arr, p.pixel_size, p.dim)
        s0 = s0.reshape(-1, *s0.shape[-p.dim :]).mean(axis=0)

    def theory_grid(t):
        if stationary_start:
            return expected_periodogram(p, math.inf, lattice=lattice)
        return expected_periodogram(p, t, lattice=lattice, s0=s0)

    def snapshot(step):
        t = step * p.dt
        s_grid = stepper.periodogram().mean(axis=0)
        k, psd = _psd_summary(p, s_grid)
        th_grid = theory_grid(t)
        _, psd_th = _psd_summary(p, th_grid)
        h = stepper.heights()
        rq = float(np.sqrt(np.mean((h - h.mean(axis=tuple(range(1, h.ndim)), keepdims=True)) ** 2)))
        return dict(
            t_s=t,
            step=step,
            k=k,
            psd=psd,
            psd_theory=psd_th,
            rq=rq,
            rq_theory=math.sqrt(_mean_square_dev(p, th_grid)),
            s_grid=s_grid,
            th_grid=th_grid,
            h=h,
        )

    history = []
    rec = iter(record + [None])
    nxt = next(rec)
    loop_time = 0.0
    for i in range(1, p.steps + 1):
        t0 = time.perf_counter()
        stepper.step()
        loop_time += time.perf_counter() - t0
        call_progress(progress, i, p.steps, "Eq. 23 steps")
        if i == nxt:
            snap = snapshot(i)
            history.append(
                {k: snap[k] for k in ("t_s", "step", "k", "psd", "psd_theory", "rq", "rq_theory")}
            )
            nxt = next(rec)
    final = snapshot(p.steps)
    h = final["h"]
    res = Result(
        h=h[0] if replicas == 1 else h,
        k=final["k"],
        psd=final["psd"],
        psd_theory=final["psd_theory"],
        psd_stationary=_psd_summary(p, expected_periodogram(p, math.inf, lattice=lattice))[1],
        rq=final["rq"],
        rq_theory=final["rq_theory"],
        mean=float(h.mean()),
        roughness=spectra.roughness(h[0], p.pixel_size, p.dim),
        t_s=p.duration,
        dx=p.pixel_size,
        dim=p.dim,
        replicas=replicas,
        operator="lattice" if lattice else "spectral",
        scheme=scheme,
        history=history,
        steps_per_s=p.steps / loop_time if loop_time > 0 else math.inf,
        nit=p.steps,
        method=scheme,
    )
    k1, k2 = p.crossovers()
    res.k1, res.k2 = k1, k2
    if p.dim == 2:
        res.line_k, res.line_psd = spectra.line_scan_psd_theory(
            final["s_grid"], p.grid_points, p.pixel_size
        )
        _, res.line_psd_theory = spectra.line_scan_psd_theory(
            final["th_grid"], p.grid_points, p.pixel_size
        )
    res.units = {"h": "m", "k": "1/m", "psd": f"m^{p.dim + 2}", "psd_theory": f"m^{p.dim + 2}",
                 "psd_stationary": f"m^{p.dim + 2}", "rq": "m", "rq_theory": "m", "mean": "m",
                 "t_s": "s", "dx": "m", "k1": "1/m", "k2": "1/m", "line_psd": "m^3",
                 "line_psd_theory": "m^3", "steps_per_s": "1/s", "time_s": "s"}
    res.message = (f"{scheme} ({res.operator} operator): {p.steps} steps of {p.dt:.3g} s on "
                   f"{'x'.join(map(str, p.shape))} x {replicas} replicas")
    res.time_s = time.perf_counter() - t_start
    return res


def solve(params: TopographyParams, *, method: str = "exact", rng=None, **kwargs: Any) -> Result:
    """Model-contract alias of :func:`evolve` (``method`` is the scheme name)."""
    from ...rng import as_generator

    return evolve(params, rng=as_generator(rng), scheme=method, **kwargs)


def with_updates(params: TopographyParams, **changes: Any) -> TopographyParams:
    """Copy of ``params`` with fields replaced (validated again)."""
    return replace(params, **changes)
