"""Multirate integration: a 65 kHz oscillation over a slow drift.

Brute force resolves every oscillation cycle (tens of quasi-static steps per
cycle of 15 us, i.e. ~10^6-10^7 steps per second of drift).  The averaged
scheme uses that a contact spring with Coulomb slip is rate independent:
under ``u = X(t) + a sin(w t)`` with a slow ``X`` each MDR spring ``i``
(stiffness ``k_i``, normal force ``q_i``) settles within a cycle into either

* elastic shakedown (``k_i a < mu q_i``): its cycle-mean force follows ``X``
  like a Coulomb spring whose limit is reduced to ``mu q_i - k_i a``, or
* alternating slip (``k_i a >= mu q_i``): zero mean force.

The cycle-averaged contact is therefore again a row of Coulomb springs, with
reduced limits (:class:`AveragedContact`); its steps only need to resolve the
slow motion ``X``, independently of the oscillation frequency.  The error is
of order of the drift per cycle over the amplitude, ``V / (a w)``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...scene.fields import param, validate_dataclass
from ..base import MethodRegistry, Result, timed

__all__ = ["AveragedContact", "DriftParams", "drift_under_oscillation", "DRIFT_SCHEMES"]

DRIFT_SCHEMES = MethodRegistry("multirate scheme")


class AveragedContact:
    """Cycle-averaged MDR contact under an oscillation of amplitude ``a`` (per contact).

    Parameters
    ----------
    spring_normal : ndarray
        Normal force of every spring (N).
    spring_stiffness : ndarray
        Tangential stiffness of every spring (N/m).
    mu : float
        Coulomb coefficient.
    amplitude : float
        Oscillation amplitude ``a`` (m).
    """

    def __init__(self, spring_normal, spring_stiffness, mu: float, amplitude: float):
        self.k = np.asarray(spring_stiffness, dtype=float) * np.ones_like(np.asarray(spring_normal, dtype=float))
        self.limit = np.maximum(0.0, mu * np.asarray(spring_normal, dtype=float) - self.k * amplitude)
        self.e = np.zeros_like(self.k)  # elastic elongation of the averaged springs (m)
        self.X = 0.0

    def step(self, X: float) -> float:
        """Move the slow coordinate to ``X`` (m); return the cycle-mean tangential force (N)."""
        e = self.e + (X - self.X)
        with np.errstate(divide="ignore", invalid="ignore"):
            cap = np.where(self.k > 0, self.limit / self.k, 0.0)
        self.e = np.clip(e, -cap, cap)
        self.X = float(X)
        return float(np.dot(self.k, self.e))

    @property
    def static_force(self) -> float:
        """Largest cycle-mean force the contact holds without sliding (N): ``sum(limit)``."""
        return float(self.limit.sum())


@dataclass(frozen=True)
class DriftParams:
    """The two-contact probe dragged at ``V`` while its ends oscillate at ``f`` (SI).

    Attributes
    ----------
    normal_force : float
        Load per contact (N).
    amplitude : float
        Per-contact amplitude a (m).
    frequency : float
        Oscillation frequency (Hz).
    velocity : float
        Slow drift speed V (m/s).
    duration : float
        Simulated time (s).
    steps_per_cycle : int
        Brute force: quasi-static steps per oscillation cycle.
    slow_steps : int
        Averaged scheme: steps over the whole duration.
    """

    normal_force: float = param(5.0, unit="N", lo=0.0, lo_open=True, hi=1e9)
    amplitude: float = param(1e-7, unit="m", lo=0.0, hi=1e-2)
    frequency: float = param(65e3, unit="Hz", lo=0.0, lo_open=True, hi=1e9)
    velocity: float = param(1e-4, unit="m/s", lo=0.0, hi=10.0)
    duration: float = param(2e-3, unit="s", lo=0.0, lo_open=True, hi=1e6)
    steps_per_cycle: int = param(64, lo=8, hi=10**5)
    slow_steps: int = param(400, lo=2, hi=10**8)

    def __post_init__(self):
        validate_dataclass(self)


def drift_under_oscillation(params: DriftParams, contact, *, scheme: str = "averaged") -> Result:
    """Force on the probe while it drifts and its two contacts oscillate in antiphase.

    Contact 1 moves as ``X + a sin(w t)``, contact 2 as ``X - a sin(w t)``
    (the probe's length oscillates), ``X = V t``.

    Parameters
    ----------
    params : DriftParams
    contact : ContactSprings
        One contact's spring row (both contacts are identical).
    scheme : {"averaged", "brute"}

    Returns
    -------
    Result
        ``t`` (s) and ``force`` (N): cycle-mean total force at the end of
        every cycle (brute) or at every slow step (averaged); ``steps``.
    """
    run = DRIFT_SCHEMES.get(scheme, "scheme")
    res = Result(method=scheme)
    with timed(res):
        t, f, steps = run(params, contact)
    res.update(t=t, force=f, nit=steps, steps=steps, units={"t": "s", "force": "N"})
    return res


@DRIFT_SCHEMES.register("brute")
def _brute(p: DriftParams, contact):
    d = contact.indentation(p.normal_force)
    c1, c2 = contact.tangential(), contact.tangential()
    c1.step(d, 0.0)
    c2.step(d, 0.0)
    n_cyc = max(1, int(round(p.duration * p.frequency)))
    spc = p.steps_per_cycle
    tau = np.arange(1, spc + 1) / spc  # phases within a cycle; trapezoid mean below
    means = np.empty(n_cyc)
    for j in range(n_cyc):
        t = (j + tau) / p.frequency
        X = p.velocity * t
        osc = p.amplitude * np.sin(2 * np.pi * (j + tau))
        f = np.array([c1.step(d, x + o)[1] + c2.step(d, x - o)[1] for x, o in zip(X, osc)])
        means[j] = f.mean()
    t_end = np.arange(1, n_cyc + 1) / p.frequency
    return t_end - 0.5 / p.frequency, means, n_cyc * spc


@DRIFT_SCHEMES.register("averaged")
def _averaged(p: DriftParams, contact):
    q, k = contact.springs(p.normal_force)
    avg = AveragedContact(q, k, contact.mu, p.amplitude)
    t = np.linspace(0.0, p.duration, p.slow_steps + 1)  # includes the initial state
    f = np.array([2.0 * avg.step(p.velocity * ti) for ti in t])
    return t, f, p.slow_steps
