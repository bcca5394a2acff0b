"""Exact and asymptotic lubrication forces on a sphere near a plane wall (SI).

Sign convention used throughout the lubrication package: ``velocity`` ``V`` is
the *approach* speed (``V = -dh/dt``, ``V > 0`` when the gap closes) and the
returned normal force is the component on the sphere that *opposes* the
approach, so it is positive (repulsive) for ``V > 0`` and negative (suction)
for ``V < 0``.  Tangential forces are magnitudes of the drag opposing the
sliding velocity ``U`` (same sign as ``U``).

Contents
--------
* :func:`damper_force` -- leading-order Reynolds/Taylor squeeze force
  ``6 pi eta R^2 V / h`` (the seed's Eq. 11 with the factor-2 erratum fixed).
* :func:`cox_brenner_force` -- two-term inner expansion for ``h/R <= 0.1``.
* :func:`brenner_force` -- Brenner's (1961) exact bispherical series (any gap).
* :func:`gcb_sliding_force` -- Goldman, Cox & Brenner (1967) drag on a sphere
  translating parallel to a wall (no rotation), ``h/R << 1``.
* :func:`couette_sliding_force` -- the seed's Eq. 12 (Couette shear only).
* :func:`power_law_squeeze_force` -- closed-form squeeze force of a power-law
  fluid in the paraboloid gap, optionally on a truncated domain ``r <= r_max``.

References
----------
.. [1] H. Brenner, "The slow motion of a sphere through a viscous fluid
   towards a plane surface", Chem. Eng. Sci. 16, 242 (1961).
   doi:10.1016/0009-2509(61)80035-3
.. [2] R. G. Cox and H. Brenner, "The slow motion of a sphere through a
   viscous fluid towards a plane surface II. Small gap widths, including
   inertial effects", Chem. Eng. Sci. 22, 1753 (1967).
   doi:10.1016/0009-2509(67)80208-2
.. [3] A. J. Goldman, R. G. Cox and H. Brenner, "Slow viscous motion of a
   sphere parallel to a plane wall I. Motion through a quiescent fluid",
   Chem. Eng. Sci. 22, 637 (1967). doi:10.1016/0009-2509(67)80047-2
"""

from __future__ import annotations

import math

import numpy as np

__all__ = [
    "damper_coefficient",
    "damper_force",
    "cox_brenner_force",
    "brenner_correction",
    "brenner_force",
    "gcb_sliding_force",
    "couette_sliding_force",
    "faxen_sliding_force",
    "power_law_slot_flux",
    "power_law_squeeze_force",
    "COX_BRENNER_CONSTANT",
    "GCB_CONSTANT",
]

#: Constant of the O(h/R) term of the Cox-Brenner expansion.
COX_BRENNER_CONSTANT = 0.9713
#: Constant of the Goldman-Cox-Brenner sliding drag.
GCB_CONSTANT = 0.9588


def damper_coefficient(radius: float, viscosity: float) -> float:
    """Coefficient alpha = 6 pi eta R^2 (N s) of the damper F = alpha V / h.

    Parameters
    ----------
    radius : float
        Sphere (asperity) radius R in m.
    viscosity : float
        Newtonian viscosity eta in Pa s.
    """
    return 6.0 * math.pi * viscosity * radius**2


def damper_force(radius, viscosity, gap, velocity):
    """Leading-order squeeze force F = 6 pi eta R^2 V / h in N (Reynolds/Taylor).

    Parameters
    ----------
    radius : float
        Sphere radius R in m.
    viscosity : float
        Viscosity eta in Pa s.
    gap : float or ndarray
        Minimum gap h in m.
    velocity : float or ndarray
        Approach speed V = -dh/dt in m/s.

    Returns
    -------
    float or ndarray
        Force in N opposing the approach.
    """
    if type(gap) is float and type(velocity) is float:  # scalar fast path (no numpy overhead)
        return 6.0 * math.pi * viscosity * radius * radius * velocity / gap
    return damper_coefficient(radius, viscosity) * np.asarray(velocity) / np.asarray(gap)


def cox_brenner_force(radius, viscosity, gap, velocity):
    """Cox-Brenner small-gap squeeze force in N, valid for h/R <= 0.1.

    ``F = 6 pi eta R^2 V / h [1 + (h/5R) ln(R/h) + 0.9713 h/R]``.

    Parameters are as in :func:`damper_force`.
    """
    eps = np.asarray(gap) / radius
    return damper_force(radius, viscosity, gap, velocity) * (
        1.0 + 0.2 * eps * np.log(1.0 / eps) + COX_BRENNER_CONSTANT * eps
    )


