"""Macroscale dynamics: a rigid body on MDR contact springs (seed Section 2, Fig. 4).

* :mod:`.rigid_body` -- stick-slip under a pulling spring (event-driven,
  stiff-capable) and prescribed oscillation with micro-slip;
* :mod:`.friction` -- friction laws (constant, velocity weakening, tables
  from the nanoscale model);
* :mod:`.multirate` -- cycle-averaged contact for a fast oscillation over a slow drift
  (imposed drift, or a body pulled through a spring);
* :mod:`.normal` -- the normal approach through the optional squeeze-film damper;
* :mod:`.contact` -- the MDR spring row under the body (uses
  :mod:`tribolmp.models.contact.mdr`);
* :mod:`.reference` -- closed-form stick-slip cycle, Mindlin-Deresiewicz loop.

Scene adapters: :func:`params_from_scene`, :func:`stick_slip_from_scene`,
:func:`oscillation_from_scene`.
"""

from __future__ import annotations

import numpy as np

from ...errors import ParameterError
from ..friction import friction_coefficient
from .contact import ContactSprings, profile_from_geometry
from .friction import (
    FRICTION_LAWS,
    ConstantFriction,
    FrictionLaw,
    TabulatedFriction,
    VelocityWeakening,
    load_friction_law,
    make_friction_law,
)
from .multirate import (
    AveragedContact,
    DriftParams,
    PulledParams,
    drift_under_oscillation,
    jenkins_mean_force,
    pulled_under_oscillation,
)
from .normal import SqueezeParams, squeeze_approach, squeeze_params_from_scene
from .rigid_body import (
    STICK_SLIP_METHODS,
    OscillationParams,
    StickSlipParams,
    oscillate,
    stick_slip,
)

__all__ = [
    "StickSlipParams",
    "OscillationParams",
    "DriftParams",
    "PulledParams",
    "SqueezeParams",
    "squeeze_approach",
    "squeeze_params_from_scene",
    "pulled_under_oscillation",
    "jenkins_mean_force",
    "stick_slip",
    "oscillate",
    "drift_under_oscillation",
    "solve",
    "params_from_scene",
    "contact_from_scene",
    "stick_slip_from_scene",
    "oscillation_from_scene",
    "ContactSprings",
    "AveragedContact",
    "FrictionLaw",
    "ConstantFriction",
    "VelocityWeakening",
    "TabulatedFriction",
    "FRICTION_LAWS",
    "STICK_SLIP_METHODS",
    "make_friction_law",
    "load_friction_law",
    "profile_from_geometry",
]


def solve(
    params: StickSlipParams, *, method: str = "auto", rng=None, law: FrictionLaw | None = None
):
    """Model-contract alias of :func:`stick_slip` (``rng`` unused: deterministic)."""
    return stick_slip(params, law, method=method)


def params_from_scene(scene, **overrides) -> StickSlipParams:
    """:class:`StickSlipParams` from ``[kinematics]`` and ``[load]``.

    Mass, drive stiffness, velocity and duration come from ``[kinematics]``.
    """
    kin = scene.kinematics
    kw = dict(
        mass=kin.mass,
        drive_stiffness=kin.drive_stiffness,
        drive_velocity=kin.sliding_velocity,
        normal_force=scene.load.normal_force,
        duration=kin.duration,
    )
    kw.update(overrides)
    if kw["drive_velocity"] <= 0:
        raise ParameterError(
            "[kinematics].sliding_velocity",
            "a drive velocity > 0 m/s for stick-slip",
            kw["drive_velocity"],
        )
    return StickSlipParams(**kw)


def contact_from_scene(
    scene, *, mu: float | None = None, n_springs: int | None = None, rng=None
) -> ContactSprings:
    """Return the MDR spring row of the scene's contact at its normal load.

    ``[geometry].profile`` sphere/cone/flat maps directly.  ``rough`` with an
    ``rng`` (numpy Generator) and a ``[roughness]`` section draws one random 1D
    MDR profile of the contact model (``rough.mdr_profiles_from_psd``,
    ``grid_points`` springs at ``pixel_size``).  A rough profile without an
    ``rng`` (or without ``[roughness]``) is a ParameterError: it used to become
    the sphere of ``[geometry].radius`` without a word.
    """
    geo = scene.geometry
    E, G = scene.effective_modulus, scene.effective_shear_modulus
    mu = friction_coefficient(scene).mu if mu is None else mu
    if geo.profile == "rough" and (rng is None or scene.roughness is None):
        raise ParameterError(
            "rng" if rng is None else "[roughness]",
            "a numpy Generator to draw the rough MDR profile of [geometry].profile = 'rough'"
            if rng is None
            else "a [roughness] section for [geometry].profile = 'rough'",
            None,
        )
    if geo.profile == "rough":
        from ..contact.rough import mdr_profiles_from_psd, self_affine_psd

        r = scene.roughness
        psd = self_affine_psd(
            r.rms_height, r.hurst, r.rolloff_wavelength, r.short_cutoff_wavelength
        )
        x, g = mdr_profiles_from_psd(psd, n_springs or r.grid_points, r.pixel_size, 1, rng)
        return ContactSprings(x, np.asarray(g)[0], E, G, mu)
    kind = geo.profile if geo.profile in ("sphere", "cone", "flat") else "sphere"
    n = n_springs or max(3, min(scene.contact.springs, 2001))
    x, g = profile_from_geometry(
        kind,
        max(scene.load.normal_force, 1e-6),
        E,
        n_springs=n,
        radius=geo.radius,
        half_angle_deg=geo.half_angle_deg,
    )
    return ContactSprings(x, g, E, G, mu)


