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

A body pulled through a spring (:func:`pulled_under_oscillation`) slides at
speeds ``v`` comparable to ``a w`` during slip, where that limit is no longer
small: the steady cycle-mean force of a spring under ``v t + a sin(w t)`` is
``mu q Phi(v/(a w), k a/(mu q))`` (:func:`jenkins_mean_force`), tabulated
once per run in ``v`` for every spring, and the averaged springs are clipped
to these speed-dependent limits.  The body's steps then resolve only its own
mode on the contact, ``2 pi sqrt(m/(k_d + k_c))``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...params import param, validate_dataclass
from ..base import MethodRegistry, Result, timed

__all__ = [
    "AveragedContact",
    "DriftParams",
    "drift_under_oscillation",
    "DRIFT_SCHEMES",
    "jenkins_mean_force",
    "PulledParams",
    "pulled_under_oscillation",
    "PULLED_SCHEMES",
]

DRIFT_SCHEMES = MethodRegistry("multirate scheme")
PULLED_SCHEMES = MethodRegistry("pulled-body multirate scheme")


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
    frequency : float, optional
        Oscillation frequency ``f`` (Hz).  Given, the limits depend on the slow
        sliding speed ``v`` through the table ``mu q_i Phi(|v|/(a w), k_i a/(mu q_i))``
        of :func:`jenkins_mean_force` (``n_velocity`` speeds, linear
        interpolation); without it, the ``v -> 0`` limits (imposed slow drift).
    """

    def __init__(
        self,
        spring_normal,
        spring_stiffness,
        mu: float,
        amplitude: float,
        frequency: float | None = None,
        n_velocity: int = 65,
    ):
        q = np.asarray(spring_normal, dtype=float)
        self.k = np.asarray(spring_stiffness, dtype=float) * np.ones_like(q)
        self.slide = mu * q  # sliding limit of every spring (N)
        self.limit = np.maximum(0.0, self.slide - self.k * amplitude)
        self.e = np.zeros_like(self.k)  # elastic elongation of the averaged springs (m)
        self.X = 0.0
        self.va = (
            amplitude * 2 * np.pi * frequency if frequency else None
        )  # velocity amplitude a w (m/s)
        if self.va:
            # Table of the per-spring cycle-mean limit against nu = |v|/(a
            # w) (sin-spaced: arcsin-like near 1).
            self.nu = np.sin(0.5 * np.pi * np.linspace(0.0, 1.0, n_velocity))
            with np.errstate(divide="ignore", invalid="ignore"):
                kappa = np.where(self.slide > 0, self.k * amplitude / self.slide, 0.0)
            self.table = self.slide[:, None] * jenkins_mean_force(self.nu[None, :], kappa[:, None])

    def limits(self, velocity: float = 0.0) -> np.ndarray:
        """Cycle-mean force limit of every spring (N) at slow sliding speed ``velocity`` (m/s).

        Without a frequency (or at ``velocity = 0``) the shakedown limits ``max(0, mu q - k a)``.
        """
        if not self.va or velocity == 0.0:
            return self.limit
        nu = min(abs(velocity) / self.va, 1.0)
        j = min(int(np.searchsorted(self.nu, nu, side="right")) - 1, self.nu.size - 2)
        w = (nu - self.nu[j]) / (self.nu[j + 1] - self.nu[j])
        return (1.0 - w) * self.table[:, j] + w * self.table[:, j + 1]

    def step(self, X: float, velocity: float = 0.0) -> float:
        """Move the slow coordinate to ``X`` (m) at slow speed ``velocity`` (m/s).

        Return the cycle-mean force (N).
        """
        e = self.e + (X - self.X)
        with np.errstate(divide="ignore", invalid="ignore"):
            cap = np.where(self.k > 0, self.limits(velocity) / self.k, 0.0)
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
    sliding_velocity : float
        Slow drift (sliding) speed V (m/s).
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
    sliding_velocity: float = param(1e-4, unit="m/s", lo=0.0, hi=10.0)
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
        X = p.sliding_velocity * t
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
    f = np.array([2.0 * avg.step(p.sliding_velocity * ti) for ti in t])
    return t, f, p.slow_steps


# ------------------------------------------------------------ pulled body


def jenkins_mean_force(nu, kappa, *, points_per_cycle: int = 2048, cycles: int = 3):
    """Steady cycle-mean force of one Coulomb spring under drift plus oscillation.

    In units of its slip limit.

    The spring (stiffness k, slip limit F_s) is driven by ``u = v t + a sin(w t)``.
    In units of ``F_s`` and ``F_s/k`` the drive is ``kappa (nu theta + sin theta)``
    with ``kappa = k a / F_s`` and ``nu = v / (a w)``, so the steady mean force
    ``Phi(nu, kappa)`` depends on these two numbers only (the spring is rate
    independent).  Limits: ``Phi(0+, kappa) = max(0, 1 - kappa)`` (shakedown),
    ``Phi(nu, inf) = (2/pi) arcsin(nu)`` (rigid-plastic), ``Phi = 1`` for
    ``nu >= 1`` or ``kappa = 0``.  Computed by stepping the spring (exact for a
    rate-independent element) over ``cycles`` cycles from a start on the steady
    branch; the mean is taken over the last cycle.  Broadcasts ``nu``, ``kappa``.
    """
    nu, kappa = np.broadcast_arrays(
        np.abs(np.asarray(nu, dtype=float)), np.asarray(kappa, dtype=float)
    )
    # start at theta = 0 with the force the steady cycle has there when it slips at the top (kappa
    # < 1) or at the bottom (kappa >= 1); one slip erases the memory, so the last cycle is steady
    e = np.where(
        kappa < 1.0, 1.0 - kappa, np.clip(-1.0 + kappa * (1.0 + 0.5 * np.pi * nu), -1.0, 1.0)
    )
    theta = 2 * np.pi * np.arange(1, points_per_cycle + 1) / points_per_cycle
    u_prev = np.zeros_like(nu)
    acc = np.zeros_like(nu)
    for c in range(cycles):
        for th in theta:
            u = kappa * (nu * (th + 2 * np.pi * c) + np.sin(th))
            e = np.clip(e + (u - u_prev), -1.0, 1.0)
            u_prev = u
            if c == cycles - 1:
                acc += e
    return np.where(kappa == 0.0, 1.0, acc / points_per_cycle)


@dataclass(frozen=True)
class PulledParams:
    """Body of mass m pulled through a spring at V over a contact oscillating at f (SI).

    The contact's relative displacement is ``x(t) + a sin(2 pi f t)`` (the plate
    under the body oscillates tangentially); the body starts at rest, unloaded
    drive spring.

    Attributes
    ----------
    mass : float
        Body mass m (kg).
    drive_stiffness : float
        Pulling-spring stiffness k_d (N/m).
    drive_velocity : float
        Speed V of the spring's end (m/s).
    normal_force : float
        Normal load on the contact (N).
    amplitude : float
        Oscillation amplitude a (m).
    frequency : float
        Oscillation frequency f (Hz).
    duration : float
        Simulated time (s).
    steps_per_cycle : int
        Brute force: steps per oscillation cycle.
    steps_per_period : int
        Averaged scheme: steps per period ``2 pi sqrt(m/(k_d + k_contact))`` of the slow
        body-contact mode.
    """

    mass: float = param(0.1, unit="kg", lo=0.0, lo_open=True, hi=1e6)
    drive_stiffness: float = param(1e6, unit="N/m", lo=0.0, lo_open=True, hi=1e15)
    drive_velocity: float = param(1e-2, unit="m/s", lo=0.0, hi=1e3)
    normal_force: float = param(5.0, unit="N", lo=0.0, lo_open=True, hi=1e9)
    amplitude: float = param(1e-7, unit="m", lo=0.0, hi=1e-2)
    frequency: float = param(65e3, unit="Hz", lo=0.0, lo_open=True, hi=1e9)
    duration: float = param(2e-3, unit="s", lo=0.0, lo_open=True, hi=1e6)
    steps_per_cycle: int = param(32, lo=8, hi=10**5)
    steps_per_period: int = param(32, lo=8, hi=10**6)

    def __post_init__(self):
        validate_dataclass(self)


def pulled_under_oscillation(params: PulledParams, contact, *, scheme: str = "averaged") -> Result:
    """Spring-pulled body on an MDR contact whose base oscillates at ``f`` (the multirate problem).

    ``brute`` steps the full :class:`TangentialMDR` at ``steps_per_cycle`` per
    oscillation cycle (semi-implicit Euler).  ``averaged`` replaces the contact
    by :class:`AveragedContact` with the tabulated cycle-mean limits
    ``mu q_i Phi(|v|/(a w), k_i a/(mu q_i))`` (:func:`jenkins_mean_force`) and
    steps only the slow body motion, with a step set by the body-contact
    mode and independent of ``f``.  Averaging error: ``O(1/(f T_slow))`` and
    the elastic lag of the springs neglected in ``Phi``.

    Returns
    -------
    Result
        ``t`` (s), ``x`` (m), ``v`` (m/s), ``friction`` (N, cycle-mean contact
        force for brute, averaged force otherwise), ``drive_force`` (N), ``steps``.
    """
    run = PULLED_SCHEMES.get(scheme, "scheme")
    res = Result(method=scheme)
    with timed(res):
        t, x, v, f, steps = run(params, contact)
    res.update(
        t=t,
        x=x,
        v=v,
        friction=f,
        drive_force=params.drive_stiffness * (params.drive_velocity * t - x),
        nit=steps,
        steps=steps,
        units={"t": "s", "x": "m", "v": "m/s", "friction": "N", "drive_force": "N"},
    )
    return res


@PULLED_SCHEMES.register("brute")
def _pulled_brute(p: PulledParams, contact):
    d = contact.indentation(p.normal_force)
    tang = contact.tangential()
    tang.step(d, 0.0)
    spc = p.steps_per_cycle
    n_cyc = max(1, round(p.duration * p.frequency))
    dt = 1.0 / (p.frequency * spc)
    m, kd, V = p.mass, p.drive_stiffness, p.drive_velocity
    x = v = 0.0
    fc = 0.0
    out = np.empty((n_cyc, 3))
    for j in range(n_cyc):
        sx = sv = sf = 0.0
        for i in range(spc):
            t = (j * spc + i) * dt
            v += dt * (kd * (V * t - x) - fc) / m
            x += dt * v
            fc = tang.step(d, x + p.amplitude * math.sin(2 * math.pi * (i + 1) / spc))[1]
            sx, sv, sf = sx + x, sv + v, sf + fc
        out[j] = sx / spc, sv / spc, sf / spc
    t_mid = (np.arange(n_cyc) + 0.5 + 0.5 / spc) / p.frequency  # centre of each cycle's samples
    return t_mid, out[:, 0], out[:, 1], out[:, 2], n_cyc * spc


@PULLED_SCHEMES.register("averaged")
def _pulled_averaged(p: PulledParams, contact):
    q, k = contact.springs(p.normal_force)
    avg = AveragedContact(q, k, contact.mu, p.amplitude, p.frequency)
    m, kd, V = p.mass, p.drive_stiffness, p.drive_velocity
    period = 2 * math.pi * math.sqrt(m / (kd + float(np.sum(avg.k))))
    n = max(2, math.ceil(p.duration / period * p.steps_per_period))
    dt = p.duration / n
    t = np.arange(n + 1) * dt
    xs, vs, fs = np.zeros(n + 1), np.zeros(n + 1), np.zeros(n + 1)
    x = v = fc = 0.0
    for i in range(n):
        v += dt * (kd * (V * t[i] - x) - fc) / m
        x += dt * v
        fc = avg.step(x, v)
        xs[i + 1], vs[i + 1], fs[i + 1] = x, v, fc
    return t, xs, vs, fs, n
