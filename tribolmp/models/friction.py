"""The one decision of the friction coefficient, for every consumer of a scene.

The macroscale rigid body, the tribospectroscopy probe, the MDR contact springs
and the CLI all ask :func:`friction_coefficient`; nothing else picks a mu.
Precedence (the first that gives a value):

1. ``rates``: the nanoscale hand-off (the MCA's measured ``mu``, a
   :class:`~tribolmp.records.Rates` record), when the chain has one;
2. the scene's ``[rates]`` section (rates given directly, ``[rates].mu``);
3. ``[load].friction_coefficient`` (the Coulomb coefficient of a scene with
   neither).

Static and kinetic coefficients default to ``mu`` when the source does not
give them separately (``mu_static`` / ``mu_kinetic`` of the record).  The
running-in work of issue 15 extends this function (mu at the part's
pressure and velocity from the nanoscale table), not its callers.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..records import Rates

__all__ = ["FrictionChoice", "friction_coefficient"]


@dataclass(frozen=True)
class FrictionChoice:
    """The friction coefficient a scene's consumers use, and where it comes from.

    Attributes
    ----------
    mu : float
        Friction coefficient (dimensionless), the constant (Coulomb) law.
    mu_static, mu_kinetic : float
        Static and kinetic coefficients (equal to ``mu`` unless the source gives both).
    source : str
        One line naming the source (report field ``mu_source``).
    """

    mu: float
    mu_static: float
    mu_kinetic: float
    source: str


def friction_coefficient(scene, rates: Rates | None = None) -> FrictionChoice:
    """Decide the friction coefficient of ``scene`` (see the module docstring for the precedence).

    Parameters
    ----------
    scene : Scene
        The validated scene.
    rates : Rates, optional
        Rates handed on by the chain (the nanoscale stage's ``rates.json``).

    Returns
    -------
    FrictionChoice
    """
    candidates = []
    if rates is not None:
        candidates.append((rates, rates.source or "nanoscale rates"))
    if getattr(scene, "rates", None) is not None:
        candidates.append((scene.rates.to_record(), "[rates].mu"))
    for rec, src in candidates:
        if rec.mu is not None:
            mu = float(rec.mu)
            ms = float(rec.mu_static) if rec.mu_static is not None else mu
            mk = float(rec.mu_kinetic) if rec.mu_kinetic is not None else mu
            return FrictionChoice(mu, ms, mk, src)
    mu = float(scene.load.friction_coefficient)
    return FrictionChoice(mu, mu, mu, "[load].friction_coefficient")