def _sinh_minus_x(x: np.ndarray) -> np.ndarray:
    """sinh(x) - x without cancellation for small x."""
    x = np.asarray(x, dtype=float)
    out = np.empty_like(x)
    small = np.abs(x) < 0.5
    xs = x[small]
    x2 = xs * xs
    # Taylor series to x^15: relative truncation error < 1e-17 for |x| < 0.5.
    term = xs * x2 / 6.0
    acc = term.copy()
    for k in range(2, 8):
        term = term * x2 / ((2 * k) * (2 * k + 1))
        acc += term
    out[small] = acc
    out[~small] = np.sinh(x[~small]) - x[~small]
    return out


def brenner_correction(gap_over_radius: float, *, tol: float = 1e-16) -> float:
    """Brenner's exact Stokes correction lambda = F / (6 pi eta R V) for any gap.

    Uses the bispherical-coordinate series of Brenner (1961), with cosh(alpha)
    = 1 + h/R, rewritten so that it stays accurate for h/R down to ~1e-12
    (no catastrophic cancellation in the bracket, no overflow of sinh).

    Parameters
    ----------
    gap_over_radius : float
        h/R > 0 (minimum gap over sphere radius).
    tol : float
        Relative size of the last series term kept.

    Returns
    -------
    float
        lambda (dimensionless); lambda -> R/h for h << R and -> 1 for h >> R.
    """
    eps = float(gap_over_radius)
    if not eps > 0 or not math.isfinite(eps):
        raise ValueError(f"gap_over_radius must be positive and finite, got {eps!r}")
    alpha = math.acosh(1.0 + eps) if eps > 1e-6 else math.log1p(eps + math.sqrt(eps * (2.0 + eps)))
    # Terms decay like exp(-(2n+1) alpha); stop where that is below tol.
    n_max = int(min(5e7, max(50.0, (math.log(1.0 / tol) + 10.0) / (2.0 * alpha))))
    n = np.arange(1, n_max + 1, dtype=float)
    k = 2.0 * n + 1.0
    x = 0.5 * k * alpha
    sa, s2a = math.sinh(alpha), math.sinh(2.0 * alpha)
    # bracket = N/D - 1 with N = 2 sinh(k a) + k sinh(2a), D = 4 sinh^2(k a/2) - k^2 sinh^2(a).
    # N - D = 2 - 2 exp(-k a) + k sinh(2a) + k^2 sinh^2(a)   (no cancellation),
    # D = (2 sinh(x) - k sinh a)(2 sinh(x) + k sinh a), first factor written as
    #     2 (sinh(x) - x) - k (sinh(a) - a)  (the x - k a/2 terms cancel exactly).
    x_c = np.minimum(x, 300.0)  # beyond this the terms are < 1e-200: clip to avoid overflow
    num = 2.0 * -np.expm1(-k * alpha) + k * s2a + (k * sa) ** 2
    d1 = 2.0 * _sinh_minus_x(x_c) - k * float(_sinh_minus_x(np.array([alpha]))[0])
    d2 = 2.0 * np.sinh(x_c) + k * sa
    bracket = num / (d1 * d2)
    weights = n * (n + 1.0) / ((2.0 * n - 1.0) * (2.0 * n + 3.0))
    terms = weights * bracket
    return float(4.0 / 3.0 * sa * np.sum(terms[::-1]))


def brenner_force(radius, viscosity, gap, velocity):
    """Exact Stokes squeeze force F = 6 pi eta R V lambda(h/R) in N (Brenner 1961).

    Parameters are as in :func:`damper_force`; ``gap`` may be an array.
    """
    gap_arr = np.asarray(gap, dtype=float)
    lam = np.vectorize(brenner_correction, otypes=[float])(gap_arr / radius)
    out = 6.0 * math.pi * viscosity * radius * np.asarray(velocity) * lam
    return float(out) if np.ndim(out) == 0 else out


def gcb_sliding_force(radius, viscosity, gap, velocity):
    """Goldman-Cox-Brenner drag (N) on a sphere sliding parallel to a wall, h/R << 1.

    ``F = 6 pi eta R U [(8/15) ln(R/h) + 0.9588]`` for pure translation (no
    rotation); the error is O((h/R) ln(R/h)).

    Parameters
    ----------
    radius, viscosity, gap : float
        R (m), eta (Pa s), minimum gap h (m).
    velocity : float
        Sliding speed U in m/s.
    """
    eps = np.asarray(gap) / radius
    return 6.0 * math.pi * viscosity * radius * np.asarray(velocity) * (
        8.0 / 15.0 * np.log(1.0 / eps) + GCB_CONSTANT
    )


def couette_sliding_force(radius, viscosity, gap, velocity, length=None):
    """Return the seed's Eq. 12: Couette shear only, F = 2 pi R eta U ln(1 + L^2/(2 h R)) in N.

    This omits the pressure-driven part of the lubrication flow; it is
    2-2.6x smaller than :func:`gcb_sliding_force` for 1e-4 <= h/R <= 1e-2.
    Kept for comparison with the seed only.

    Parameters
    ----------
    radius, viscosity, gap, velocity : float
        R (m), eta (Pa s), h (m), U (m/s).
    length : float, optional
        Integration radius L in m (the seed: distance between asperities);
        defaults to R.
    """
    L = radius if length is None else length
    return 2.0 * math.pi * radius * viscosity * np.asarray(velocity) * np.log1p(
        L**2 / (2.0 * np.asarray(gap) * radius)
    )


