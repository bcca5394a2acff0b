"""Reduced lubrication models: named squeeze and sliding force laws (SI units).

The seed (Section 4) replaces the fluid film by distance- and
velocity-dependent surface forces.  This module offers them by name:

Squeeze (normal approach, ``V = -dh/dt``; force opposing the approach, N)

``damper``
    F = alpha V / h, alpha = 6 pi eta R^2 (Eq. 11 with the factor 2 fixed).
    For a power-law fluid (n != 1) the closed-form power-law force.
``power-law``
    :func:`~.reference.power_law_squeeze_force` (n > 1/3; n = 1 is the damper).
``cox-brenner``
    Two-term small-gap Stokes expansion, for h/R <= 0.1 (Newtonian only).
``brenner``
    Brenner's exact Stokes series, any gap (Newtonian only).
``reynolds``
    The numerical Reynolds reference (:mod:`.reynolds`), Newtonian or power-law.

Sliding (parallel translation at U; drag opposing U, N)

``gcb``
    Goldman-Cox-Brenner 6 pi eta R U [(8/15) ln(R/h) + 0.9588], h/R << 1.
``couette``
    The seed's Eq. 12, Couette shear only: 2-2.6x too small; for comparison.
``faxen``
    Far-field wall correction for h >~ R.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

from ...errors import ParameterError
from ...params import param, renamed, validate_dataclass
from ..base import MethodRegistry, Result, check_positive, check_range, timed
from . import reference as ref

__all__ = [
    "Params",
    "SQUEEZE",
    "SLIDING",
    "squeeze_force",
    "sliding_force",
    "solve",
    "squeeze_damper_force",
    "params_from_scene",
]

SQUEEZE = MethodRegistry("squeeze model")
SLIDING = MethodRegistry("sliding model")


# ``velocity`` kept: CLI --velocity (errors name it as given), docs/conventions.md
@renamed(velocity="approach_velocity")
@dataclass(frozen=True)
class Params:
    """A sphere near a plane in a lubricant (SI units).

    Attributes
    ----------
    radius : float
        Sphere (asperity, particle) radius R in m.
    viscosity : float
        Newtonian viscosity eta in Pa s.
    gap : float
        Minimum gap h in m.
    approach_velocity : float
        Approach speed V = -dh/dt in m/s (> 0: closing).
    sliding_velocity : float
        Tangential speed U in m/s.
    power_law_index : float
        Flow index n > 1/3 (1 = Newtonian).
    consistency : float or None
        Power-law consistency K in Pa s^n (None: K = viscosity).
    length : float or None
        Integration radius L (m) of the seed's Couette estimate (None: R).
    reynolds_cells : int
        Cells of the Reynolds reference mesh.
    reynolds_domain : float
        Outer radius of the Reynolds domain in units of sqrt(2 R h).
    """

    radius: float = param(1e-3, unit="m", lo=0.0, lo_open=True, hi=1e3)
    viscosity: float = param(0.1, unit="Pa s", lo=0.0, lo_open=True, hi=1e9)
    gap: float = param(1e-6, unit="m", lo=0.0, lo_open=True, hi=1e3)
    approach_velocity: float = param(1e-3, unit="m/s", lo=-1e6, hi=1e6)
    sliding_velocity: float = param(0.0, unit="m/s", lo=-1e6, hi=1e6)
    power_law_index: float = param(1.0, lo=1.0 / 3.0, lo_open=True, hi=5.0)
    consistency: float | None = param(None, unit="Pa s^n", lo=0.0, lo_open=True, hi=1e9)
    length: float | None = param(None, unit="m", lo=0.0, lo_open=True, hi=1e3)
    reynolds_cells: int = param(400, lo=8, hi=20_000)
    reynolds_domain: float = param(1000.0, lo=2.0, hi=1e9)

    def __post_init__(self) -> None:
        validate_dataclass(self)

    @property
    def newtonian(self) -> bool:
        """True for n == 1."""
        return self.power_law_index == 1.0

    @property
    def K(self) -> float:
        """Consistency in Pa s^n (the viscosity when not given)."""
        return self.viscosity if self.consistency is None else self.consistency


def _newtonian_only(p: Params, model: str) -> None:
    if not p.newtonian:
        raise ParameterError(
            "model",
            "'damper', 'power-law' or 'reynolds' for a "
            f"power-law fluid (n = {p.power_law_index:g})",
            model,
        )


@SQUEEZE.register("damper")
def _damper(p: Params) -> dict:
    if not p.newtonian:
        return _power_law(p)
    return {"force": float(ref.damper_force(p.radius, p.viscosity, p.gap, p.approach_velocity))}


@SQUEEZE.register("power-law")
def _power_law(p: Params) -> dict:
    return {
        "force": ref.power_law_squeeze_force(
            p.radius, p.K, p.power_law_index, p.gap, p.approach_velocity
        )
    }


@SQUEEZE.register("cox-brenner")
def _cox_brenner(p: Params) -> dict:
    _newtonian_only(p, "cox-brenner")
    if p.gap / p.radius > 0.1:
        raise ParameterError(
            "gap", "gap/radius <= 0.1 for model 'cox-brenner' (use 'brenner')", p.gap / p.radius
        )
    return {
        "force": float(ref.cox_brenner_force(p.radius, p.viscosity, p.gap, p.approach_velocity))
    }


@SQUEEZE.register("brenner")
def _brenner(p: Params) -> dict:
    _newtonian_only(p, "brenner")
    return {"force": float(ref.brenner_force(p.radius, p.viscosity, p.gap, p.approach_velocity))}


@SQUEEZE.register("reynolds")
def _reynolds(p: Params) -> dict:
    from . import reynolds

    rp = reynolds.ReynoldsParams(
        radius=p.radius,
        gap=p.gap,
        approach_velocity=p.approach_velocity,
        viscosity=p.viscosity,
        power_law_index=p.power_law_index,
        consistency=p.consistency,
        cells=p.reynolds_cells,
        domain=p.reynolds_domain,
    )
    res = reynolds.solve(rp, method="axisymmetric")
    # Share of the infinite-domain force lost outside r_max, from the exact
    # paraboloid solution (zero for an infinite domain; large for n -> 1/3).
    full = ref.power_law_squeeze_force(p.radius, p.K, p.power_law_index, p.gap, 1.0)
    part = ref.power_law_squeeze_force(
        p.radius, p.K, p.power_law_index, p.gap, 1.0, r_max=res.r_max
    )
    return {
        "force": res.force,
        "nit": res.nit,
        "r_max": res.r_max,
        "truncation_error": 1.0 - part / full,
    }


@SLIDING.register("gcb")
def _gcb(p: Params) -> dict:
    _newtonian_only(p, "gcb")
    return {"force": float(ref.gcb_sliding_force(p.radius, p.viscosity, p.gap, p.sliding_velocity))}


@SLIDING.register("couette")
def _couette(p: Params) -> dict:
    _newtonian_only(p, "couette")
    return {
        "force": float(
            ref.couette_sliding_force(p.radius, p.viscosity, p.gap, p.sliding_velocity, p.length)
        )
    }


@SLIDING.register("faxen")
def _faxen(p: Params) -> dict:
    _newtonian_only(p, "faxen")
    return {
        "force": float(ref.faxen_sliding_force(p.radius, p.viscosity, p.gap, p.sliding_velocity))
    }


_UNITS = {"force": "N", "time_s": "s", "r_max": "m", "gap_over_radius": "1"}


def _run(registry: MethodRegistry, p: Params, model: str) -> Result:
    impl = registry.get(model, "model")
    res = Result(method=model, model=model)
    with timed(res):
        res.update(impl(p))
    res["gap_over_radius"] = p.gap / p.radius
    res["units"] = dict(_UNITS)
    res["message"] = f"{registry.kind} '{model}'"
    return res


def squeeze_force(params: Params, model: str = "damper") -> Result:
    """Squeeze force on the sphere (N, opposing the approach) from a named model.

    Parameters
    ----------
    params : Params
        Geometry, fluid and approach speed.
    model : str
        One of :data:`SQUEEZE` (``damper``, ``power-law``, ``cox-brenner``,
        ``brenner``, ``reynolds``).

    Returns
    -------
    Result
        ``force`` (N), ``model``, ``time_s`` and model-specific diagnostics.
    """
    return _run(SQUEEZE, params, model)


def sliding_force(params: Params, model: str = "gcb") -> Result:
    """Drag on a sphere sliding parallel to the plane (N, opposing ``sliding_velocity``).

    Parameters
    ----------
    params : Params
        Geometry, fluid and sliding speed.
    model : str
        One of :data:`SLIDING` (``gcb``, ``couette``, ``faxen``).
    """
    return _run(SLIDING, params, model)


def solve(params: Params, *, method: str = "damper", rng=None) -> Result:
    """Return the squeeze force of ``method`` (common entry point, see :func:`squeeze_force`)."""
    return squeeze_force(params, method)


def squeeze_damper_force(radius: float, viscosity: float, gap: float, velocity: float) -> float:
    """Reduced squeeze damper F = 6 pi eta R^2 V / h in N (opposing approach; V > 0 approach).

    Parameters
    ----------
    radius : float
        R in m (> 0).
    viscosity : float
        eta in Pa s (> 0).
    gap : float
        h in m (> 0).
    velocity : float
        Approach speed V = -dh/dt in m/s.
    """
    try:
        ok = (
            radius > 0
            and viscosity > 0
            and gap > 0
            and math.isfinite(radius * viscosity * gap * velocity)
        )
    except TypeError:
        ok = False
    if not ok:  # slow path only to build the one-line message naming the field
        check_positive("radius", radius, "m")
        check_positive("viscosity", viscosity, "Pa s")
        check_positive("gap", gap, "m")
        check_range("velocity", velocity, unit="m/s")
    return ref.damper_force(radius, viscosity, float(gap), float(velocity))


def params_from_scene(scene, *, velocity: float | None = None) -> Params:
    """Build :class:`Params` from a scene's ``[lubricant]`` and ``[geometry]`` sections.

    The sphere radius is ``[geometry].radius``, the gap ``[lubricant].film_thickness``
    and the sliding speed ``[kinematics].sliding_velocity``.  The approach speed
    defaults to 1e-3 of the gap per second unless given.

    Raises
    ------
    ParameterError
        When the scene has no ``[lubricant]`` section.
    """
    lub = scene.lubricant
    if lub is None:
        raise ParameterError(
            "[lubricant]", "a [lubricant] section for the lubrication model", "nothing"
        )
    gap = lub.film_thickness
    return Params(
        radius=scene.geometry.radius,
        viscosity=lub.viscosity,
        gap=gap,
        approach_velocity=1e-3 * gap if velocity is None else velocity,
        sliding_velocity=scene.kinematics.sliding_velocity,
        power_law_index=lub.power_law_index,
        consistency=lub.consistency if lub.power_law_index != 1.0 else None,
    )


def with_gap(params: Params, gap: float) -> Params:
    """Copy of ``params`` at another gap (m)."""
    return replace(params, gap=gap)