def stick_slip_from_scene(
    scene,
    mu: float | None = None,
    contact_law: str = "rigid",
    *,
    law: FrictionLaw | None = None,
    contact_stiffness: float | None = None,
    method: str = "auto",
    rng=None,
    contact_gap: float | None = None,
    **overrides,
):
    """Chain entry point: stick-slip of the scene's body.

    Parameters
    ----------
    scene : Scene
    mu : float, optional
        Friction coefficient (constant law); default
        :func:`tribolmp.models.friction.friction_coefficient` of the scene
        (``[rates].mu``, else ``[load].friction_coefficient``).  Ignored if ``law`` is given.
    contact_law : {"rigid", "mdr"}
        Rigid contact during stick, or the MDR tangential stiffness of the
        sticking springs (load dependent, so it vanishes with the load).
    law : FrictionLaw, optional
        Any friction law (e.g. :func:`load_friction_law` of a rates.json).
    contact_stiffness : float, optional
        Constant contact stiffness (N/m) instead of the MDR one.
    method : str
        Integrator (see :func:`stick_slip`).
    rng : numpy.random.Generator, optional
        Draws the rough MDR profile for ``[geometry].profile = "rough"``
        (see :func:`contact_from_scene`).
    contact_gap : float, optional
        With a ``[lubricant]`` section: the gap (m) at which the asperities
        touch.  The body then first approaches through the squeeze film
        (:func:`squeeze_approach` from ``h0 = [lubricant].film_thickness``)
        and the friction acts on the load the solid contact carries,
        ``contact_force(t)``; the result gets ``squeeze`` (that approach).
        The approach is overdamped here (normal inertia neglected: it costs
        ~10x more and the film damps the normal mode); use
        :func:`squeeze_approach` with ``mass`` for the inertial one.
        Without it the normal direction stays quasi-static (dry).
    **overrides
        Fields of :class:`StickSlipParams`.
    """
    if contact_law not in ("rigid", "mdr"):
        raise ParameterError("contact_law", "one of ['rigid', 'mdr']", contact_law)
    if law is None:
        if mu is None:
            mu = friction_coefficient(scene).mu
        law = ConstantFriction(mu)
    kc = None
    if contact_stiffness is not None:
        overrides["contact_stiffness"] = float(contact_stiffness)
    elif contact_law == "mdr":
        p0 = params_from_scene(scene, **overrides)
        kc = contact_from_scene(scene, mu=law.mu_s, rng=rng).stiffness_table(
            max(p0.normal_force, 1e-9)
        )
    params = params_from_scene(scene, **overrides)
    if contact_gap is None:
        return stick_slip(params, law, method=method, contact_stiffness=kc)
    sq = squeeze_approach(
        squeeze_params_from_scene(
            scene,
            normal_force=params.normal_force,
            duration=params.duration,
            mass=0.0,
            contact_gap=contact_gap,
        ),
        contact_from_scene(scene, mu=law.mu_s, rng=rng),
        n_out=2001,
    )
    res = stick_slip(
        params,
        law,
        method="rk45" if method in ("auto", "analytic") else method,
        contact_stiffness=kc,
        normal_load=(sq.t, sq.contact_force),
    )
    res["squeeze"] = sq
    return res


def oscillation_from_scene(
    scene,
    amplitude: float,
    *,
    frequency: float | None = None,
    cycles: int = 3,
    steps_per_cycle: int = 200,
    mu: float | None = None,
    rng=None,
    progress=None,
):
    """Chain entry point.

    Prescribed tangential oscillation of the scene's contact (micro-slip loops).

    ``progress(fraction, what)`` is called ~200 times over the steps (long runs).
    """
    ts = scene.tribospectroscopy
    f = frequency or (ts.frequency if ts is not None else 65e3)
    p = OscillationParams(
        normal_force=scene.load.normal_force,
        amplitude=amplitude,
        frequency=f,
        cycles=cycles,
        steps_per_cycle=steps_per_cycle,
    )
    return oscillate(p, contact_from_scene(scene, mu=mu, rng=rng), progress=progress)