def faxen_sliding_force(radius, viscosity, gap, velocity):
    """Far-field (Faxen) drag in N on a sphere sliding parallel to a wall, h >~ R.

    ``F = 6 pi eta R U / (1 - 9/16 s + 1/8 s^3 - 45/256 s^4 - 1/16 s^5)`` with
    ``s = R / (R + h)``; accurate to a few per cent for h/R >= 0.5.
    """
    s = radius / (radius + np.asarray(gap))
    return 6.0 * math.pi * viscosity * radius * np.asarray(velocity) / (
        1.0 - 9.0 / 16.0 * s + s**3 / 8.0 - 45.0 / 256.0 * s**4 - s**5 / 16.0
    )


def power_law_slot_flux(gap, gradient, consistency, index):
    """Flux per unit width (m^2/s) of a power-law fluid in a slot of height h.

    For tau = K |gamma_dot|^(n-1) gamma_dot and a pressure gradient G = -dp/dx,
    ``q = n/(2n+1) h^((2n+1)/n) 2^(-(n+1)/n) |G/K|^(1/n) sign(G)``; for n = 1 this
    is the Poiseuille flux h^3 G / (12 eta).

    Parameters
    ----------
    gap : float or ndarray
        Slot height h in m.
    gradient : float or ndarray
        Driving gradient G = -dp/dx in Pa/m.
    consistency, index : float
        K in Pa s^n and n (dimensionless).
    """
    n = index
    g = np.asarray(gradient, dtype=float)
    return (
        n / (2.0 * n + 1.0)
        * np.asarray(gap) ** ((2.0 * n + 1.0) / n)
        * 2.0 ** (-(n + 1.0) / n)
        * np.abs(g / consistency) ** (1.0 / n)
        * np.sign(g)
    )


def power_law_squeeze_force(radius, consistency, index, gap, velocity, r_max=None):
    """Closed-form squeeze force (N) of a power-law fluid, paraboloid gap h0 + r^2/2R.

    Mass conservation fixes the radial flux per unit circumference, q = V r / 2;
    inverting the slot flux (:func:`power_law_slot_flux`) gives

    ``-dp/dr = C r^n / h(r)^(2n+1)``,  ``C = 2^(n+1) K ((2n+1)/(2n))^n V^n``,

    and with ``F = pi int_0^rmax r^2 (-dp/dr) dr`` (p = 0 at r_max):

    ``F = (pi/2) C (2R)^((n+3)/2) h0^((1-3n)/2) B(u; (n+3)/2, (3n-1)/2)``

    with ``u = T^2/(1+T^2)``, ``T = r_max/sqrt(2 R h0)`` (u = 1: the complete beta
    function).  The infinite-domain force exists only for n > 1/3, because the
    pressure decays like r^-(3n+1); it reduces to 6 pi eta R^2 V / h0 at n = 1.

    Parameters
    ----------
    radius : float
        R in m.
    consistency : float
        K in Pa s^n.
    index : float
        Flow index n; must exceed 1/3 when ``r_max`` is None.
    gap : float
        Minimum gap h0 in m.
    velocity : float
        Approach speed V in m/s (the force has the sign of V).
    r_max : float, optional
        Outer radius (m) where p = 0; None = infinite domain.
    """
    from scipy import special

    n = float(index)
    a, b = (n + 3.0) / 2.0, (3.0 * n - 1.0) / 2.0
    if r_max is None:
        if not n > 1.0 / 3.0:
            raise ValueError(
                f"power-law index must exceed 1/3 for a finite squeeze force, got {n!r}"
            )
        beta = special.beta(a, b)
    else:
        T2 = r_max**2 / (2.0 * radius * gap)
        u = T2 / (1.0 + T2)
        if b > 0:
            beta = special.betainc(a, b, u) * special.beta(a, b)
        else:  # the truncated integral is finite for any n; integrate it directly
            from scipy import integrate

            beta = (
                2.0
                * integrate.quad(
                    lambda t: t ** (n + 2.0) / (1.0 + t * t) ** (2.0 * n + 1.0),
                    0.0,
                    math.sqrt(T2),
                    limit=200,
                )[0]
            )
    V = float(velocity)
    C = 2.0 ** (n + 1.0) * consistency * ((2.0 * n + 1.0) / (2.0 * n)) ** n * abs(V) ** n
    F = 0.5 * math.pi * C * (2.0 * radius) ** a * gap ** ((1.0 - 3.0 * n) / 2.0) * beta
    return math.copysign(F, V) if V != 0 else 0.0
