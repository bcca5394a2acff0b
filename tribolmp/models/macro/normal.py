"""Normal direction of the rigid body with the optional squeeze-film damper.

The body (mass ``m``, possibly 0) is pressed by a load ``W`` towards the plate
through a lubricant film of thickness ``h``.  The film resists approach with
the reduced squeeze damper of the lubrication model,
``F_sq = squeeze_damper_force(R, eta, h, V)`` (``= alpha V / h``,
``alpha = 6 pi eta R^2``, ``V = -dh/dt``), which is singular as ``h -> 0``.
Optionally the asperities touch at a gap ``h_c``: below it the MDR contact
carries ``F_c = normal_force(h_c - h)``.

Stability: the state is ``s = ln(h/h0)`` (and the momentum ``p = m dh/dt`` if
``m > 0``), so ``h = h0 exp(s)`` can never become negative, and the
approach is integrated with the implicit Radau method (the damping rate
``alpha/(m h)`` grows without bound as ``h -> 0``).  Under a constant load and
no contact, ``m dh/dt + alpha ln(h/h0) + W t = m dh/dt(0)`` exactly; for
``m = 0`` this is ``h = h0 exp(-W t / alpha)``
(:func:`tribolmp.models.macro.reference.squeeze_approach_gap`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...errors import ConvergenceError
from ...params import param, renamed, validate_dataclass
from ..base import Result, timed

__all__ = ["SqueezeParams", "squeeze_approach", "squeeze_params_from_scene"]


@renamed(load="normal_force")  # old name kept (docs/conventions.md)
@dataclass(frozen=True)
class SqueezeParams:
    """Normal approach of the body through a squeeze film (SI).

    Attributes
    ----------
    normal_force : float
        Normal load W pressing the body down (N) (old name ``load``).
    radius : float
        Curvature radius R of the body's contact (m).
    viscosity : float
        Newtonian viscosity eta (Pa s).
    gap : float
        Initial film thickness h0 (m).
    duration : float
        Simulated time (s).
    mass : float
        Body mass m (kg); 0 = overdamped (inertia neglected).
    approach_velocity : float
        Initial approach speed -dh/dt (m/s); only with ``mass > 0``.
    contact_gap : float
        Gap h_c at which the MDR contact starts to carry load (m); 0 = no solid contact.
    rtol : float
        Relative tolerance of the integrator.
    """

    normal_force: float = param(10.0, unit="N", lo=0.0, hi=1e9)
    radius: float = param(5e-3, unit="m", lo=0.0, lo_open=True, hi=10.0)
    viscosity: float = param(0.1, unit="Pa s", lo=0.0, lo_open=True, hi=1e6)
    gap: float = param(1e-6, unit="m", lo=0.0, lo_open=True, hi=1.0)
    duration: float = param(0.01, unit="s", lo=0.0, lo_open=True, hi=1e6)
    mass: float = param(0.0, unit="kg", lo=0.0, hi=1e6)
    approach_velocity: float = param(0.0, unit="m/s", lo=-1e3, hi=1e3)
    contact_gap: float = param(0.0, unit="m", lo=0.0, hi=1.0)
    rtol: float = param(1e-9, lo=1e-13, hi=1e-2)

    def __post_init__(self):
        validate_dataclass(self)


def squeeze_params_from_scene(scene, **overrides) -> SqueezeParams:
    """:class:`SqueezeParams` from the scene.

    Reads ``[lubricant]`` (viscosity, film thickness), ``[geometry].radius``,
    ``[load].normal_force`` and ``[kinematics]`` (mass, duration).  Requires a ``[lubricant]``
    section.
    """
    from ...errors import ParameterError

    if scene.lubricant is None:
        raise ParameterError(
            "[lubricant]", "a [lubricant] section for the squeeze damper", "nothing"
        )
    kw = {
        "normal_force": scene.load.normal_force,
        "radius": scene.geometry.radius,
        "viscosity": scene.lubricant.viscosity,
        "gap": scene.lubricant.film_thickness,
        "duration": scene.kinematics.duration,
        "mass": scene.kinematics.mass,
    }
    if "load" in overrides:  # the old name of normal_force
        overrides["normal_force"] = overrides.pop("load")
    kw.update(overrides)
    return SqueezeParams(**kw)


def squeeze_approach(params: SqueezeParams, contact=None, *, n_out: int = 201) -> Result:
    """Integrate the body's approach through the film (implicit Radau in ``ln h``).

    Parameters
    ----------
    params : SqueezeParams
    contact : ContactSprings, optional
        MDR contact engaged below ``params.contact_gap`` (needed if that is > 0).
    n_out : int
        Output samples (uniform in time).

    Returns
    -------
    Result
        ``t`` (s), ``gap`` (m, always > 0), ``log_gap`` (``ln(h/h0)``),
        ``approach_velocity`` (m/s, ``-dh/dt``), ``film_force`` (N, from
        ``squeeze_damper_force``), ``contact_force`` (N, carried by the
        solid contact), ``nfev``.
    """
    from scipy.integrate import solve_ivp

    from ..lubrication import squeeze_damper_force  # lazy: only lubricated bodies need it

    p = params
    h0, W, m, hc = p.gap, p.normal_force, p.mass, p.contact_gap
    if hc > 0 and contact is None:
        from ...errors import ParameterError

        raise ParameterError("contact", "a ContactSprings when contact_gap > 0", None)

    def gap_of(
        s,
    ):  # Newton trials of the implicit solver may probe huge |s|: keep h representable (> 0)
        return h0 * math.exp(min(max(s, -700.0), 700.0))

    def damping(h):  # N s/m: the damper is linear in the approach speed
        return squeeze_damper_force(p.radius, p.viscosity, h, 1.0)

    def solid(h):
        return contact.normal_force(hc - h) if hc > 0 and h < hc else 0.0

    def stiffness(h):  # dF_c/dh (N/m), finite difference on the MDR law (only for the Jacobian)
        if not (hc > 0 and h < hc):
            return 0.0
        dh = 1e-6 * max(hc - h, 1e-15)
        return (solid(h + dh) - solid(h - dh)) / (2 * dh)

    if m == 0.0:
        # s' = -(W - F_c) / (h c(h)):  h c(h) = alpha for the reduced damper, so s is linear in t
        def rhs(t, y):
            h = gap_of(y[0])
            return [-(W - solid(h)) / (h * damping(h))]

        def jac(t, y):
            h = gap_of(y[0])
            hc_ = h * damping(h)
            return [[stiffness(h) * h / hc_]]  # d(h c)/ds = 0 for c ~ 1/h

        y0 = [0.0]
    else:
        # y = (s, q) with q = m dh/dt / h0:  s' = q h0/(m h),  q' = (-W + F_c - c(h) h0 q / m) / h0
        def rhs(t, y):
            h = gap_of(y[0])
            c = damping(h)
            return [y[1] * h0 / (m * h), (-W + solid(h) - c * h0 * y[1] / m) / h0]

        def jac(t, y):
            h = gap_of(y[0])
            c = damping(h)
            # c ~ 1/h: dc/ds = -c
            return [[-y[1] * h0 / (m * h), h0 / (m * h)],
                    [(stiffness(h) * h + c * h0 * y[1] / m) / h0, -c / m]]

        y0 = [0.0, -p.approach_velocity * m / h0]
    res = Result(method="radau-log-gap")
    with timed(res):
        t_out = np.linspace(0.0, p.duration, n_out)
        sol = solve_ivp(
            rhs,
            (0.0, p.duration),
            y0,
            method="Radau",
            jac=jac,
            t_eval=t_out,
            rtol=p.rtol,
            atol=[p.rtol] + ([p.rtol * max(W, 1e-30) * p.duration / h0 + 1e-300] if m > 0 else []),
        )
        if sol.status != 0:
            raise ConvergenceError(
                f"squeeze approach: integrator failed at t = {sol.t[-1]:g} s: {sol.message}"
            )
        s = sol.y[0]
        # h may underflow to 0.0 in float64 when the film keeps thinning (log_gap stays exact), so
        # nothing below evaluates the damper at h: with c(h) = alpha / h, the film force is
        # -alpha ds/dt and the approach speed -dh/dt = -h ds/dt.
        h = h0 * np.exp(s)
        alpha = damping(1.0)
        s_dot = np.array([rhs(ti, yi)[0] for ti, yi in zip(sol.t, sol.y.T)])
        V = -h * s_dot
        film = -alpha * s_dot
        fc = np.array([solid(hi) for hi in h])
    res.update(
        t=sol.t,
        gap=h,
        log_gap=s,
        approach_velocity=V,
        film_force=film,
        contact_force=fc,
        nfev=sol.nfev,
        nit=int(sol.t.size),
        alpha=alpha,
        units={
            "t": "s",
            "gap": "m",
            "approach_velocity": "m/s",
            "film_force": "N",
            "contact_force": "N",
            "alpha": "N s",
        },
        message=f"gap {h0:g} -> {h0:g}*exp({s[-1]:.6g}) m in {p.duration:g} s",
    )
    if fc[-1] < W * (1.0 - 1e-6) and s_dot[-1] < 0.0:
        # The solid contact cannot (yet) carry the load: the film is still being squeezed out
        # (it thins exponentially and never ruptures in this model).
        res.update(status=1, message=res.message + f"; film still thinning, solid contact carries "
                   f"{fc[-1]:.4g} of {W:.4g} N")
    return res
