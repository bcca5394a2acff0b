"""Closed-form reference solutions for the rigid body on contact springs.

* :func:`stick_slip_cycle` -- the limit cycle of a rigid block pulled through a
  spring ``k`` at speed ``V`` with static/kinetic Coulomb friction
  ``mu_s >= mu_k`` and rigid contact;
* :func:`free_oscillation` -- the body after the normal load has vanished;
* :func:`mindlin_loop` -- the Mindlin-Deresiewicz hysteresis of a Hertz
  contact under a tangential oscillation at constant normal load
  (Masing's rule on Mindlin's loading curve, in MDR variables).

References
----------
Popov VL, Contact Mechanics and Friction, 2nd ed., Springer (2017), ch. 12
(stick-slip) and ch. 8 (Cattaneo-Mindlin), doi:10.1007/978-3-662-53081-8.
Mindlin RD, Deresiewicz H. J Appl Mech 20 (1953) 327.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = [
    "restick_criterion",
    "squeeze_approach_gap",
    "vibrated_coulomb_mean_force",
    "stick_slip_cycle",
    "free_oscillation",
    "mindlin_loading",
    "mindlin_loop",
    "mindlin_dissipation",
]


def stick_slip_cycle(mass: float, stiffness: float, velocity: float, normal_force: float,
                     mu_s: float, mu_k: float) -> dict:
    """Limit cycle of Coulomb stick-slip with a rigid contact.

    During slip ``xi = x - V t + mu_k N / k`` oscillates harmonically at
    ``omega = sqrt(k/m)``; the slip starts at ``F = mu_s N`` with the body at
    rest and ends when it is at rest again, which by energy conservation is at
    ``F = (2 mu_k - mu_s) N``, independent of ``V``.

    Returns
    -------
    dict
        ``force_max`` and ``force_min`` (N, spring force at slip start/end),
        ``slip_time``, ``stick_time``, ``period`` (s), ``slip_distance`` (m).
    """
    w = math.sqrt(stiffness / mass)
    A = (mu_s - mu_k) * normal_force / stiffness
    if A <= 0:
        return dict(
            force_max=mu_k * normal_force,
            force_min=mu_k * normal_force,
            slip_time=math.inf,
            stick_time=0.0,
            period=math.inf,
            slip_distance=math.inf,
        )
    slip = (math.pi + 2.0 * math.atan(velocity / (w * A))) / w
    stick = 2.0 * A / velocity
    return dict(
        force_max=mu_s * normal_force,
        force_min=(2 * mu_k - mu_s) * normal_force,
        slip_time=slip,
        stick_time=stick,
        period=slip + stick,
        slip_distance=velocity * (slip + stick),
    )


def restick_criterion(mass: float, drive_stiffness: float, velocity: float, normal_force: float,
                      mu_s: float, mu_k: float, contact_stiffness: float = 0.0) -> dict:
    """Whether a body that has slipped once sticks again (repeated stick-slip), analytically.

    Model of :func:`tribolmp.models.macro.stick_slip` with a constant
    ``mu_s >= mu_k``: during stick the body creeps on the tangential contact
    spring ``k_c`` in series with the drive spring ``k_d``, at the quasi-static
    velocity ``v0 = V k_d / (k_d + k_c)`` (``v0 = 0`` for a rigid contact,
    ``k_c = 0`` here); the contact's transient is damped (the model's contact
    damping) and far shorter than a stick phase.  At the slip the contact force
    drops from ``mu_s N`` to ``mu_k N``: the undamped body then oscillates about
    the kinetic equilibrium at ``omega = sqrt(k_d / m)`` with velocity
    ``V + A omega sin(...)``, ``(A omega)^2 = (dF / sqrt(k_d m))^2 + (V - v0)^2``
    and ``dF = (mu_s - mu_k) N``.  It sticks again iff its velocity reaches zero,
    ``A omega > V``, i.e.

        dF > dF_c = sqrt(k_d m v0 (2 V - v0)).

    With a rigid contact (``v0 = 0``) any static excess gives stick-slip (the
    classic result); a compliant contact's pre-slip creep needs a finite one.

    Returns
    -------
    dict
        ``static_excess_N`` (dF), ``threshold_N`` (dF_c), ``creep_velocity_m_s``
        (v0), ``repeats`` (bool, dF > dF_c), ``min_slip_velocity_m_s`` (V - A omega).
    """
    k, V, m = float(drive_stiffness), float(velocity), float(mass)
    v0 = (
        0.0
        if contact_stiffness <= 0 or math.isinf(contact_stiffness)
        else V * k / (k + contact_stiffness)
    )
    dF = (float(mu_s) - float(mu_k)) * float(normal_force)
    threshold = math.sqrt(k * m * v0 * (2.0 * V - v0))
    a_omega = math.hypot(dF / math.sqrt(k * m), V - v0)
    return dict(static_excess_N=dF, threshold_N=threshold, creep_velocity_m_s=v0,
                repeats=bool(dF > threshold), min_slip_velocity_m_s=V - a_omega)


def free_oscillation(
    t, mass: float, stiffness: float, velocity: float, x0: float, v0: float, t0: float, xd0: float
):
    """Position (m) of a frictionless body pulled by a spring.

    The spring's end moves as ``xd0 + V (t - t0)``.
    """
    w = math.sqrt(stiffness / mass)
    tau = np.asarray(t, dtype=float) - t0
    xi0, dxi0 = x0 - xd0, v0 - velocity
    return xd0 + velocity * tau + xi0 * np.cos(w * tau) + dxi0 / w * np.sin(w * tau)


def mindlin_loading(u, mu_n: float, u_slip: float):
    """Mindlin's first loading curve ``F = mu N [1 - (1 - u/u_s)^{3/2}]`` (N).

    Full slip beyond ``u_s``.

    ``u_slip = mu E* d / G*`` in MDR variables (d the indentation).
    """
    r = np.clip(1.0 - np.asarray(u, dtype=float) / u_slip, 0.0, None)
    return mu_n * (1.0 - r**1.5)


def mindlin_loop(u, u_amp: float, mu_n: float, u_slip: float, branch: str):
    """Steady Mindlin-Deresiewicz loop (``u_amp <= u_slip``): unloading or reloading branch (N).

    Masing's rule: ``F_unload(u) = F* - 2 F_load((u_amp - u)/2)``,
    ``F_reload(u) = -F* + 2 F_load((u + u_amp)/2)``, ``F* = F_load(u_amp)``.
    """
    u = np.asarray(u, dtype=float)
    f_star = mindlin_loading(u_amp, mu_n, u_slip)
    if branch == "unload":
        return f_star - 2.0 * mindlin_loading(0.5 * (u_amp - u), mu_n, u_slip)
    return -f_star + 2.0 * mindlin_loading(0.5 * (u + u_amp), mu_n, u_slip)


def mindlin_dissipation(u_amp: float, mu_n: float, u_slip: float) -> float:
    """Energy (J) dissipated per cycle of the steady loop: the integral of F du around it.

    The reloading branch (u increasing) lies above the unloading one.
    """
    from scipy.integrate import quad

    return quad(
        lambda u: float(
            mindlin_loop(u, u_amp, mu_n, u_slip, "reload")
            - mindlin_loop(u, u_amp, mu_n, u_slip, "unload")
        ),
        -u_amp,
        u_amp,
        epsabs=0,
        epsrel=1e-12,
    )[0]


def squeeze_approach_gap(t, gap0: float, load: float, radius: float, viscosity: float):
    """Gap (m) of a massless sphere pressed by a constant load through a squeeze film.

    ``W = alpha V / h`` with ``alpha = 6 pi eta R^2`` (PHYSICS.md, corrected
    Eq. 11) gives ``d ln h / dt = -W / alpha``, so ``h = h0 exp(-W t / alpha)``:
    the film thins exponentially and never reaches zero.
    """
    alpha = 6.0 * math.pi * viscosity * radius**2
    return gap0 * np.exp(-load * np.asarray(t, dtype=float) / alpha)


def vibrated_coulomb_mean_force(nu):
    """Cycle-mean Coulomb force (in units of the sliding force) under ``v + a w cos(w t)``.

    A rigid-plastic contact (no elasticity) sliding at mean speed ``v`` while
    vibrated in the sliding direction with velocity amplitude ``a w``:
    ``<sign(v + a w cos)> = (2/pi) arcsin(nu)``, ``nu = v/(a w)``, and 1 for ``nu >= 1``.
    """
    nu = np.asarray(nu, dtype=float)
    return np.sign(nu) * np.where(
        np.abs(nu) >= 1.0, 1.0, 2.0 / np.pi * np.arcsin(np.clip(np.abs(nu), 0.0, 1.0))
    )
