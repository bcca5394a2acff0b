"""Coupled running-in: the part's own surface evolves by Eq. 23 while the contact feeds the rates.

The loop (issue 15, PHYSICS.md sections 4 and 8):

1. the initial surface is the part's (``[roughness]`` generated at its
   physical size and pixel, or a named height map);
2. the scene's sliding duration is cut into ``checkpoints`` equal intervals;
3. at the start of each interval the contact model solves the current
   surface at the scene's nominal pressure: the interfacial stiffness per
   unit area and, from the BEM, the real-contact fraction ``phi`` (MDR gives
   no area; ``phi`` is then estimated by
   :func:`~tribolmp.models.bridges.contact_fraction_estimate` and the
   recorded ``real_area_fraction`` is ``None``);
4. the Eq. 23 coefficients at the part (:func:`~tribolmp.models.bridges.rates_at_part`,
   factor ``phi V / V_MCA``) are held constant over the interval, and every
   Fourier mode is advanced by its exact Ornstein-Uhlenbeck transition
   (:mod:`tribolmp.models.topography.spde`, exact for any interval);
5. after the last interval the contact is solved once more.

The coupling is explicit in ``phi`` (first order in the checkpoint spacing):
:func:`checkpoint_convergence` reruns with half the spacing and reports the
change of the final Rq and stiffness, which the tests bound.

The expected periodogram is propagated alongside (the same piecewise-constant
coefficients, starting from the initial surface's periodogram), so the PSD at
every checkpoint can be compared with the Eq. 23 theory.

SI units throughout.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..errors import ParameterError
from ..params import param, validate_dataclass
from . import bridges
from .base import Result

#: Fewest BEM contact pixels for a real-contact fraction resolved to ~2 % per pixel (below this
#: the coupled loop is quantized by the pixel count, see :func:`running_in`).
MIN_CONTACT_PIXELS = 40
#: Relative L1 pressure change at which the checkpoint BEM stops (see :func:`contact_at_load`).
BEM_TOL = 1e-8

__all__ = [
    "BEM_TOL",
    "MIN_CONTACT_PIXELS",
    "RunInParams",
    "checkpoint_convergence",
    "contact_at_load",
    "part_surface",
    "running_in",
]


@dataclass(frozen=True)
class RunInParams:
    """Conditions of the part during running-in (SI).

    Parameters
    ----------
    duration : float
        Sliding time (s).
    sliding_velocity : float
        Sliding velocity of the part (m/s).
    normal_force : float
        Normal load (N).
    apparent_area : float
        Apparent (nominal) contact area (m^2).
    E_star : float
        Effective modulus E* (Pa).
    checkpoints : int
        Number of equal intervals of the duration.
    slab_thickness : float
        Thickness of the 2D MCA's slab (m), see :func:`~tribolmp.models.bridges.rates_at_part`.
    contact_method : {"mdr", "bem"}
        Contact model at every checkpoint.
    realizations : int
        MDR ensemble size.
    contact_seed : int
        Seed of the MDR ensemble, the same at every checkpoint (common random
        numbers: stiffness changes are then the surface's, not the draw's).
    phi_tolerance : float
        Between checkpoints the interval is cut into sub-steps so that the
        real-contact fraction changes by at most this fraction per sub-step
        (step halving); each sub-step is a predictor with ``phi`` at its start
        and a corrector with the mean of ``phi`` at both ends (Heun, second
        order in the sub-step).  A huge value (1e9) gives one step per checkpoint interval (the
        coupling then lags by a whole interval: first order in the spacing).
    """

    duration: float = param(0.05, unit="s", lo=0.0, lo_open=True, doc="Sliding time.")
    sliding_velocity: float = param(0.01, unit="m/s", lo=0.0, doc="Sliding velocity of the part.")
    normal_force: float = param(10.0, unit="N", lo=0.0, lo_open=True, doc="Normal load.")
    apparent_area: float = param(
        1e-6, unit="m^2", lo=0.0, lo_open=True, doc="Apparent contact area."
    )
    E_star: float = param(1.13e11, unit="Pa", lo=0.0, lo_open=True, doc="Effective modulus E*.")
    checkpoints: int = param(8, lo=1, hi=10_000, doc="Equal intervals of the duration.")
    slab_thickness: float = param(
        2.5e-9, unit="m", lo=0.0, lo_open=True, doc="MCA slab thickness w."
    )
    contact_method: str = param(
        "mdr", choices=("mdr", "bem"), doc="Contact model at the checkpoints."
    )
    realizations: int = param(16, lo=1, hi=100_000, doc="MDR ensemble size.")
    contact_seed: int = param(0, lo=0, hi=2**63 - 1, doc="Seed of the MDR ensemble.")
    phi_tolerance: float = param(
        0.05, lo=0.0, lo_open=True, doc="Largest relative change of phi per sub-step."
    )

    def __post_init__(self) -> None:
        validate_dataclass(self)

    @property
    def pressure(self) -> float:
        """Nominal pressure N / A0 (Pa)."""
        return self.normal_force / self.apparent_area


def part_surface(
    *,
    rms_height: float,
    hurst: float,
    rolloff_wavelength: float,
    short_cutoff_wavelength: float,
    grid_points: int,
    pixel_size: float,
    rng: np.random.Generator,
    surface_file: str = "",
    rescale: bool = True,
    surface_options: dict[str, Any] | None = None,
) -> tuple[np.ndarray, float, str]:
    """Return the part's initial surface: a height map, or ``[roughness]`` at its size and pixel.

    A generated surface is one Gaussian realisation of the self-affine PSD of
    the contact model (:func:`tribolmp.models.contact.rough.self_affine_psd`)
    on ``grid_points^2`` pixels of ``pixel_size``; with ``rescale`` it is
    scaled so that its Rq equals ``rms_height`` exactly (the scene gives the
    part's Rq, not an ensemble expectation: one realisation of a surface with a
    100 um roll-off on a 512 um map scatters by ~10 % in Rq).

    Returns
    -------
    heights : ndarray (m), pixel_size : float (m), source : str
    """
    from .contact.rough import generate_surface, self_affine_psd

    if surface_file:
        from .contact.solve import load_surface
        from .topography.measured import surface_provenance

        # A measured file (any SurfaceTopography format): units and pixel from its metadata,
        # [roughness].surface_* overrides only when given (issue 16); the source names which.
        opts = {k: v for k, v in (surface_options or {}).items() if v is not None}
        h, dx = load_surface(
            surface_file, opts.get("pixel_size"), unit=opts.get("unit"),
            detrend=opts.get("detrend", "none"), missing=opts.get("missing", "refuse"),
        )
        dx = pixel_size if dx is None else dx
        if h.shape[0] != h.shape[1] or h.shape[0] % 2:
            raise ParameterError(
                "[roughness].surface_file",
                "a square height map with an even side",
                f"shape {h.shape}",
            )
        return h, float(dx), "height map " + surface_provenance(surface_file, pixel_size, **opts)
    psd = self_affine_psd(rms_height, hurst, rolloff_wavelength, short_cutoff_wavelength)
    h = generate_surface(grid_points, pixel_size, psd, rng)
    if rescale:
        h = (h - h.mean()) * (rms_height / float(np.sqrt(np.mean((h - h.mean()) ** 2))))
    return (
        h,
        float(pixel_size),
        f"random [roughness] surface {grid_points}^2 x {pixel_size:g} m"
        + (", Rq rescaled to rms_height" if rescale else ""),
    )


def contact_at_load(
    h: np.ndarray,
    dx: float,
    *,
    E_star: float,
    pressure: float,
    method: str,
    realizations: int,
    seed: int,
    p0: np.ndarray | None = None,
) -> dict[str, Any]:
    """Solve a periodic patch at one nominal pressure: stiffness per area, contact fraction.

    ``method = "bem"``: the periodic BEM
    (:func:`~tribolmp.models.contact.bem.solve_bem`, the solver of contract C5's
    ``interfacial_stiffness``: stiffness of the cell / its area), which gives the
    area.  ``p0`` (a previous pressure field, e.g. the last checkpoint's) warm-starts
    it, and it stops at a relative pressure change of ``BEM_TOL`` = 1e-8: the
    stiffness and the area depend only on the converged contact set (measured
    identical to tol 1e-10 on the default surface, 41 -> 14 iterations warm).
    ``method = "mdr"``: the MDR ensemble of 1D profiles with the patch's
    spectrum; no area (``area_fraction`` None), ``phi`` from
    :func:`~tribolmp.models.bridges.contact_fraction_estimate`.

    Returns
    -------
    dict
        ``k_per_area`` (N/m^3), ``area_fraction`` (1 or None), ``phi`` (1,
        used for the rates), ``phi_source``, ``grad_rms`` (1), ``time_s``.
    """
    t0 = time.perf_counter()
    patch = h.shape[0] * h.shape[1] * dx * dx
    grad = bridges.rms_gradient(h, dx)
    p_field = None
    if method == "bem":
        from .contact.bem import solve_bem

        r = solve_bem(h, dx, E_star, pressure, periodic=True, tol=BEM_TOL, p0=p0)
        kpa, area, p_field = float(r.stiffness) / patch, float(r.area_fraction), r.p
        phi, src = area, "BEM real-contact fraction"
    elif method == "mdr":
        from .contact.solve import solve_rough

        r = solve_rough(
            h,
            dx,
            E_star,
            [pressure],
            method="mdr",
            realizations=realizations,
            rng=np.random.default_rng(seed),
        )
        kpa = float(np.asarray(r["stiffness"])[0]) / patch
        area = None
        phi = bridges.contact_fraction_estimate(pressure, E_star, grad)
        src = "estimate kappa p/(E* |grad h|_rms), kappa = 2 (MDR gives no area)"
    else:
        raise ParameterError("contact_method", "one of ['mdr', 'bem']", method)
    return {
        "k_per_area": kpa,
        "area_fraction": area,
        "phi": phi,
        "phi_source": src,
        "grad_rms": grad,
        "p": p_field,
        "time_s": time.perf_counter() - t0,
    }


def _radial(s_grid: np.ndarray, n: int, dx: float) -> tuple[np.ndarray, np.ndarray]:
    from .topography import spectra

    k, avg, _ = spectra.radial_average(s_grid, n, dx)
    return k, avg


def running_in(
    h0: np.ndarray,
    pixel_size: float,
    eq23: Mapping[str, Any],
    params: RunInParams,
    *,
    rng: np.random.Generator,
    mu_of_phi: Callable[[float], float] | None = None,
    correlation_length: float = 0.0,
    keep_surfaces: bool = False,
) -> Result:
    """Evolve the part's surface by Eq. 23 over the sliding duration, coupled to the contact.

    Parameters
    ----------
    h0 : ndarray, shape (n, n)
        Initial heights (m), periodic, ``n`` even.
    pixel_size : float
        Grid spacing (m).
    eq23 : mapping
        1D Eq. 23 coefficients at the MCA (:func:`~tribolmp.models.bridges.eq23_from_rates`).
    params : RunInParams
    rng : numpy.random.Generator
        Noise of Eq. 23.
    mu_of_phi : callable, optional
        Friction coefficient at a real-contact fraction (e.g. matched at the
        mean real pressure ``p / phi``); recorded per checkpoint.
    correlation_length : float
        Noise correlation length of Eq. 23 (m); 0 = delta-correlated.
    keep_surfaces : bool
        Also return the surface at every checkpoint (``surfaces``).

    Returns
    -------
    Result
        Arrays over the ``checkpoints + 1`` checkpoints (initial included):
        ``sliding_distance_m``, ``sliding_time_s`` (s; ``time_s`` is the wall
        time, as in every Result), ``rq_m``, ``normal_stiffness_N_m``
        (apparent contact, series with the punch), ``stiffness_per_area_N_m3``,
        ``real_area_fraction`` (None where MDR ran), ``phi`` (used),
        ``rate_factor``, ``mu`` (None without ``mu_of_phi``);
        ``k`` and ``psd`` / ``psd_theory`` (radially averaged, one row per
        checkpoint); ``h`` (final), ``theory_grid`` (final expected
        periodogram, real-FFT grid), ``stationary_grid`` (for the last
        interval's coefficients), ``topography_params`` (last interval),
        ``bound_N_m``, ``rq_initial_m``, ``rq_final_m``, ``domain_size_m``.
    """
    from .topography import spectra
    from .topography.spde import TopographyParams, evolve, expected_periodogram

    if not isinstance(params, RunInParams):
        raise ParameterError("params", "a RunInParams", type(params).__name__)
    h = np.asarray(h0, dtype=float)
    if h.ndim != 2 or h.shape[0] != h.shape[1] or h.shape[0] % 2 or h.shape[0] < 4:
        raise ParameterError("h0", "a square height map with an even side >= 4", f"shape {h.shape}")
    n, dx = h.shape[0], float(pixel_size)
    t0 = time.perf_counter()
    N = params.checkpoints
    dt = params.duration / N
    area = params.apparent_area
    bound = bridges.punch_bound(area, params.E_star)

    warm: dict[str, Any] = {"p": None}

    def record(hh):
        # Each checkpoint's BEM starts from the previous checkpoint's pressure field (the surface
        # changed little in between): the same converged contact, in fewer iterations.
        c = contact_at_load(
            hh,
            dx,
            E_star=params.E_star,
            pressure=params.pressure,
            method=params.contact_method,
            realizations=params.realizations,
            seed=params.contact_seed,
            p0=warm["p"],
        )
        warm["p"] = c.pop("p")
        c["k"] = bridges.apparent_contact_stiffness(c["k_per_area"], area, params.E_star)[
            "stiffness"
        ]
        return c

    s_theory = spectra.periodogram(h, dx, 2)
    rows: list[dict[str, Any]] = []
    psd, psd_th, surfaces = [], [], []
    tp = None
    contact_time = topo_time = 0.0
    substeps = rejected = 0
    sub_size = None
    for i in range(N + 1):
        c = record(h)
        contact_time += c["time_s"]
        rq = float(np.sqrt(np.mean((h - h.mean()) ** 2)))
        k_r, s_r = _radial(spectra.periodogram(h, dx, 2), n, dx)
        _, s_t = _radial(s_theory, n, dx)
        psd.append(s_r)
        psd_th.append(s_t)
        if keep_surfaces:
            surfaces.append(h.copy())
        part = bridges.rates_at_part(
            eq23,
            phi=c["phi"],
            velocity_m_s=params.sliding_velocity,
            slab_thickness_m=params.slab_thickness,
        )
        rows.append(
            {
                "time_s": i * dt,
                "rq": rq,
                "k": c["k"],
                "kpa": c["k_per_area"],
                "area": c["area_fraction"],
                "phi": c["phi"],
                "phi_source": c["phi_source"],
                "factor": part["factor"],
                "grad": c["grad_rms"],
                "mu": None if mu_of_phi is None else float(mu_of_phi(c["phi"])),
            }
        )
        if i == N:
            break
        t1 = time.perf_counter()
        # phi between checkpoints: the same estimate from the rms gradient (MDR), or the estimate
        # calibrated on this checkpoint's BEM area (ratio held until the next BEM solve).
        est0 = bridges.contact_fraction_estimate(params.pressure, params.E_star, c["grad_rms"])
        cal = c["phi"] / est0 if est0 > 0 else 1.0

        def phi_of(hh, cal=cal):
            return min(
                1.0,
                cal
                * bridges.contact_fraction_estimate(
                    params.pressure, params.E_star, bridges.rms_gradient(hh, dx)
                ),
            )

        left, sub, phi_now = dt, sub_size or dt, c["phi"]

        def step_params(phi: float, step: float) -> TopographyParams:
            """Eq. 23 of the part for one sub-step, rates moved to contact fraction ``phi``."""
            part = bridges.rates_at_part(eq23, phi=phi, velocity_m_s=params.sliding_velocity,
                                         slab_thickness_m=params.slab_thickness)
            return TopographyParams(
                dim=2, n=n, dx=dx, d0=part["d0"], dx_noise=part["dx_l2"], dz=part["dz"],
                mu=part["mu"], l=1.0, correlation_length=correlation_length, dt=step, steps=1,
            )

        while left > 1e-12 * dt:
            step = min(sub, left)
            tp = step_params(phi_now, step)
            h_try = np.asarray(evolve(tp, rng=rng, h0=h).h)
            phi_try = phi_of(h_try)
            change = abs(phi_try - phi_now) / max(phi_now, 1e-300)
            if change > params.phi_tolerance and step > dt / 2**20:
                sub = step / 2  # reject: phi moved too much within the step
                rejected += 1
                continue
            # Corrector (Heun in phi): redo the step with the mean of the fractions at its two ends,
            # so the coupling error is second order in the sub-step.
            phi_mid = 0.5 * (phi_now + phi_try)
            tp = step_params(phi_mid, step)
            h = np.asarray(evolve(tp, rng=rng, h0=h).h)
            # Expectation of the periodogram under the same piecewise-constant coefficients.
            s_theory = expected_periodogram(tp, step, lattice=False, s0=s_theory)
            left -= step
            substeps += 1
            phi_now = phi_of(h)
            sub = step * 2 if change < 0.5 * params.phi_tolerance else step
        sub_size = sub
        topo_time += time.perf_counter() - t1
    stationary = expected_periodogram(tp, math.inf, lattice=False) if tp is not None else None
    t_arr = np.array([r["time_s"] for r in rows])
    out = Result(
        sliding_distance_m=(params.sliding_velocity * t_arr).tolist(),
        sliding_time_s=t_arr.tolist(),
        rq_m=[r["rq"] for r in rows],
        normal_stiffness_N_m=[r["k"] for r in rows],
        stiffness_per_area_N_m3=[r["kpa"] for r in rows],
        real_area_fraction=[r["area"] for r in rows],
        phi=[r["phi"] for r in rows],
        phi_source=rows[0]["phi_source"],
        rms_gradient=[r["grad"] for r in rows],
        rate_factor=[r["factor"] for r in rows],
        mu=[r["mu"] for r in rows],
        k=k_r,
        psd=np.array(psd),
        psd_theory=np.array(psd_th),
        h=h,
        pixel_size_m=dx,
        theory_grid=s_theory,
        stationary_grid=stationary,
        topography_params=tp,
        surfaces=surfaces if keep_surfaces else None,
        bound_N_m=bound,
        rq_initial_m=rows[0]["rq"],
        rq_final_m=rows[-1]["rq"],
        domain_size_m=n * dx,
        contact_method=params.contact_method,
        checkpoints=N,
        substeps=substeps,
        rejected_substeps=rejected,
        contact_time_s=contact_time,
        topography_time_s=topo_time,
        nit=N,
        method=f"coupled Eq. 23 (exact OU) + {params.contact_method}",
        units={
            "sliding_distance_m": "m",
            "sliding_time_s": "s",
            "rq_m": "m",
            "normal_stiffness_N_m": "N/m",
            "stiffness_per_area_N_m3": "N/m^3",
            "real_area_fraction": "1",
            "phi": "1",
            "rate_factor": "1",
            "mu": "1",
            "k": "1/m",
            "psd": "m^4",
            "psd_theory": "m^4",
            "h": "m",
            "bound_N_m": "N/m",
            "rq_initial_m": "m",
            "rq_final_m": "m",
            "domain_size_m": "m",
            "pixel_size_m": "m",
        },
    )
    # The BEM area is a count of contact pixels: with few of them one pixel is a coarse step of
    # phi, and the calibration of phi between checkpoints (hence the wear rate) jumps by that step
    # from one checkpoint to the next.  Measured (docs/chain.md): 12 contact pixels (8 % per pixel,
    # 64^2 map at phi = 0.003) move the final Rq by 5-9 % when the spacing is halved; 48 pixels
    # (128^2) by < 0.3 %.  Said, never hidden.
    pixels = [None if r["area"] is None else r["area"] * n * n for r in rows]
    counted = [c for c in pixels if c is not None]
    out.contact_pixels_min = min(counted) if counted else None
    out.warnings = []
    if counted and min(counted) < MIN_CONTACT_PIXELS:
        out.warnings.append(
            f"BEM real-contact area of only {min(counted):.0f} pixels at a checkpoint (one pixel = "
            f"{100 / max(min(counted), 1):.0f} % of phi): the coupled rates are quantized; use a "
            f"map with >= {MIN_CONTACT_PIXELS} contact pixels for results converged in the spacing"
        )
    out.message = (
        f"{N} checkpoints over {params.duration:g} s "
        f"({params.sliding_velocity * params.duration:g} m slid): Rq {out.rq_initial_m:.3g} -> "
        f"{out.rq_final_m:.3g} m, k {rows[0]['k']:.3g} -> {rows[-1]['k']:.3g} N/m "
        f"(bound {bound:.3g} N/m)" + "".join("; " + w for w in out.warnings)
    )
    out.time_s = time.perf_counter() - t0
    return out


def checkpoint_convergence(
    h0: np.ndarray,
    pixel_size: float,
    eq23: Mapping[str, Any],
    params: RunInParams,
    *,
    seed: int,
    coarse: Result | None = None,
    **kwargs: Any,
) -> Result:
    """Relative change of the final Rq and stiffness when the checkpoint spacing is halved.

    Runs :func:`running_in` with ``checkpoints`` and ``2 checkpoints`` from the
    same initial surface (noise seeded by ``seed`` in both: the noise differs
    draw by draw, so the deltas include its sampling error, negligible when
    the initial roughness dominates the Eq. 23 noise).

    ``coarse``, when given, is the run at ``params`` already made (its noise
    stream need not be ``seed``'s), so only the fine run is computed.

    Returns
    -------
    Result
        ``rq_delta``, ``stiffness_delta`` (relative, 1), ``coarse``, ``fine`` (the two runs).
    """
    from dataclasses import replace

    if coarse is None:
        coarse = running_in(h0, pixel_size, eq23, params, rng=np.random.default_rng(seed), **kwargs)
    fine = running_in(
        h0,
        pixel_size,
        eq23,
        replace(params, checkpoints=2 * params.checkpoints),
        rng=np.random.default_rng(seed),
        **kwargs,
    )
    drq = abs(fine.rq_final_m - coarse.rq_final_m) / fine.rq_final_m
    dk = (
        abs(fine.normal_stiffness_N_m[-1] - coarse.normal_stiffness_N_m[-1])
        / fine.normal_stiffness_N_m[-1]
    )
    return Result(
        rq_delta=drq,
        stiffness_delta=dk,
        coarse=coarse,
        fine=fine,
        checkpoints=(params.checkpoints, 2 * params.checkpoints),
        units={"rq_delta": "1", "stiffness_delta": "1"},
        message=f"halving the spacing ({params.checkpoints} -> {2 * params.checkpoints}): "
        f"final Rq changes by {drq:.2e}, stiffness by {dk:.2e}",
    )
