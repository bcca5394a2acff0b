"""Eq. 23 parameters from physical rates (the nanoscale model's ``rates.json``) or a scene.

Mapping and its assumptions
---------------------------
The surface is pictured as blocks of size ``l`` (the elementary step length,
``step_length_m``) piled in columns on a lattice of spacing ``l`` in ``d``
dimensions (d = 1 profile, d = 2 surface).  A block hops to one of the ``2d``
neighbour columns once per step time ``tau`` (``step_time_s``), and blocks are
detached or re-attached at a site with frequency ``nu_z = 1/tau_z``.  Matching
the variance of these discrete events to the continuum noise
``<f f> = 2 D delta`` of a cell of volume ``l^d`` gives

* ``D0 = diffusion_m2_s`` (measured lateral diffusion) or, when it is missing
  or zero, the random-walk value ``l^2 / (2 d tau)`` (the seed's
  ``D ~ l^2/tau`` up to the lattice factor);
* ``Dx = l^(d+2) / (2 d tau)``: one hop carries a height ``l`` across a bond,
  bonds see ``1/(d tau)`` hops per second;
* ``Dz = l^(d+2) nu_z / 2`` (the seed's Eq. 22, ``Dz = l^2/tau_z``, with the
  cell volume and the factor 2 of the noise convention) where
  ``nu_z = detachment_rate + reattachment_rate`` (1/s) when given, otherwise
  ``transfer_rate`` (1/m) times the sliding velocity (m/s);
* ``mu = wear_rate`` (1/s), or ``detachment_rate`` when no wear rate is given.

With these, the high-k plateau ``Dx l^2 / D0`` equals ``l^(d+2)`` when ``D0``
is the random-walk value: height fluctuations of about one block at the block
scale.  ``Dx`` and ``Dz`` therefore carry units m^3/s in 1D and m^4/s in 2D.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from ...errors import ParameterError
from ...records import Rates
from .spde import TopographyParams

__all__ = ["params_from_rates", "params_from_scene"]


def _rate(rates: Mapping[str, Any], key: str, *, required: bool = False, positive: bool = False):
    if key not in rates or rates[key] is None:
        if required:
            raise ParameterError(f"rates.{key}", "a value (missing from the rates)", None)
        return None
    v = rates[key]
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or v < 0 or (positive and v == 0):
        raise ParameterError(f"rates.{key}", "a finite number " + ("> 0" if positive else ">= 0"), v)
    return float(v)


_C1 = ("mu_per_s", "d0_m2_s", "dz", "dx_l2")


def _has_c1(rates: Mapping[str, Any]) -> bool:
    """All four Eq. 23 coefficients of contract C1 given (not null, not flagged invalid)."""
    valid = rates.get("valid") if isinstance(rates.get("valid"), Mapping) else {}
    flagged = set(rates.get("flagged") or ())
    return all(rates.get(k) is not None and valid.get(k) is not False and k not in flagged for k in _C1)


def _drives_eq23(rates: Mapping[str, Any]) -> bool:
    """Whether a rates mapping can parameterise Eq. 23: C1 coefficients, or the legacy l and tau."""
    return _has_c1(rates) or (rates.get("step_length_m") is not None and rates.get("step_time_s") is not None)


def params_from_rates(
    rates: Mapping[str, Any],
    *,
    dim: int = 1,
    n: int = 1024,
    dx: float | None = None,
    duration: float | None = None,
    steps: int = 200,
    correlation_length: float = 0.0,
    sliding_velocity: float | None = None,
    operator: str = "spectral",
) -> TopographyParams:
    """Build :class:`TopographyParams` from nanoscale rates (see the module docstring).

    Parameters
    ----------
    rates : Rates or mapping
        The shared :class:`~tribolmp.records.Rates` record or ``rates.json`` content: ``step_length_m`` (m) and ``step_time_s`` (s)
        are required; ``diffusion_m2_s`` (m^2/s), ``wear_rate``,
        ``detachment_rate``, ``reattachment_rate`` (1/s) and
        ``transfer_rate`` (1/m) are used when present.  Other keys are ignored.
    dim, n : int
        Dimension and grid points per side.
    dx : float, optional
        Grid spacing (m); default the step length ``l``.
    duration : float, optional
        Evolution time (s); default ``5/mu`` (the slowest mode's PSD is then
        within exp(-10) of stationary), or ``1000 tau`` when ``mu = 0``.
    steps : int
        Number of time steps (the exact scheme is exact for any step).
    correlation_length : float
        Noise correlation length (m).
    sliding_velocity : float, optional
        Sliding velocity (m/s) turning ``transfer_rate`` into a frequency.
    operator : {"spectral", "lattice"}
        Operator of the exact scheme.

    Returns
    -------
    TopographyParams
    """
    if isinstance(rates, Rates):
        # The shared record (tribolmp.records.Rates): its given fields, under the same names.
        rates = {k: v for k, v in rates.to_dict(with_units=False).items() if v is not None}
    if not isinstance(rates, Mapping):
        raise ParameterError("rates", "a mapping (rates.json content)", type(rates).__name__)
    if dim not in (1, 2):
        raise ParameterError("dim", "one of [1, 2]", dim)
    l = _rate(rates, "step_length_m", required=True, positive=True)
    if _has_c1(rates) and _rate(rates, "step_time_s") is None:
        # rates.json v2 (issue 14): the Eq. 23 coefficients measured on the MCA's 1D profile (contract C1).
        # A 2D surface gets them per unit width of the 2D MCA's slab, one automaton (l) thick (PHYSICS.md 8).
        slab = l if dim == 2 else 1.0
        mu_c1, d0_c1 = _rate(rates, "mu_per_s"), _rate(rates, "d0_m2_s")
        dz_c1, dxl2_c1 = _rate(rates, "dz") * slab, _rate(rates, "dx_l2") * slab
        if duration is None:
            duration = 5.0 / mu_c1 if mu_c1 > 0 else 1000.0 * l**2 / max(d0_c1, 1e-300)
        if not (isinstance(steps, int) and steps >= 1):
            raise ParameterError("steps", "an integer >= 1", steps)
        return TopographyParams(
            dim=dim, n=n, dx=l if dx is None else dx, d0=d0_c1, dx_noise=dxl2_c1 / l**2, dz=dz_c1, mu=mu_c1, l=l,
            correlation_length=correlation_length, dt=duration / steps, steps=steps, operator=operator,
        )
    tau = _rate(rates, "step_time_s", required=True, positive=True)
    d0 = _rate(rates, "diffusion_m2_s") or l**2 / (2 * dim * tau)
    dx_noise = l ** (dim + 2) / (2 * dim * tau)
    det = _rate(rates, "detachment_rate")
    nu_z = None
    if det is not None or _rate(rates, "reattachment_rate") is not None:
        nu_z = (det or 0.0) + (_rate(rates, "reattachment_rate") or 0.0)
    elif _rate(rates, "transfer_rate") is not None and sliding_velocity is not None:
        if not (isinstance(sliding_velocity, (int, float)) and math.isfinite(sliding_velocity) and sliding_velocity >= 0):
            raise ParameterError("sliding_velocity", "a finite number >= 0 (m/s)", sliding_velocity)
        nu_z = _rate(rates, "transfer_rate") * float(sliding_velocity)
    if nu_z is None:
        raise ParameterError("rates", "detachment_rate/reattachment_rate (1/s), or transfer_rate (1/m) "
                             "with a sliding_velocity", sorted(rates))
    dz = l ** (dim + 2) * nu_z / 2.0
    mu = _rate(rates, "wear_rate")
    if mu is None:
        mu = det or 0.0
    if duration is None:
        duration = 5.0 / mu if mu > 0 else 1000.0 * tau
    if not (isinstance(steps, int) and steps >= 1):
        raise ParameterError("steps", "an integer >= 1", steps)
    return TopographyParams(
        dim=dim, n=n, dx=l if dx is None else dx, d0=d0, dx_noise=dx_noise, dz=dz, mu=mu, l=l,
        correlation_length=correlation_length, dt=duration / steps, steps=steps, operator=operator,
    )


def params_from_scene(scene, rates: Mapping[str, Any] | None = None) -> TopographyParams:
    """Eq. 23 parameters from a :class:`~tribolmp.scene.Scene`.

    The grid (``dim``, ``grid_points``, ``pixel_size``), ``duration``,
    ``steps`` and ``correlation_length`` come from ``[topography]``
    (defaults when absent).  The rates come from, in order: the ``rates``
    argument (e.g. the nanoscale model's ``rates.json``; used only if it can
    drive Eq. 23: valid C1 coefficients or the legacy ``step_length_m`` and
    ``step_time_s``), the scene's ``[rates]`` section (with ``[kinematics].sliding_velocity`` for the
    transfer rate), or the ``[topography]`` fields ``d0, dx_noise, dz, mu, l``.
    The integrator is ``scene.topography.scheme`` (not part of the params).
    """
    from ...scene.schema import Topography

    topo = scene.topography or Topography()
    given = rates
    if isinstance(rates, Rates):
        given = {k: v for k, v in rates.to_dict(with_units=False).items() if v is not None}
    if rates is not None and not _drives_eq23(given):
        # A measured rates.json (issue 14) holds no step_time_s (it was the identity l^2/D) and, from a run
        # too short for the slow modes, no valid Eq. 23 coefficients: nothing measured can drive Eq. 23.
        # The scene's [rates] or [topography] values do (stated in the topography stage's rates_source).
        rates = None
    if rates is None and scene.rates is not None:
        rates = scene.rates.to_record()
    if rates is not None:
        return params_from_rates(
            rates, dim=topo.dim, n=topo.grid_points, dx=topo.pixel_size, duration=topo.duration,
            steps=topo.steps, correlation_length=topo.correlation_length,
            sliding_velocity=scene.kinematics.sliding_velocity,
        )
    return TopographyParams(
        dim=topo.dim, n=topo.grid_points, dx=topo.pixel_size, d0=topo.d0, dx_noise=topo.dx_noise,
        dz=topo.dz, mu=topo.mu, l=topo.l, correlation_length=topo.correlation_length,
        dt=topo.duration / topo.steps, steps=topo.steps,
    )
