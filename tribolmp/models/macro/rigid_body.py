"""A rigid body of mass m on nonlinear contact springs (seed Section 2, Fig. 4).

Tangential dynamics along the sliding direction; the normal direction is
quasi-static (the MDR normal law maps load <-> indentation), or, with a
lubricant, the squeeze-film approach of :mod:`.normal` whose solid-contact
load enters here as a tabulated ``normal_load``.  Two drives:

* :func:`stick_slip` -- the body is pulled through a spring of stiffness
  ``k_d`` whose end moves at ``V``.  The contact either sticks or slips with a
  chosen :mod:`friction law <tribolmp.models.macro.friction>`.  Phases are
  integrated separately and switched by located events (stick -> slip when the
  contact force reaches ``mu_s N``, slip -> stick when the velocity returns to
  zero and the spring force is within ``mu_s N``).  Because the switching
  conditions differ (a force threshold one way, a velocity zero the other),
  there is no chattering.  The contact is either rigid during stick, or a
  tangential spring ``k_c`` (the MDR stiffness of the sticking springs) with
  damping; large ``k_c`` makes the stick phase stiff, which the implicit
  Radau/BDF integrators handle with steps set by the slow dynamics.
* :func:`oscillate` -- a prescribed tangential oscillation (plus an optional
  drift) of the body on an MDR contact with per-spring slip and memory
  (:class:`~tribolmp.models.contact.mdr.TangentialMDR`): Mindlin-Deresiewicz
  micro-slip hysteresis.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ...errors import BlowUpError, ConvergenceError, ParameterError
from ...params import param, validate_dataclass
from ...progress import call_progress
from ..base import MethodRegistry, Result, timed
from .friction import ConstantFriction, FrictionLaw

__all__ = ["StickSlipParams", "OscillationParams", "stick_slip", "oscillate", "STICK_SLIP_METHODS"]

STICK_SLIP_METHODS = MethodRegistry("stick-slip")

STICK, SLIP_POS, SLIP_NEG = 0, 1, -1


@dataclass(frozen=True)
class StickSlipParams:
    """Parameters of the spring-pulled rigid body (SI).

    Attributes
    ----------
    mass : float
        Body mass m (kg).
    drive_stiffness : float
        Pulling-spring stiffness k_d (N/m).
    drive_velocity : float
        Speed V of the spring's end (m/s).
    normal_force : float
        Normal load N (N) at t = 0.
    duration : float
        Simulated time (s).
    contact_stiffness : float
        Tangential stiffness k_c of the sticking contact (N/m); 0 = rigid contact.
    contact_damping_ratio : float
        Damping ratio of the contact spring during stick (1 = critical).
    unload_time : float
        If > 0, the normal load falls linearly to zero at this time (s).
    rtol : float
        Relative tolerance of the integrator.
    max_events : int
        Bound on stick/slip transitions (a guard against runaway switching).
    """

    mass: float = param(0.1, unit="kg", lo=0.0, lo_open=True, hi=1e6)
    drive_stiffness: float = param(1e6, unit="N/m", lo=0.0, lo_open=True, hi=1e15)
    drive_velocity: float = param(0.01, unit="m/s", lo=0.0, lo_open=True, hi=1e3)
    normal_force: float = param(10.0, unit="N", lo=0.0, hi=1e9)
    duration: float = param(0.05, unit="s", lo=0.0, lo_open=True, hi=1e6)
    contact_stiffness: float = param(0.0, unit="N/m", lo=0.0, hi=1e18)
    contact_damping_ratio: float = param(1.0, lo=0.0, hi=100.0)
    unload_time: float = param(0.0, unit="s", lo=0.0, hi=1e6)
    rtol: float = param(1e-9, lo=1e-13, hi=1e-2)
    max_events: int = param(200_000, lo=1, hi=10**8)

    def __post_init__(self):
        validate_dataclass(self)

    def load(self, t: float) -> float:
        """Return the normal load N(t) (N)."""
        if self.unload_time > 0:
            return self.normal_force * max(0.0, 1.0 - t / self.unload_time)
        return self.normal_force


class _Trace:
    """Collects samples and events of a piecewise run."""

    def __init__(self):
        self.t, self.x, self.v, self.phase = [], [], [], []
        self.events: list[dict] = []

    def add(self, t, x, v, phase):
        self.t.extend(np.atleast_1d(t).tolist())
        self.x.extend(np.atleast_1d(x).tolist())
        self.v.extend(np.atleast_1d(v).tolist())
        self.phase.extend([phase] * np.atleast_1d(t).size)

    def event(self, t, old, new, force, load):
        self.events.append(
            dict(
                t=float(t),
                from_phase=_NAME[old],
                to_phase=_NAME[new],
                force_N=float(force),
                normal_N=float(load),
            )
        )


_NAME = {STICK: "stick", SLIP_POS: "slip+", SLIP_NEG: "slip-"}


class _LoadTable:
    """``StickSlipParams`` seen with a tabulated normal load N(t).

    Piecewise linear between knots.
    """

    def __init__(self, params: StickSlipParams, t, n):
        t, n = np.asarray(t, dtype=float), np.asarray(n, dtype=float)
        if t.ndim != 1 or t.size < 2 or t.shape != n.shape:
            raise ParameterError(
                "normal_load",
                "two 1D arrays (t, N) of equal length >= 2",
                f"shapes {t.shape}, {n.shape}",
            )
        if not (
            np.all(np.isfinite(t))
            and np.all(np.isfinite(n))
            and np.all(np.diff(t) > 0)
            and np.all(n >= 0)
        ):
            raise ParameterError(
                "normal_load",
                "finite increasing times (s) and finite loads >= 0 N",
                "invalid entries",
            )
        self._p, self._t, self._n = params, t, n
        self.load_knots = t

    def __getattr__(self, name):
        if name.startswith(
            "_"
        ):  # only the params' public fields are forwarded (no recursion on _p)
            raise AttributeError(name)
        return getattr(self._p, name)

    def load(self, t: float) -> float:
        """Return the normal load N(t) (N), held constant outside the table."""
        return float(np.interp(t, self._t, self._n))


def stick_slip(params: StickSlipParams, law: FrictionLaw | None = None, *, method: str = "auto",
               contact_stiffness: Callable[[float], float] | None = None, x0: float = 0.0,
               normal_load: tuple | None = None) -> Result:
    """Integrate the spring-pulled body through stick and slip phases.

    Parameters
    ----------
    params : StickSlipParams
    law : FrictionLaw, optional
        Friction law; default ``ConstantFriction(0.3)``.
    method : {"auto", "radau", "radau-rk45", "bdf", "lsoda", "rk45", "analytic"}
        ODE integrator of each phase (``analytic``: exact closed-form segments,
        for a rigid contact, constant friction and constant load).  ``auto``
        picks ``analytic`` when it applies, else ``rk45`` for a rigid contact
        and ``radau-rk45`` (implicit Radau in the stiff stick phase, RK45 in
        slip) for a contact spring.
    contact_stiffness : callable, optional
        ``k_c(N)`` in N/m (e.g. :meth:`ContactSprings.stiffness_table`);
        overrides ``params.contact_stiffness`` so that the contact softens as
        the load vanishes.
    x0 : float
        Initial position (m); the body starts at rest in stick.
    normal_load : (t, N), optional
        Tabulated normal load on the contact (s, N), e.g. the ``contact_force``
        of :func:`~tribolmp.models.macro.normal.squeeze_approach` (the share
        of the load the solid contact carries beside the squeeze film); replaces
        ``params.normal_force``/``unload_time``.

    Returns
    -------
    Result
        ``t`` (s), ``x`` (m), ``v`` (m/s), ``drive_force`` (N), ``phase``
        (0 stick, +-1 slip), ``events`` (list of transitions with time, phases,
        force and load), ``n_transitions``, ``nfev``.
    """
    law = ConstantFriction(0.3) if law is None else law
    if normal_load is not None:
        params = _LoadTable(params, *normal_load)
    if method == "auto":
        rigid = contact_stiffness is None and params.contact_stiffness == 0.0
        if (
            rigid
            and isinstance(law, ConstantFriction)
            and params.unload_time == 0.0
            and normal_load is None
        ):
            method = "analytic"
        # explicit RK is fine for a rigid contact; a contact spring makes the stick phase stiff
        else:
            method = "rk45" if rigid else "radau-rk45"
    run = STICK_SLIP_METHODS.get(method)
    res = Result(method=method)
    with timed(res):
        tr, nfev = run(params, law, contact_stiffness, x0)
    params = getattr(params, "_p", params)
    t = np.array(tr.t)
    x = np.array(tr.x)
    if not np.all(np.isfinite(x)):
        raise BlowUpError("stick-slip: non-finite position")
    res.update(
        t=t, x=x, v=np.array(tr.v), phase=np.array(tr.phase, dtype=int),
        drive_force=params.drive_stiffness * (params.drive_velocity * t - x),
        events=tr.events, n_transitions=len(tr.events), nfev=nfev, nit=len(tr.events) + 1,
        units={"t": "s", "x": "m", "v": "m/s", "drive_force": "N"},
        message=f"{len(tr.events)} stick/slip transitions in {params.duration:g} s",
    )
    return res


def _guard(tr: _Trace, t_start: float, t_end: float, p: StickSlipParams, streak: int) -> int:
    """Count consecutive zero-length phases; many in a row would be chattering."""
    if len(tr.events) > p.max_events:
        raise ConvergenceError(f"stick-slip: more than max_events = {p.max_events} transitions")
    streak = streak + 1 if t_end - t_start <= 1e-12 * p.duration else 0
    if streak > 8:
        raise ConvergenceError(
            f"stick-slip: chattering at t = {t_end:g} s (repeated zero-length phases)"
        )
    return streak


def _next_phase(F: float, N: float, law: FrictionLaw, V: float) -> int:
    if N > 0 and abs(F) <= law.mu_s * N:
        return STICK
    return SLIP_POS if (F > 0 or (F == 0 and V > 0)) else SLIP_NEG


def _rigid_stick_end(
    p: StickSlipParams, law: FrictionLaw, t0: float, x: float
) -> tuple[float, int]:
    """First t > t0 where |k_d (V t - x)| reaches mu_s N(t).

    Both sides are piecewise linear in t.
    """
    k, V = p.drive_stiffness, p.drive_velocity
    inner = getattr(p, "load_knots", [p.unload_time])
    knots = [t0] + [float(tk) for tk in inner if t0 < tk < p.duration] + [p.duration]
    for a, b in zip(knots[:-1], knots[1:]):
        found = []
        for sgn in (1, -1):
            # g(t) = sgn k (V t - x) - mu_s N(t), linear on [a, b]
            ga = sgn * k * (V * a - x) - law.mu_s * p.load(a)
            gb = sgn * k * (V * b - x) - law.mu_s * p.load(b)
            if ga >= 0 and a == t0 and (gb > ga or ga > 0):
                found.append((t0, sgn))
            elif ga < 0 <= gb:
                found.append((a + (b - a) * (-ga) / (gb - ga), sgn))
        if found:
            return min(found)
    return p.duration, 0


def _ode_runner(solver: str, slip_solver: str | None = None):
    slip_solver = slip_solver or solver

    def run(p: StickSlipParams, law: FrictionLaw, kc_of_load, x0: float):
        from scipy.integrate import solve_ivp

        m, k, V = p.mass, p.drive_stiffness, p.drive_velocity
        kc = kc_of_load or (lambda N: p.contact_stiffness)
        rigid = kc_of_load is None and p.contact_stiffness == 0.0
        # steps are limited by the slow (drive) dynamics, never by the contact
        max_step = min(p.duration / 50, 2 * math.pi * math.sqrt(m / k) / 16)
        tr = _Trace()
        t, x, v, phase, anchor = 0.0, x0, 0.0, STICK, x0
        nfev, streak = 0, 0
        opts = dict(
            method=solver,
            rtol=p.rtol,
            atol=1e-12 * max(1.0, abs(V) * p.duration),
            max_step=max_step,
        )
        tr.add(t, x, v, phase)
        while t < p.duration:
            t_start = t
            if phase == STICK and rigid:
                t_new, sgn = _rigid_stick_end(p, law, t, x)
                tr.add(t_new, x, 0.0, STICK)
                t, v = t_new, 0.0
                if sgn == 0:
                    break
                new = SLIP_POS if sgn > 0 else SLIP_NEG
            elif phase == STICK and p.load(t) <= 0.0 and k * (V * t - x) != 0.0:
                # no load but a drive force: nothing can hold the body
                new = _next_phase(k * (V * t - x), 0.0, law, V)
            elif phase == STICK:
                # State (e, de/dt) with e = x - anchor the contact deformation:
                # e is ~mu N / k_c, tiny for a stiff contact, so it gets its own tolerance.
                def rhs(tt, y, s=anchor):
                    kk = kc(p.load(tt))
                    c = 2 * p.contact_damping_ratio * math.sqrt(kk * m)
                    return [y[1], (k * (V * tt - s - y[0]) - kk * y[0] - c * y[1]) / m]

                def jac(tt, y):
                    kk = kc(p.load(tt))
                    return [
                        [0.0, 1.0],
                        [-(k + kk) / m, -2 * p.contact_damping_ratio * math.sqrt(kk * m) / m],
                    ]

                def ev(tt, y):
                    kk = kc(p.load(tt))
                    c = 2 * p.contact_damping_ratio * math.sqrt(kk * m)
                    return abs(kk * y[0] + c * y[1]) - law.mu_s * p.load(tt)

                ev.terminal, ev.direction = True, 1
                k0 = max(kc(p.load(t)), 1e-300)
                e_scale = max(law.mu_s * p.load(t), k * V * max_step, 1e-30) / (k0 + k)
                sopts = dict(
                    opts, atol=[p.rtol * e_scale, p.rtol * e_scale * math.sqrt((k0 + k) / m)]
                )
                if solver in ("Radau", "BDF", "LSODA"):
                    sopts["jac"] = jac
                sol = solve_ivp(rhs, (t, p.duration), [x - anchor, v], events=ev, **sopts)
                nfev += sol.nfev
                tr.add(sol.t, anchor + sol.y[0], sol.y[1], STICK)
                t, x, v = float(sol.t[-1]), anchor + float(sol.y[0, -1]), float(sol.y[1, -1])
                if sol.status == -1:
                    raise ConvergenceError(
                        f"stick-slip: integrator failed at t = {t:g} s: {sol.message}"
                    )
                if sol.status != 1:
                    break
                kk = kc(p.load(t))
                fc = kk * float(sol.y[0, -1]) + 2 * p.contact_damping_ratio * math.sqrt(kk * m) * v
                new = SLIP_POS if fc > 0 else SLIP_NEG
            else:
                sgn = float(phase)

                def rhs(tt, y, sgn=sgn):
                    return [
                        y[1],
                        (k * (V * tt - y[0]) - sgn * law.kinetic(abs(y[1])) * p.load(tt)) / m,
                    ]

                def jac(tt, y, sgn=sgn):
                    h = 1e-6 * max(abs(y[1]), 1e-9)
                    dmu = (law.kinetic(abs(y[1]) + h) - law.kinetic(abs(y[1]))) / h
                    return [[0.0, 1.0], [-k / m, -dmu * p.load(tt) / m]]

                def ev(tt, y, sgn=sgn):
                    return sgn * y[1]

                ev.terminal, ev.direction = True, -1
                slip_opts = dict(opts, method=slip_solver)
                if slip_solver in ("Radau", "BDF", "LSODA"):
                    slip_opts["jac"] = jac
                sol = solve_ivp(rhs, (t, p.duration), [x, v], events=ev, **slip_opts)
                nfev += sol.nfev
                tr.add(sol.t, sol.y[0], sol.y[1], phase)
                t, x, v = float(sol.t[-1]), float(sol.y[0, -1]), float(sol.y[1, -1])
                if sol.status == -1:
                    raise ConvergenceError(
                        f"stick-slip: integrator failed at t = {t:g} s: {sol.message}"
                    )
                if sol.status != 1:
                    break
                N = p.load(t)
                new = _next_phase(k * (V * t - x), N, law, V)
                if new == STICK:
                    if rigid:
                        v = 0.0
                    else:  # the contact spring keeps the force it had at the end of the slip
                        kk = kc(N)
                        anchor = x - (sgn * law.kinetic(0.0) * N / kk if kk > 0 else 0.0)
            tr.event(t, phase, new, k * (V * t - x), p.load(t))
            streak = _guard(tr, t_start, t, p, streak)
            phase = new
        return tr, nfev

    return run


for _name, _solver in (("radau", "Radau"), ("bdf", "BDF"), ("lsoda", "LSODA"), ("rk45", "RK45")):
    STICK_SLIP_METHODS.register(_name)(_ode_runner(_solver))
# Only the stick phase on a contact spring is stiff: implicit there, explicit in slip.
STICK_SLIP_METHODS.register("radau-rk45")(_ode_runner("Radau", "RK45"))


@STICK_SLIP_METHODS.register("analytic")
def _analytic(p: StickSlipParams, law: FrictionLaw, kc_of_load, x0: float):
    """Exact event-driven segments: harmonic slip, linear stick (rigid, constant mu and N)."""
    if (
        not isinstance(law, ConstantFriction)
        or p.contact_stiffness != 0.0
        or kc_of_load is not None
        or p.unload_time > 0
        or isinstance(p, _LoadTable)
    ):
        raise ParameterError(
            "method",
            "'analytic' only with a constant friction law, rigid contact and constant load",
            "analytic",
        )
    m, k, V, N = p.mass, p.drive_stiffness, p.drive_velocity, p.normal_force
    w = math.sqrt(k / m)
    tr = _Trace()
    t, x, v, phase, streak = 0.0, x0, 0.0, STICK, 0
    tr.add(t, x, v, phase)
    while t < p.duration:
        t_start = t
        if phase == STICK:
            t_new, sgn = _rigid_stick_end(p, law, t, x)
            tr.add(t_new, x, 0.0, STICK)
            t = t_new
            if sgn == 0:
                break
            new = SLIP_POS if sgn > 0 else SLIP_NEG
        else:
            sgn = float(phase)
            xi0 = x - V * t + sgn * law.mu_k * N / k
            dxi0 = v - V
            R = math.hypot(xi0 * w, dxi0)
            phi = math.atan2(xi0 * w, dxi0)
            # v(tau) = V + R cos(w tau + phi); stop where sgn*v falls through 0
            tau_end = p.duration - t
            if R > abs(V) and R > 0:
                theta = math.acos(-V / R) * (1 if sgn > 0 else -1)
                tau = (theta - phi) / w
                period = 2 * math.pi / w
                tau = tau % period
                if tau <= 1e-14 * period:
                    tau += period
                tau_end = min(tau_end, tau)
            taus = np.linspace(0.0, tau_end, 33)
            xs = (
                V * (t + taus)
                - sgn * law.mu_k * N / k
                + xi0 * np.cos(w * taus)
                + dxi0 / w * np.sin(w * taus)
            )
            vs = V + R * np.cos(w * taus + phi)
            tr.add(t + taus, xs, vs, phase)
            t, x, v = t + tau_end, float(xs[-1]), float(vs[-1])
            if t >= p.duration:
                break
            v = 0.0
            new = _next_phase(k * (V * t - x), N, law, V)
        tr.event(t, phase, new, k * (V * t - x), N)
        streak = _guard(tr, t_start, t, p, streak)
        phase = new
    return tr, 0


# ---------------------------------------------------------------- oscillation


@dataclass(frozen=True)
class OscillationParams:
    """Prescribed tangential motion ``u(t) = u_mean + V t + A sin(2 pi f t)`` at constant load.

    Attributes
    ----------
    normal_force : float
        Normal load N (N).
    amplitude : float
        Tangential amplitude A (m).
    frequency : float
        Frequency f (Hz).
    cycles : int
        Number of cycles.
    steps_per_cycle : int
        Quasi-static steps per cycle.
    drift_velocity : float
        Superimposed slow drift V (m/s).
    """

    normal_force: float = param(10.0, unit="N", lo=0.0, hi=1e9)
    amplitude: float = param(1e-7, unit="m", lo=0.0, hi=1.0)
    frequency: float = param(65e3, unit="Hz", lo=0.0, lo_open=True, hi=1e9)
    cycles: int = param(3, lo=1, hi=10**7)
    steps_per_cycle: int = param(200, lo=8, hi=10**6)
    drift_velocity: float = param(0.0, unit="m/s", lo=-1e3, hi=1e3)

    def __post_init__(self):
        validate_dataclass(self)


def oscillate(params: OscillationParams, contact, *, progress=None) -> Result:
    """Drive an MDR contact with per-spring slip through a prescribed oscillation.

    Parameters
    ----------
    params : OscillationParams
    contact : ContactSprings
        The spring row (:class:`~tribolmp.models.macro.contact.ContactSprings`).

    Returns
    -------
    Result
        ``t`` (s), ``u`` (m), ``force_x`` (N), ``force_n`` (N),
        ``dissipation_per_cycle_J`` (J, loop area of every cycle),
        ``stiffness_x`` (N/m, final), ``indentation_m``.
    """
    res = Result(method="TangentialMDR quasi-static")
    with timed(res):
        d = contact.indentation(params.normal_force)
        tang = contact.tangential()
        n = params.cycles * params.steps_per_cycle
        t = np.arange(n + 1) / (params.steps_per_cycle * params.frequency)
        u = params.drift_velocity * t + params.amplitude * np.sin(2 * np.pi * params.frequency * t)
        fx = np.empty_like(t)
        fn = np.empty_like(t)
        tang.step(d, 0.0)
        for i, ui in enumerate(u):
            fn[i], fx[i] = tang.step(d, ui)
            call_progress(progress, i + 1, u.size, "oscillation steps")
        work = np.concatenate([[0.0], np.cumsum(0.5 * (fx[1:] + fx[:-1]) * np.diff(u))])
        per = work[:: params.steps_per_cycle]
        res.update(
            t=t,
            u=u,
            force_x=fx,
            force_n=fn,
            indentation_m=d,
            dissipation_per_cycle_J=np.diff(per),
            stiffness_x=tang.stiffness_x,
            nit=n,
            units={
                "t": "s",
                "u": "m",
                "force_x": "N",
                "force_n": "N",
                "dissipation_per_cycle_J": "J",
                "stiffness_x": "N/m",
                "indentation_m": "m",
            },
        )
    return res
