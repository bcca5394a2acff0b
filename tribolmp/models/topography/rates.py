"""Eq. 23 parameters from physical rates (the nanoscale model's ``rates.json``) or a scene.

Mapping and its assumptions
---------------------------
The mapping is :func:`tribolmp.models.bridges.eq23_from_rates` (one place,
one time convention): the Eq. 23 coefficients of the MCA's 1D profile at the
MCA's own conditions, either measured (contract C1 fields ``mu_per_s``,
``d0_m2_s``, ``dz``, ``dx_l2``) or from the legacy fields with the stated
block picture (``D0 = diffusion_m2_s``, ``Dx l^2 = l^3 D0`` -- high-k plateau
``l^3``, one block at the block scale, with the analysis' ``tau = l^2/D`` --,
``Dz = l^3 nu_z / 2``, ``mu = wear_rate``, ``nu_z`` from the detachment and
reattachment rates or ``transfer_rate * V_MCA``).  A zero diffusion
coefficient is a value, not a missing one; ``step_time_s`` is not used (it is
``l^2 / D`` by the analysis' definition).

For ``dim = 2`` the 1D noise intensities are multiplied by the slab thickness
``w`` of the 2D MCA (``slab_thickness_m``, default ``step_length_m``): a
profile is the strip average of the surface across ``w`` (see
:func:`tribolmp.models.bridges.rates_at_part`, which also moves the rates to a
part's sliding conditions; this module keeps the MCA's conditions).
``Dx`` and ``Dz`` carry units m^3/s in 1D and m^4/s in 2D; ``TopographyParams.l``
is set to the step length and ``dx_noise = (Dx l^2) / l^2``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from ...errors import ParameterError
from ...records import Rates
from .spde import TopographyParams

__all__ = ["params_from_rates", "params_from_scene", "topography_fallback"]


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
    fallback: Mapping[str, Any] | None = None,
) -> TopographyParams:
    """Build :class:`TopographyParams` from nanoscale rates at the MCA's conditions.

    See the module docstring.

    Parameters
    ----------
    rates : Rates or mapping
        The :class:`~tribolmp.records.Rates` record, ``rates.json`` content or ``[rates]``: the C1
        coefficients, or ``step_length_m`` (m), ``diffusion_m2_s`` (m^2/s), ``wear_rate`` (1/s) and
        ``detachment_rate``/``reattachment_rate`` (1/s) or ``transfer_rate`` (1/m); the MCA velocity
        ``sliding_velocity_m_s`` / ``velocity_m_s`` (m/s).  Other keys are ignored.
    dim, n : int
        Dimension and grid points per side.
    dx : float, optional
        Grid spacing (m); default the step length ``l``.
    duration : float, optional
        Evolution time (s); default ``5/mu`` (the slowest mode's PSD is then
        within exp(-10) of stationary), or ``1000 l^2/D0`` when ``mu = 0``.
    steps : int
        Number of time steps (the exact scheme is exact for any step).
    correlation_length : float
        Noise correlation length (m).
    sliding_velocity : float, optional
        The MCA's sliding velocity (m/s), used only when the rates do not
        carry it (never the part's: a rate is converted at the velocity it
        was measured at).
    operator : {"spectral", "lattice"}
        Operator of the exact scheme.
    fallback : mapping, optional
        Coefficients (C1 names and units, 1D) for what the rates do not give,
        see :func:`tribolmp.models.bridges.eq23_from_rates` and :func:`topography_fallback`.

    Returns
    -------
    TopographyParams
    """
    from ..bridges import eq23_from_rates

    if isinstance(rates, Rates):
        # The shared record (tribolmp.records.Rates): its given fields, under the same names.
        rates = {**{k: v for k, v in rates.to_dict(with_units=False).items() if v is not None},
                 "valid": {k: False for k in rates.flagged}}
    if not isinstance(rates, Mapping):
        raise ParameterError("rates", "a mapping (rates.json content)", type(rates).__name__)
    if dim not in (1, 2):
        raise ParameterError("dim", "one of [1, 2]", dim)
    r = dict(rates)
    if (
        r.get("sliding_velocity_m_s") is None
        and r.get("velocity_m_s") is None
        and sliding_velocity is not None
    ):
        if not (
            isinstance(sliding_velocity, (int, float))
            and math.isfinite(sliding_velocity)
            and sliding_velocity > 0
        ):
            raise ParameterError(
                "sliding_velocity", "a finite MCA velocity > 0 (m/s)", sliding_velocity
            )
        r["sliding_velocity_m_s"] = float(sliding_velocity)
    eq = eq23_from_rates(r, fallback=fallback)
    step = eq.step_length_m or 1.0
    w = 1.0
    if dim == 2:
        w = r.get("slab_thickness_m") or eq.step_length_m
        if not w:
            raise ParameterError(
                "rates.slab_thickness_m", "the 2D MCA's slab thickness (m) for a 2D surface", None
            )
    mu = eq.mu
    if duration is None:
        duration = 5.0 / mu if mu > 0 else (1000.0 * step * step / eq.d0 if eq.d0 > 0 else 1.0)
    if not (isinstance(steps, int) and steps >= 1):
        raise ParameterError("steps", "an integer >= 1", steps)
    return TopographyParams(
        dim=dim,
        n=n,
        dx=step if dx is None else dx,
        d0=eq.d0,
        dx_noise=eq.dx_l2 * w / step**2,
        dz=eq.dz * w,
        mu=mu,
        l=step,
        correlation_length=correlation_length,
        dt=duration / steps,
        steps=steps,
        operator=operator,
    )


def topography_fallback(topo, slab: float) -> dict[str, Any]:
    """Return a ``[topography]`` section's Eq. 23 values in the 1D C1 names.

    Used for coefficients not measured.

    A 2D value is ``slab`` times the 1D one (the profile is the strip average of
    the surface over the 2D MCA's slab, see :func:`tribolmp.models.bridges.rates_at_part`).
    """
    w = slab if topo.dim == 2 else 1.0
    return {
        "mu_per_s": topo.mu,
        "d0_m2_s": topo.d0,
        "dz": topo.dz / w,
        "dx_l2": topo.dx_noise * topo.l**2 / w,
        "source": "[topography] values (assumed: not measured by the MCA)",
    }


def params_from_scene(scene, rates: Mapping[str, Any] | None = None) -> TopographyParams:
    """Eq. 23 parameters from a :class:`~tribolmp.scene.Scene`.

    The grid (``dim``, ``grid_points``, ``pixel_size``), ``duration``,
    ``steps`` and ``correlation_length`` come from ``[topography]``
    (defaults when absent).  The rates come from, in order: the ``rates``
    argument (e.g. the nanoscale model's ``rates.json``), the scene's
    ``[rates]`` section (at the MCA's ``sliding_velocity_m_s``, never the
    scene's), or the ``[topography]`` fields ``d0, dx_noise, dz, mu, l``.
    The integrator is ``scene.topography.scheme`` (not part of the params).
    """
    from ...scene.schema import Topography

    topo = scene.topography or Topography()
    if rates is None and scene.rates is not None:
        rates = scene.rates.to_record()
    if rates is not None:
        # A measured rates.json (issue 14) may lack coefficients (no wear_rate; C1 null
        # for a run too short for the slow modes): those come from the [topography]
        # values, listed per coefficient by tribolmp.models.bridges.eq23_from_rates (an
        # assumption the running-in report states).
        return params_from_rates(
            rates,
            dim=topo.dim,
            n=topo.grid_points,
            dx=topo.pixel_size,
            duration=topo.duration,
            steps=topo.steps,
            correlation_length=topo.correlation_length,
            fallback=topography_fallback(topo, topo.l),
        )
    return TopographyParams(
        dim=topo.dim, n=topo.grid_points, dx=topo.pixel_size, d0=topo.d0, dx_noise=topo.dx_noise,
        dz=topo.dz, mu=topo.mu, l=topo.l, correlation_length=topo.correlation_length,
        dt=topo.duration / topo.steps, steps=topo.steps,
    )
