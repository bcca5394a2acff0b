"""Analytic reference solutions of contact mechanics (SI units).

Frictionless and frictional contact of axisymmetric rigid indenters with an
elastic half-space of effective modulus ``E*`` (Pa).  These are the yardsticks
of the MDR and BEM solvers; they are independent of both.

``G*`` in the Mindlin functions is the MDR tangential modulus,
``1/G* = (2-nu1)/(4 G1) + (2-nu2)/(4 G2)`` (four times Johnson's).

References
----------
K. L. Johnson, *Contact Mechanics*, Cambridge (1985). doi:10.1017/CBO9781139171731 K. L. Johnson, K.
Kendall, A. D. Roberts, Proc. R. Soc. A 324, 301 (1971). doi:10.1098/rspa.1971.0141 R. D. Mindlin,
H. Deresiewicz, J. Appl. Mech. 20, 327 (1953).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = [
    "hertz_force",
    "hertz_radius",
    "hertz_indentation",
    "hertz_pressure",
    "hertz_displacement",
    "cone_force",
    "cone_radius",
    "cone_pressure",
    "flat_punch_force",
    "flat_punch_pressure",
    "power_law_force",
    "jkr_indentation",
    "jkr_force",
    "jkr_pull_off_force_control",
    "jkr_pull_off_displacement_control",
    "mindlin_slip_displacement",
    "mindlin_force",
    "mindlin_unloading_force",
    "mindlin_dissipation",
    "PERIODIC_IMAGE_COEFF",
]

#: Coefficient of the periodic-image correction of a square periodic BEM cell:
#: d = u(apex) - <u> + PERIODIC_IMAGE_COEFF * F / (pi E* L)  (PHYSICS.md §2).
PERIODIC_IMAGE_COEFF = 3.900265


# ------------------------------------------------------------------ Hertz


def hertz_force(d, R, E_star):
    """Hertz force (N): ``F = 4/3 E* sqrt(R) d^(3/2)`` for indentation d (m), radius R (m)."""
    d = np.maximum(np.asarray(d, dtype=float), 0.0)
    return 4.0 / 3.0 * E_star * math.sqrt(R) * d**1.5


def hertz_radius(d, R):
    """Hertz contact radius (m): ``a = sqrt(R d)``."""
    return np.sqrt(R * np.maximum(np.asarray(d, dtype=float), 0.0))


def hertz_indentation(F, R, E_star):
    """Hertz indentation (m) for force F (N)."""
    return (3.0 * np.asarray(F, dtype=float) / (4.0 * E_star * math.sqrt(R))) ** (2.0 / 3.0)


def hertz_pressure(r, d, R, E_star):
    """Hertz pressure (Pa): ``p = (2 E*/(pi R)) sqrt(a^2 - r^2)``."""
    a = hertz_radius(d, R)
    r = np.asarray(r, dtype=float)
    return 2.0 * E_star / (math.pi * R) * np.sqrt(np.maximum(a * a - r * r, 0.0))


def hertz_displacement(r, d, R):
    """Hertz surface displacement (m) inside and outside the contact.

    ``w = d - r^2/(2R)`` for r <= a and
    ``w = [(2a^2 - r^2) asin(a/r) + a sqrt(r^2 - a^2)] / (pi R)`` beyond.
    """
    a = float(hertz_radius(d, R))
    r = np.asarray(r, dtype=float)
    rr = np.maximum(r, a)
    outside = ((2 * a * a - rr * rr) * np.arcsin(a / rr) + a * np.sqrt(rr * rr - a * a)) / (
        math.pi * R
    )
    return np.where(r <= a, d - r * r / (2 * R), outside)


# ------------------------------------------------------------------- cone


def cone_force(d, half_angle_deg, E_star):
    """Cone force (N): ``F = (2/pi) E* tan(alpha) d^2``, alpha = half-angle from the axis."""
    t = math.tan(math.radians(half_angle_deg))
    d = np.maximum(np.asarray(d, dtype=float), 0.0)
    return 2.0 / math.pi * E_star * t * d * d


def cone_radius(d, half_angle_deg):
    """Cone contact radius (m): ``a = 2 d tan(alpha) / pi``."""
    return 2.0 / math.pi * math.tan(math.radians(half_angle_deg)) * np.asarray(d, dtype=float)


def cone_pressure(r, d, half_angle_deg, E_star):
    """Cone pressure (Pa): ``p = (E*/(2 tan(alpha))) arccosh(a/r)`` (log-singular at the tip)."""
    a = cone_radius(d, half_angle_deg)
    r = np.asarray(r, dtype=float)
    with np.errstate(divide="ignore"):
        x = np.where(r < a, a / np.maximum(r, 1e-300), 1.0)
    return E_star / (2.0 * math.tan(math.radians(half_angle_deg))) * np.arccosh(x)


# -------------------------------------------------------------- flat punch


def flat_punch_force(d, R, E_star):
    """Flat cylindrical punch force (N): ``F = 2 E* R d``."""
    return 2.0 * E_star * R * np.asarray(d, dtype=float)


def flat_punch_pressure(r, d, R, E_star):
    """Flat punch pressure (Pa): ``p = E* d / (pi sqrt(R^2 - r^2))`` (edge singularity)."""
    r = np.asarray(r, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(r < R, E_star * d / (math.pi * np.sqrt(R * R - r * r)), 0.0)


def power_law_force(d, exponent, coefficient, E_star):
    """Force (N) for ``f = c r^n``: ``F = 2 E* d a n/(n+1)`` with ``kappa_n c a^n = d``."""
    k = math.sqrt(math.pi) * math.exp(
        math.lgamma(exponent / 2 + 1) - math.lgamma(exponent / 2 + 0.5)
    )
    d = np.asarray(d, dtype=float)
    a = (d / (k * coefficient)) ** (1.0 / exponent)
    return 2.0 * E_star * d * a * exponent / (exponent + 1.0)


# -------------------------------------------------------------------- JKR


def jkr_indentation(a, R, E_star, work_of_adhesion):
    """JKR indentation (m) at contact radius a (m): ``d = a^2/R - sqrt(2 pi a w / E*)``."""
    a = np.asarray(a, dtype=float)
    return a * a / R - np.sqrt(2.0 * math.pi * a * work_of_adhesion / E_star)


def jkr_force(a, R, E_star, work_of_adhesion):
    """JKR force (N) at contact radius a (m): ``F = 4 E* a^3/(3R) - sqrt(8 pi w E* a^3)``."""
    a = np.asarray(a, dtype=float)
    return 4.0 * E_star * a**3 / (3.0 * R) - np.sqrt(
        8.0 * math.pi * work_of_adhesion * E_star * a**3
    )


def jkr_pull_off_force_control(R, work_of_adhesion):
    """Pull-off force (N) under force control: ``-3/2 pi w R``."""
    return -1.5 * math.pi * work_of_adhesion * R


def jkr_pull_off_displacement_control(R, work_of_adhesion):
    """Force (N) at the fixed-grips instability: ``-5/6 pi w R``."""
    return -5.0 / 6.0 * math.pi * work_of_adhesion * R


# ---------------------------------------------------------------- Mindlin


def mindlin_slip_displacement(d, mu, E_star, G_star):
    """Tangential displacement (m) of full sliding for a Hertz contact: ``u_s = mu E* d / G*``."""
    return mu * E_star * d / G_star


def mindlin_force(u, d, R, mu, E_star, G_star):
    """Cattaneo-Mindlin tangential force (N) under monotonic loading at constant d.

    ``F_x = mu F_N (1 - (1 - u/u_s)^(3/2))`` for ``0 <= u <= u_s`` (then ``mu F_N``);
    equivalently ``F_x = mu F_N (1 - (c/a)^3)`` with the stick radius c.
    """
    us = mindlin_slip_displacement(d, mu, E_star, G_star)
    FN = hertz_force(d, R, E_star)
    x = np.clip(np.asarray(u, dtype=float) / us, -1.0, 1.0)
    return np.sign(x) * mu * FN * (1.0 - (1.0 - np.abs(x)) ** 1.5)


def mindlin_unloading_force(u, u_amp, d, R, mu, E_star, G_star):
    """Mindlin-Deresiewicz branch (N) on unloading from ``u_amp`` (m) back towards ``-u_amp``.

    ``F(u) = F(u_amp) - 2 F_virgin((u_amp - u)/2)`` (exact for Hertz at constant normal force).
    """
    F_amp = mindlin_force(u_amp, d, R, mu, E_star, G_star)
    return F_amp - 2.0 * mindlin_force(
        (u_amp - np.asarray(u, dtype=float)) / 2.0, d, R, mu, E_star, G_star
    )


def mindlin_dissipation(u_amp, d, R, mu, E_star, G_star):
    """Energy (J) dissipated per cycle of a displacement oscillation ``+-u_amp`` (m).

    Masing's rule makes the loop area ``W = 8 int_0^{u*} F du - 4 u* F(u*)``
    (virgin curve F, saturating at ``mu F_N`` beyond ``u_s``), with
    ``int_0^{u} F = mu F_N [u - (2 u_s/5)(1 - (1 - u/u_s)^(5/2))]`` for ``u <= u_s``.
    """
    us = mindlin_slip_displacement(d, mu, E_star, G_star)
    FN = float(hertz_force(d, R, E_star))
    ua = float(u_amp)
    uc = min(ua, us)
    integral = mu * FN * (uc - 0.4 * us * (1.0 - (1.0 - uc / us) ** 2.5)) + mu * FN * max(
        ua - us, 0.0
    )
    return 8.0 * integral - 4.0 * ua * float(mindlin_force(uc, d, R, mu, E_star, G_star))
