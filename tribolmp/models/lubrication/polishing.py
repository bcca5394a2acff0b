"""Lubricated polishing: abrasive particles in a lubricant film between a pad and a workpiece (SI).

After the seed's Section 4 and its ref. [7] (Popov & Filippov 2005), in a
quasi-static, mean-field form that separates the three time scales (squeeze
out ~us, particle transit ~ms, polishing ~s-min):

1. **Particles.**  Each step, N_p = phi A / (pi a^2) rigid spherical particles
   of radius a are placed on randomly chosen lines y_i (rng supplied by the
   caller).  Between two steps a particle slides much farther than the
   periodic map is long (v dt >> L), so it visits every x of its line for
   an equal share of time: its action is averaged along the line.
2. **Contact.**  A rigid flat pad at height Z presses every particle onto the
   workpiece; a particle at (x, y_i) on local height z indents the (elastic,
   E*) workpiece by delta = z + 2a - Z and carries the Hertz force
   (4/3) E* a^(1/2) delta^(3/2).  Z follows from the load balance
   sum_i <F_i>_x = p A (monotone, bracketed root).  Only the high spots
   carry load, which is why the peaks are removed first.
3. **Pair law (lubricant).**  When a particle enters under the pad, the
   lubricant film of thickness h_f beneath it must be squeezed out to the
   rupture thickness h_c before it touches.  The Eq. 13 pair law integrated
   over the particle and the plane (:func:`~.pairlaw.pairlaw_sphere_plane_exact`,
   reproduced by the ring quadrature to < 1 %) gives
   F = alpha V / (h (1 + h/2a)), alpha = 6 pi eta a^2, so under its load F
   the squeeze-out takes t_s = alpha ln[h_f (h_c + 2a) / (h_c (h_f + 2a))] / F.
   During t_s the load goes through the film and nothing is removed; a
   particle stays under the pad for t_r = L_pad / v, so it removes material
   only in the fraction f = max(0, 1 - t_s / t_r) of its passage.
4. **Removal (Archard).**  Volume k F v f dt / n is taken from each pixel of
   the particle's line (n pixels per line; bilinear weights across lines,
   volume conserving).
5. **Sub-steps.**  Each output step is subdivided so that the non-uniform part
   of the cut stays below ``max_cut`` times max(Sq, Hertz indentation); larger
   cuts would dig grooves along the particle lines instead of removing peaks.

Preston's law (removal rate = k p v) therefore holds while t_s << t_r, by
construction: with f = 1 the Archard sum is k v sum F = k v p A because the
load balance is enforced, so it is *not* a test of the model.  What the
model predicts is the roughness evolution and the loss of removal when the
film carries part of the load; both are checked in the tests against
:func:`polish_resolved`, a particle-resolved simulation of the same step
(every particle at its own position, the pad's load balance solved for the
instantaneous configuration instead of the line average).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...errors import ParameterError
from ...params import param, validate_dataclass
from ...rng import as_generator
from ..base import Result, timed
from .reference import damper_coefficient

__all__ = [
    "PolishParams",
    "polish",
    "polish_resolved",
    "self_affine_surface",
    "squeeze_out_time",
    "params_from_scene",
]


@dataclass(frozen=True)
class PolishParams:
    """Lubricated polishing of a periodic workpiece (SI units).

    Attributes
    ----------
    grid_points : int
        Points per side of the workpiece height map.
    pixel_size : float
        Grid spacing (m).
    rms_height : float
        Initial rms roughness Sq (m) of the generated workpiece.
    hurst : float
        Hurst exponent of the generated workpiece.
    rolloff_wavelength : float
        Roll-off wavelength of the generated workpiece (m).
    particle_radius : float
        Abrasive particle radius a (m).
    particle_fraction : float
        Areal fraction phi of particles.
    archard_coefficient : float
        k in dh/dt = k p v (1/Pa).
    pressure : float
        Nominal pressure p (Pa).
    sliding_velocity : float
        Sliding velocity v (m/s).
    duration : float
        Polishing time (s).
    steps : int
        Time steps.
    viscosity : float
        Lubricant viscosity eta (Pa s).
    film_thickness : float
        Lubricant layer h_f a particle must squeeze out (m).
    film_cutoff : float
        Film rupture thickness h_c (m).
    pad_length : float
        Path length L a particle spends under the pad (m).
    E_star : float
        Effective modulus of particle/workpiece contact (Pa).
    max_cut : float
        Largest non-uniform part of the depth removed in one sub-step (max minus
        mean of the cut), as a fraction of the larger of
        the current Sq and the mean Hertz indentation of the loaded particles
        (steps are subdivided automatically; ``nit`` counts the sub-steps).
    """

    grid_points: int = param(64, lo=8, hi=4096)
    pixel_size: float = param(2e-6, unit="m", lo=0.0, lo_open=True, hi=1.0)
    rms_height: float = param(0.5e-6, unit="m", lo=0.0, lo_open=True, hi=1e-2)
    hurst: float = param(0.8, lo=0.0, hi=1.0, lo_open=True)
    rolloff_wavelength: float = param(32e-6, unit="m", lo=0.0, lo_open=True, hi=10.0)
    particle_radius: float = param(1e-6, unit="m", lo=0.0, lo_open=True, hi=1e-2)
    particle_fraction: float = param(0.05, lo=0.0, hi=0.6, lo_open=True)
    archard_coefficient: float = param(1e-13, unit="1/Pa", lo=0.0, lo_open=True, hi=1e-3)
    pressure: float = param(1e5, unit="Pa", lo=0.0, lo_open=True, hi=1e10)
    sliding_velocity: float = param(0.5, unit="m/s", lo=0.0, lo_open=True, hi=1e3)
    duration: float = param(60.0, unit="s", lo=0.0, lo_open=True, hi=1e7)
    steps: int = param(100, lo=1, hi=10**6)
    viscosity: float = param(0.1, unit="Pa s", lo=0.0, lo_open=True, hi=1e9)
    film_thickness: float = param(1e-6, unit="m", lo=0.0, lo_open=True, hi=1.0)
    film_cutoff: float = param(1e-9, unit="m", lo=0.0, lo_open=True, hi=1e-3)
    pad_length: float = param(1e-3, unit="m", lo=0.0, lo_open=True, hi=10.0)
    E_star: float = param(1.13e11, unit="Pa", lo=0.0, lo_open=True, hi=1e13)
    max_cut: float = param(0.05, lo=0.0, lo_open=True, hi=1.0)

    def __post_init__(self) -> None:
        validate_dataclass(self)
        if self.film_cutoff >= self.film_thickness:
            raise ParameterError(
                "film_cutoff", f"< film_thickness ({self.film_thickness:g} m)", self.film_cutoff
            )

    @property
    def area(self) -> float:
        """Workpiece area A (m^2)."""
        return (self.grid_points * self.pixel_size) ** 2

    @property
    def n_particles(self) -> int:
        """Particles per step, phi A / (pi a^2), at least 1."""
        return max(
            1, int(round(self.particle_fraction * self.area / (math.pi * self.particle_radius**2)))
        )


def self_affine_surface(n, dx, rms, hurst, rolloff, rng) -> np.ndarray:
    """Random periodic self-affine height map (m), zero mean, rms ``rms``.

    PSD ~ 1 for q < q_r = 2 pi / rolloff and ~ (q/q_r)^(-2(1+H)) above, up to the
    grid's Nyquist wavenumber; Gaussian random phases from ``rng``.
    """
    q = 2.0 * math.pi * np.fft.fftfreq(n, d=dx)
    qx, qy = np.meshgrid(q, q, indexing="ij")
    qq = np.hypot(qx, qy)
    qr = 2.0 * math.pi / rolloff
    amp = (qr / np.maximum(qq, qr)) ** (1.0 + hurst)
    amp[0, 0] = 0.0
    noise = rng.standard_normal((n, n))
    h = np.real(np.fft.ifft2(np.fft.fft2(noise) * amp))
    h -= h.mean()
    return h * (rms / h.std())


def squeeze_out_time(radius, viscosity, load, film, cutoff):
    """Time (s) for a particle to squeeze the film from ``film`` to ``cutoff``.

    The particle is under ``load`` (N); film and cutoff thicknesses in m.

    Exact for the integrated pair law F = alpha V / (h (1 + h/2a)):
    t = alpha ln[film (cutoff + 2a) / (cutoff (film + 2a))] / F with alpha = 6 pi eta a^2.
    """
    alpha = damper_coefficient(radius, viscosity)  # 6 pi eta a^2, the pair-law prefactor
    two_a = 2.0 * radius
    with np.errstate(divide="ignore"):
        return (
            alpha
            * math.log(film * (cutoff + two_a) / (cutoff * (film + two_a)))
            / np.asarray(load, dtype=float)
        )


def _pad_height(z_lines, a, E_star, load_per_line_sum):
    """Pad height Z (m) such that sum over lines of the line-mean Hertz force = load (N).

    ``z_lines`` has shape (N_p, n): the heights seen along each particle's line.
    Returns Z and the forces F (N) of shape (N_p, n).
    """
    from scipy.optimize import brentq

    top = float(z_lines.max()) + 2.0 * a
    c = 4.0 / 3.0 * E_star * math.sqrt(a)
    n = z_lines.shape[1]

    def forces(Z):
        return c * np.clip(z_lines + 2.0 * a - Z, 0.0, None) ** 1.5

    # a single loaded pixel carrying n * load bounds the pad's lowest position
    delta1 = (n * load_per_line_sum / c) ** (2.0 / 3.0)
    Z = brentq(
        lambda Z: float(forces(Z).sum()) / n - load_per_line_sum,
        top - 1.001 * delta1,
        top,
        xtol=1e-18,
        rtol=1e-15,
    )
    return Z, forces(Z)


def polish(params: PolishParams, *, rng, h0=None, snapshots: int = 5) -> Result:
    """Simulate lubricated polishing and return roughness against time.

    Parameters
    ----------
    params : PolishParams
    rng : numpy.random.Generator
        Source of particle positions (and of the initial surface if ``h0`` is None).
    h0 : ndarray, optional
        Initial workpiece height map (m), shape (grid_points, grid_points).
    snapshots : int
        Number of height maps kept (evenly spaced in time, including start and end).

    Returns
    -------
    Result
        ``t`` (s), ``sq`` (rms roughness, m), ``sa`` (mean absolute deviation, m),
        ``removed_volume`` (m^3, cumulative from the Archard sum),
        ``volume_change`` (m^3, from the height maps), ``mass_balance_error``
        (relative), ``removal_rate`` (m/s, mean depth rate), ``preston_rate``
        (k p v, m/s), ``contact_fraction`` (load-weighted f), ``h`` (final map, m),
        ``snapshots`` (list of maps), ``snapshot_t`` (s), ``load_error`` (relative).
    """
    rng = as_generator(rng)
    p = params
    n, dx, a = p.grid_points, p.pixel_size, p.particle_radius
    if h0 is None:
        h = self_affine_surface(n, dx, p.rms_height, p.hurst, p.rolloff_wavelength, rng)
    else:
        h = np.array(h0, dtype=float)
        if h.shape != (n, n) or not np.all(np.isfinite(h)):
            raise ParameterError("h0", f"a finite ({n}, {n}) height map", getattr(h0, "shape", h0))
    load = p.pressure * p.area
    dt = p.duration / p.steps
    t_r = p.pad_length / p.sliding_velocity
    c_hertz = 4.0 / 3.0 * p.E_star * math.sqrt(a)
    res = Result(method="mean-field-pairlaw-archard")
    t = np.linspace(0.0, p.duration, p.steps + 1)
    sq, sa, removed, vol, fc, load_err = (np.zeros(p.steps + 1) for _ in range(6))
    sq[0], sa[0] = h.std(), np.mean(np.abs(h - h.mean()))
    nsub = 0
    vol[0] = h.sum() * dx * dx
    snap_at = set(
        np.unique(np.linspace(0, p.steps, max(2, snapshots)).round().astype(int)).tolist()
    )
    snaps, snap_t = [h.copy()], [0.0]
    with timed(res):
        for k in range(1, p.steps + 1):
            # Sub-steps keep the deepest local cut per sub-step below max_cut * Sq: a
            # too-large step would dig grooves along the particle lines instead of
            # removing peaks (the removal is linear in the sub-step, so it is rescaled).
            left, removed[k], fsum, wsum = dt, removed[k - 1], 0.0, 0.0
            while left > 0:
                fy = rng.uniform(0.0, n, p.n_particles)  # line coordinate in pixels
                j0 = np.floor(fy).astype(int) % n
                j1 = (j0 + 1) % n
                ty = (fy - np.floor(fy))[:, None]
                z_lines = (1.0 - ty) * h[:, j0].T + ty * h[
                    :, j1
                ].T  # (N_p, n) heights along each line
                Z, F = _pad_height(z_lines, a, p.E_star, load)
                load_err[k] = max(load_err[k], abs(F.sum() / n / load - 1.0))
                f = np.zeros_like(F)
                loaded = F > 0
                ts = squeeze_out_time(a, p.viscosity, F[loaded], p.film_thickness, p.film_cutoff)
                f[loaded] = np.clip(1.0 - ts / t_r, 0.0, 1.0)
                rate = (
                    p.archard_coefficient * F * p.sliding_velocity * f / n
                )  # Archard volume rate per (line, pixel)
                cut = np.zeros_like(h)
                np.add.at(cut, (slice(None), j0), ((1.0 - ty) * rate).T / (dx * dx))
                np.add.at(cut, (slice(None), j1), (ty * rate).T / (dx * dx))
                # the cut per sub-step must be small against the roughness or, once the
                # surface is smooth, against the Hertz indentation over which the load spreads
                delta = float(np.sum(F * (F / c_hertz) ** (2.0 / 3.0)) / F.sum())
                limit = p.max_cut * max(h.std(), delta)
                # only the non-uniform part of the cut changes the topography
                dev = float(cut.max() - cut.mean())
                step = left if dev * left <= limit else max(limit / dev, dt * 1e-6)
                step = min(step, left)
                h -= cut * step
                removed[k] += rate.sum() * step
                fsum += float(np.sum(F * f) / F.sum()) * step
                wsum += step
                left -= step
                nsub += 1
            fc[k] = fsum / wsum
            vol[k] = h.sum() * dx * dx
            sq[k], sa[k] = h.std(), np.mean(np.abs(h - h.mean()))
            if k in snap_at:
                snaps.append(h.copy())
                snap_t.append(float(t[k]))
    change = vol[0] - vol
    mb = (
        float(abs(change[-1] - removed[-1]) / removed[-1])
        if removed[-1] > 0
        else float(abs(change[-1]))
    )
    res.update(
        t=t,
        sq=sq,
        sa=sa,
        removed_volume=removed,
        volume_change=change,
        mass_balance_error=mb,
        removal_rate=float(removed[-1] / (p.area * p.duration)),
        preston_rate=p.archard_coefficient * p.pressure * p.sliding_velocity,
        contact_fraction=float(np.mean(fc[1:])),
        load_error=float(load_err[1:].max()),
        h=h,
        pixel_size=dx,
        snapshots=snaps,
        snapshot_t=np.array(snap_t),
        n_particles=p.n_particles,
        nit=nsub,
        units={
            "t": "s",
            "sq": "m",
            "sa": "m",
            "removed_volume": "m^3",
            "volume_change": "m^3",
            "removal_rate": "m/s",
            "preston_rate": "m/s",
            "h": "m",
            "pixel_size": "m",
            "snapshot_t": "s",
        },
        message=f"{p.steps} output steps ({nsub} sub-steps), "
                f"{p.n_particles} particles per sub-step",
    )
    return res


def _pad_heights_many(z, a, E_star, load):
    """Pad heights Z_m (m) of every row m of ``z``, by bisection.

    Each solves sum_i c (z_mi + 2a - Z_m)_+^1.5 = load.
    """
    c = 4.0 / 3.0 * E_star * math.sqrt(a)
    top = z.max(axis=1) + 2.0 * a
    # one particle carrying the whole load bounds the pad's lowest position
    lo = top - 1.001 * (load / c) ** (2.0 / 3.0)
    hi = top.copy()
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        f = c * np.clip(z + 2.0 * a - mid[:, None], 0.0, None) ** 1.5
        over = f.sum(axis=1) > load
        lo = np.where(over, mid, lo)
        hi = np.where(over, hi, mid)
    Z = 0.5 * (lo + hi)
    return Z, c * np.clip(z + 2.0 * a - Z[:, None], 0.0, None) ** 1.5


def polish_resolved(params: PolishParams, *, rng, h0=None, positions: int | None = None) -> Result:
    """Particle-resolved reference of :func:`polish`: every particle at its own position.

    Each sub-step draws the same N_p particles as the mean-field model (random
    lines y_i) with random starting points x_i, and follows them through one
    passage of the periodic map in ``positions`` equal moves (default one per
    pixel).  At each move the pad height is solved for the *instantaneous*
    configuration (sum_i F_i = p A over the N_p particles, Hertz per particle,
    heights and removal bilinear in x and y), the squeeze-out fraction
    f = 1 - t_s(F_i)/t_r is taken per particle and force, and the Archard
    volume k F_i v f_i is removed at the particle's position.  The mean-field
    model instead balances the load of the line-averaged forces; nothing else
    differs, so the comparison isolates that approximation.  Sub-steps follow
    the same ``max_cut`` rule.  Slow (O(N_p n) per sub-step with a vectorised
    bisection); for tests and benchmarks.
    """
    rng = as_generator(rng)
    p = params
    n, dx, a = p.grid_points, p.pixel_size, p.particle_radius
    if h0 is None:
        h = self_affine_surface(n, dx, p.rms_height, p.hurst, p.rolloff_wavelength, rng)
    else:
        h = np.array(h0, dtype=float)
        if h.shape != (n, n) or not np.all(np.isfinite(h)):
            raise ParameterError("h0", f"a finite ({n}, {n}) height map", getattr(h0, "shape", h0))
    M = n if positions is None else int(positions)
    load = p.pressure * p.area
    dt = p.duration / p.steps
    t_r = p.pad_length / p.sliding_velocity
    c_hertz = 4.0 / 3.0 * p.E_star * math.sqrt(a)
    t = np.linspace(0.0, p.duration, p.steps + 1)
    sq, removed, fc = np.zeros(p.steps + 1), np.zeros(p.steps + 1), np.zeros(p.steps + 1)
    sq[0] = h.std()
    res = Result(method="particle-resolved-pairlaw-archard")
    nsub = 0
    Np = p.n_particles
    with timed(res):
        for k in range(1, p.steps + 1):
            left, removed[k], fsum, wsum = dt, removed[k - 1], 0.0, 0.0
            while left > 0:
                fy = rng.uniform(0.0, n, Np)
                fx0 = rng.uniform(0.0, n, Np)
                fx = (fx0[None, :] + np.arange(M)[:, None] * (n / M)) % n  # (M, Np)
                i0 = np.floor(fx).astype(int) % n
                i1 = (i0 + 1) % n
                tx = fx - np.floor(fx)
                j0 = np.floor(fy).astype(int) % n
                j1 = (j0 + 1) % n
                ty = np.broadcast_to(fy - np.floor(fy), fx.shape)
                J0, J1 = np.broadcast_to(j0, fx.shape), np.broadcast_to(j1, fx.shape)
                z = ((1 - tx) * (1 - ty) * h[i0, J0] + tx * (1 - ty) * h[i1, J0]
                     + (1 - tx) * ty * h[i0, J1] + tx * ty * h[i1, J1])
                _, F = _pad_heights_many(z, a, p.E_star, load)
                f = np.zeros_like(F)
                loaded = F > 0
                ts = squeeze_out_time(a, p.viscosity, F[loaded], p.film_thickness, p.film_cutoff)
                f[loaded] = np.clip(1.0 - ts / t_r, 0.0, 1.0)
                rate = (
                    p.archard_coefficient * F * p.sliding_velocity * f / M
                )  # volume rate per (move, particle)
                cut = np.zeros_like(h)
                for wgt, ii, jj in (((1 - tx) * (1 - ty), i0, J0), (tx * (1 - ty), i1, J0),
                                    ((1 - tx) * ty, i0, J1), (tx * ty, i1, J1)):
                    np.add.at(cut, (ii.ravel(), jj.ravel()), (wgt * rate).ravel() / (dx * dx))
                Fl = F[loaded]
                delta = float(np.sum(Fl * (Fl / c_hertz) ** (2.0 / 3.0)) / Fl.sum())
                limit = p.max_cut * max(h.std(), delta)
                dev = float(cut.max() - cut.mean())
                step = left if dev * left <= limit else max(limit / dev, dt * 1e-6)
                step = min(step, left)
                h -= cut * step
                removed[k] += rate.sum() * step
                fsum += float(np.sum(F * f) / F.sum()) * step
                wsum += step
                left -= step
                nsub += 1
            fc[k] = fsum / wsum
            sq[k] = h.std()
    res.update(
        t=t,
        sq=sq,
        removed_volume=removed,
        h=h,
        removal_rate=float(removed[-1] / (p.area * p.duration)),
        preston_rate=p.archard_coefficient * p.pressure * p.sliding_velocity,
        contact_fraction=float(np.mean(fc[1:])),
        nit=nsub,
        positions=M,
        units={
            "t": "s",
            "sq": "m",
            "removed_volume": "m^3",
            "removal_rate": "m/s",
            "preston_rate": "m/s",
            "h": "m",
        },
        message=f"{p.steps} output steps ({nsub} sub-steps), "
                f"{Np} particles x {M} positions per sub-step",
    )
    return res


def params_from_scene(scene, **overrides) -> PolishParams:
    """Build :class:`PolishParams` from the scene.

    Sections read: ``[polishing]``, ``[lubricant]``, ``[roughness]``, ``[geometry]``.

    Missing optional sections fall back to the :class:`PolishParams` defaults;
    keyword ``overrides`` replace single fields (e.g. ``grid_points`` for a quick run).
    """
    kw: dict = {}
    pol = scene.polishing
    if pol is not None:
        kw.update(
            particle_radius=pol.particle_radius,
            particle_fraction=pol.particle_fraction,
            archard_coefficient=pol.archard_coefficient,
            pressure=pol.pressure,
            sliding_velocity=pol.sliding_velocity,
            duration=pol.duration,
        )
    if scene.lubricant is not None:
        kw.update(
            viscosity=scene.lubricant.viscosity, film_thickness=scene.lubricant.film_thickness
        )
    rough = scene.roughness
    if rough is not None:
        kw.update(
            rms_height=rough.rms_height,
            hurst=rough.hurst,
            pixel_size=rough.pixel_size,
            grid_points=min(rough.grid_points, 128),
            rolloff_wavelength=rough.rolloff_wavelength,
        )
    kw.update(pad_length=scene.geometry.apparent_length, E_star=scene.effective_modulus)
    kw.update(overrides)
    return PolishParams(**kw)
