"""Tribospectroscopy: friction force against oscillation amplitude (seed Section 5, Figs. 7-8).

Forward models (:mod:`.models`), the inverse problem (:mod:`.fit`) and the
scene adapters used by the CLI and the multiscale chain.

Amplitude convention: every ``amplitude`` inside this package is the
*per-contact* amplitude ``a = dl/4`` (``dl`` the peak-to-peak change of the
probe length); ``convention="probe"`` at the boundaries means the end-face
amplitude ``dl/2 = 2a`` of the paper.  Characteristic lengths (``lambda``,
``mu N / k``) are per contact.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...errors import ParameterError
from ...params import param, validate_dataclass
from ..base import MethodRegistry, Result, timed
from .fit import MeasuredCurve, fit_length, read_curve_csv, write_curve_csv
from .models import (
    CONVENTION_TEXT,
    CONVENTIONS,
    microslip_force,
    pinning_force_sq,
    pinning_shape,
    shakedown_force,
    to_per_contact,
)

__all__ = [
    "TribospecParams",
    "solve",
    "params_from_scene",
    "tribospec_from_scene",
    "MODELS",
    "fit_length",
    "read_curve_csv",
    "write_curve_csv",
    "MeasuredCurve",
    "pinning_shape",
    "pinning_force_sq",
    "shakedown_force",
    "microslip_force",
    "to_per_contact",
    "CONVENTIONS",
    "CONVENTION_TEXT",
]

MODELS = MethodRegistry("tribospectroscopy model")


@dataclass(frozen=True)
class TribospecParams:
    """The oscillating two-contact probe (SI; amplitudes per contact).

    Attributes
    ----------
    amplitudes : tuple of float
        Per-contact amplitudes a (m).
    model : {"potential", "stiffness"}
        Pinning-potential or contact-stiffness (shakedown) model.
    law : {"linear", "microslip"}
        Stiffness model only: one linear spring per contact (PHYSICS.md
        formula) or per-spring Coulomb slip on the MDR row.
    mu : float
        Coulomb coefficient.
    normal_force : float
        Load per contact N (N); the probe rests on two contacts.
    correlation_length : float
        Pinning correlation length lambda (m).
    force0 : float
        Potential model: friction force of both contacts at a = 0 (N); 0 means ``2 mu N``.
    background_sq : float
        Potential model: amplitude-independent background of F^2 (N^2).
    contact_stiffness : float
        Tangential stiffness k of one contact (N/m); 0 = from the MDR contact.
    profile : {"sphere", "cone", "flat"}
        Shape of each contact for the MDR row.
    radius, half_angle_deg : float
        Sphere/punch radius (m), cone half-angle (deg).
    E_star, G_star : float
        Effective normal and MDR tangential moduli (Pa).
    n_springs : int
        MDR springs per contact.
    frequency : float
        Oscillation frequency (Hz); the quasi-static models do not depend on it
        as long as the drift per cycle is small (recorded in the output).
    """

    amplitudes: tuple[float, ...] = param(
        tuple(i * 1e-8 for i in range(51)), unit="m", lo=0.0, hi=1e-2
    )
    model: str = param("potential", choices=("potential", "stiffness"))
    law: str = param("linear", choices=("linear", "microslip"))
    mu: float = param(0.3, lo=0.0, lo_open=True, hi=10.0)
    normal_force: float = param(5.0, unit="N", lo=0.0, lo_open=True, hi=1e9)
    correlation_length: float = param(50e-9, unit="m", lo=0.0, lo_open=True, hi=1e-2)
    force0: float = param(0.0, unit="N", lo=0.0, hi=1e12)
    background_sq: float = param(0.0, unit="N^2", lo=0.0, hi=1e24)
    contact_stiffness: float = param(0.0, unit="N/m", lo=0.0, hi=1e18)
    profile: str = param("sphere", choices=("sphere", "cone", "flat"))
    radius: float = param(5e-3, unit="m", lo=0.0, lo_open=True, hi=10.0)
    half_angle_deg: float = param(80.0, unit="deg", lo=0.0, lo_open=True, hi=90.0, hi_open=True)
    E_star: float = param(113.2e9, unit="Pa", lo=0.0, lo_open=True, hi=1e13)
    G_star: float = param(93.2e9, unit="Pa", lo=0.0, lo_open=True, hi=1e13)
    n_springs: int = param(401, lo=3, hi=10**7)
    frequency: float = param(65e3, unit="Hz", lo=0.0, lo_open=True, hi=1e9)

    def __post_init__(self):
        validate_dataclass(self)
        if not self.amplitudes:
            raise ParameterError("amplitudes", "at least one amplitude", self.amplitudes)

    def contact(self):
        """Return the MDR spring row of one contact.

        A :class:`~tribolmp.models.macro.contact.ContactSprings`.
        """
        from ..macro.contact import ContactSprings, profile_from_geometry

        x, g = profile_from_geometry(
            self.profile,
            self.normal_force,
            self.E_star,
            n_springs=self.n_springs,
            radius=self.radius,
            half_angle_deg=self.half_angle_deg,
        )
        return ContactSprings(x, g, self.E_star, self.G_star, self.mu)


@MODELS.register("potential")
def _potential(p: TribospecParams, a: np.ndarray) -> tuple[np.ndarray, dict]:
    f0 = p.force0 or 2.0 * p.mu * p.normal_force
    f2 = pinning_force_sq(a, p.correlation_length, f0, p.background_sq)
    return f2, dict(length_m=p.correlation_length, force0_N=f0)


@MODELS.register("stiffness")
def _stiffness(p: TribospecParams, a: np.ndarray) -> tuple[np.ndarray, dict]:
    mu_n = p.mu * p.normal_force
    if p.law == "microslip":
        contact = p.contact()
        q, k = contact.springs(p.normal_force)
        f = microslip_force(a, q, k, p.mu)
        k_tot = float(np.sum(k[q > 0]))
        # zero mean force once even the centre spring alternates: a >= mu q_i / k_i for all i
        limit = float(np.max(np.where(k > 0, p.mu * q / np.where(k > 0, k, 1.0), 0.0)))
    else:
        k_tot = p.contact_stiffness or p.contact().stiffness(p.normal_force)
        f = shakedown_force(a, mu_n, k_tot)
        limit = mu_n / k_tot
    return f * f, dict(length_m=mu_n / k_tot, contact_stiffness_N_m=k_tot, shakedown_limit_m=limit)


def solve(params: TribospecParams, *, method: str | None = None, rng=None) -> Result:
    """Friction force of the probe at every amplitude.

    Parameters
    ----------
    params : TribospecParams
    method : str, optional
        Model name; defaults to ``params.model``.
    rng : ignored
        The forward models are deterministic.

    Returns
    -------
    Result
        ``amplitude_m`` (per contact), ``force_N``, ``force_sq_N2``,
        ``length_m`` (lambda or mu N / k, per contact), model extras
        (``contact_stiffness_N_m``, ``shakedown_limit_m``, ``force0_N``),
        ``amplitude_convention``.
    """
    name = method or params.model
    model = MODELS.get(name, "model")
    res = Result(method=name)
    with timed(res):
        a = np.asarray(params.amplitudes, dtype=float)
        f2, extra = model(params, a)
    res.update(
        amplitude_m=a,
        force_N=np.sqrt(f2),
        force_sq_N2=f2,
        model=name,
        law=params.law if name == "stiffness" else "",
        convention="per-contact",
        amplitude_convention=CONVENTION_TEXT["per-contact"],
        frequency_Hz=params.frequency,
        units={
            "amplitude_m": "m",
            "force_N": "N",
            "force_sq_N2": "N^2",
            "length_m": "m",
            "contact_stiffness_N_m": "N/m",
            "shakedown_limit_m": "m",
            "force0_N": "N",
            "frequency_Hz": "Hz",
        },
        **extra,
    )
    res.message = f"{name}: {a.size} amplitudes, characteristic length {extra['length_m']:.3g} m"
    return res


def params_from_scene(scene, **overrides) -> TribospecParams:
    """Build :class:`TribospecParams` from a :class:`~tribolmp.scene.Scene`.

    Reads ``[tribospectroscopy]`` (amplitudes converted to per contact,
    model, correlation length, frequency), ``[load]`` (``normal_force`` shared
    by the two contacts; ``friction_coefficient``, or ``[rates].mu`` when
    given), ``[geometry]`` (sphere/cone/flat contact; ``rough`` uses the
    sphere of ``radius`` as the probe tip unless ``contact_stiffness`` is
    passed) and the effective moduli.  Keyword ``overrides`` replace fields.
    """
    from ...scene.schema import Tribospectroscopy
    from ..friction import friction_coefficient

    ts = scene.tribospectroscopy or Tribospectroscopy()
    geo = scene.geometry
    mu = friction_coefficient(scene).mu  # the one decision of mu (nanoscale/[rates]/[load])
    amps = tuple(float(v) for v in to_per_contact(np.asarray(ts.amplitudes, float), ts.convention))
    kw = dict(
        amplitudes=amps,
        model=ts.model,
        mu=mu,
        normal_force=scene.load.normal_force / 2.0,
        correlation_length=ts.correlation_length,
        profile=geo.profile if geo.profile in ("sphere", "cone", "flat") else "sphere",
        radius=geo.radius,
        half_angle_deg=geo.half_angle_deg,
        E_star=scene.effective_modulus,
        G_star=scene.effective_shear_modulus,
        n_springs=max(3, min(scene.contact.springs, 4001)),
        frequency=ts.frequency,
    )
    kw.update(overrides)
    return TribospecParams(**kw)


def tribospec_from_scene(scene, contact_stiffness: float | None = None, *, model: str | None = None,
                         amplitudes=None, law: str = "linear") -> Result:
    """Chain entry point: the F(a) curve of a scene.

    Parameters
    ----------
    scene : Scene
    contact_stiffness : float, optional
        Tangential stiffness of one contact (N/m), e.g. from the contact
        model's ``stiffness_vs_load`` for a rough surface; default: MDR
        stiffness of the scene's contact shape.
    model : str, optional
        ``potential`` or ``stiffness``; default the scene's.
    amplitudes : array_like, optional
        Per-contact amplitudes (m); default the scene's.
    law : {"linear", "microslip"}
        Stiffness-model variant.
    """
    over = {"law": law}
    if contact_stiffness is not None:
        k = float(contact_stiffness)
        if not (math.isfinite(k) and k > 0):
            # A zero or non-finite stiffness from upstream is a failed contact stage, not "use MDR".
            raise ParameterError(
                "contact_stiffness", "a finite stiffness > 0 N/m from the contact model", k
            )
        over["contact_stiffness"] = k
    if model is not None:
        over["model"] = model
    if amplitudes is not None:
        over["amplitudes"] = tuple(float(v) for v in np.atleast_1d(amplitudes))
    return solve(params_from_scene(scene, **over))
