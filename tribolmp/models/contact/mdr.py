"""Method of Dimensionality Reduction (MDR) for axisymmetric and 1D contacts.

A 3D frictional contact of an axisymmetric body with an elastic half-space is
mapped exactly onto a 1D row of independent springs (Popov & Heß):

* normal stiffness ``E* dx`` and tangential stiffness ``G* dx`` per spring,
  with ``1/G* = (2-nu1)/(4 G1) + (2-nu2)/(4 G2)`` (four times Johnson's G*);
* the profile ``f(r)`` is replaced by ``g(x) = |x| int_0^{pi/2} f'(|x| sin t) dt``;
* ``F = 2 E* int_0^a (d - g) dx`` with ``g(a) = d`` (no adhesion) or
  ``d = g(a) - sqrt(2 pi a dgamma / E*)`` (JKR, Heß's rule);
* pressure and 3D displacement follow from the inverse transforms.

The spring row is treated as the piecewise-linear line through the spring
tips and integrated *exactly*, including the partial cell at each contact edge
(sub-grid edge).  This makes the force a continuous, piecewise-smooth function
of the indentation and its error O(dx^2) with a small constant
(relative error ``dx^2 / (4 a^2)`` for Hertz, zero for the cone when ``x = 0``
is a spring).  Inverse transforms and the adhesive edge use a cubic spline of
the half profile, because they need ``g'``.

All quantities are SI: lengths in m, moduli and pressures in Pa, forces in N,
stiffnesses in N/m, work of adhesion in J/m^2.

References
----------
V. L. Popov, M. Heß, *Method of Dimensionality Reduction in Contact Mechanics
and Friction*, Springer (2015). doi:10.1007/978-3-642-53876-6
M. Heß, *Über die exakte Abbildung ausgewählter dreidimensionaler
Kontaktprobleme auf Systeme mit niedrigerer räumlicher Dimension* (2011).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...errors import NoContactError, ParameterError
from ..base import check_int, check_positive, check_range

__all__ = [
    "PROFILE_KINDS",
    "kappa",
    "axisymmetric_profile",
    "profile_transform",
    "profile_transform_tabulated",
    "normal_force",
    "normal_stiffness",
    "contact_length",
    "spring_widths",
    "contact_lengths",
    "contact_radius",
    "AxisymmetricMDR",
    "TangentialMDR",
]

PROFILE_KINDS = ("sphere", "cone", "flat", "power")

# Gauss-Legendre nodes on [0, 1], reused by all quadratures of this module.
_GL_X, _GL_W = np.polynomial.legendre.leggauss(48)
_GL_X = 0.5 * (_GL_X + 1.0)
_GL_W = 0.5 * _GL_W


def kappa(n: float) -> float:
    """MDR stretch factor of a power-law profile ``f = c r^n``: ``g = kappa_n c |x|^n``.

    ``kappa_n = sqrt(pi) Gamma(n/2 + 1) / Gamma(n/2 + 1/2)`` (dimensionless).
    """
    n = check_positive("exponent", n)
    return math.sqrt(math.pi) * math.exp(math.lgamma(n / 2 + 1) - math.lgamma(n / 2 + 0.5))


# ------------------------------------------------------------------ profiles


def axisymmetric_profile(
    kind: str,
    n_springs: int,
    x_max: float,
    *,
    radius: float | None = None,
    half_angle_deg: float | None = None,
    exponent: float | None = None,
    coefficient: float | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Spring positions and the MDR-transformed gap of an axisymmetric indenter.

    Parameters
    ----------
    kind : {"sphere", "cone", "flat", "power"}
        ``sphere``: paraboloid ``f = r^2/(2R)`` -> ``g = x^2/R``;
        ``cone``: ``f = r / tan(alpha)`` with ``alpha`` the half-angle from the
        axis -> ``g = (pi/2)|x| / tan(alpha)``;
        ``flat``: cylindrical punch of radius R -> ``g = 0`` for ``|x| <= R``,
        ``+inf`` beyond (the punch edge sits halfway between the last inside
        and the first outside spring);
        ``power``: ``f = c r^n`` -> ``g = kappa_n c |x|^n``.
    n_springs : int
        Number of springs (>= 3).  An odd number puts a spring on the axis.
    x_max : float
        Half-length of the row (m); the springs span ``[-x_max, x_max]``.
    radius : float, optional
        Sphere or punch radius R (m).
    half_angle_deg : float, optional
        Cone half-angle from the axis, in degrees, in (0, 90).
    exponent, coefficient : float, optional
        ``n`` (dimensionless) and ``c`` (m^(1-n)) of the power law.

    Returns
    -------
    x : ndarray
        Spring positions (m), uniform spacing, symmetric about 0.
    g : ndarray
        Transformed gap ``g(x)`` (m); ``g.min() == 0``.
    """
    check_choiceish(kind)
    n = check_int("n_springs", n_springs, 3, 10**9)
    x_max = check_positive("x_max", x_max, "m")
    x = np.linspace(-x_max, x_max, n)
    ax = np.abs(x)
    if kind == "sphere":
        R = check_positive("radius", _required("radius", radius), "m")
        g = ax**2 / R
    elif kind == "cone":
        alpha = check_range(
            "half_angle_deg",
            _required("half_angle_deg", half_angle_deg),
            0.0,
            90.0,
            lo_open=True,
            hi_open=True,
            unit="deg",
        )
        g = 0.5 * math.pi * ax / math.tan(math.radians(alpha))
    elif kind == "flat":
        R = check_positive("radius", _required("radius", radius), "m")
        g = np.where(ax <= R, 0.0, np.inf)
    else:
        nexp = check_positive("exponent", _required("exponent", exponent))
        c = check_positive("coefficient", _required("coefficient", coefficient))
        g = kappa(nexp) * c * ax**nexp
    return x, g


def check_choiceish(kind: str) -> None:
    """Raise a one-line error unless ``kind`` is a known axisymmetric profile."""
    if kind not in PROFILE_KINDS:
        raise ParameterError("profile", f"one of {list(PROFILE_KINDS)}", kind)


def _required(name: str, value):
    if value is None:
        raise ParameterError(name, "a value for this profile", None)
    return value


def profile_transform(fprime, x, *, n_quad: int = 96) -> np.ndarray:
    """Numerical MDR transform ``g(x) = |x| int_0^{pi/2} f'(|x| sin t) dt``.

    This form has no singularity (unlike ``int f'(r)/sqrt(x^2-r^2) dr``), so a
    plain Gauss-Legendre rule converges fast for smooth ``f'``.

    Parameters
    ----------
    fprime : callable
        Derivative ``f'(r)`` of the axisymmetric gap (dimensionless), vectorised.
    x : array_like
        Positions (m).
    n_quad : int
        Gauss-Legendre nodes in theta.

    Returns
    -------
    ndarray
        ``g(x)`` in m.
    """
    ax = np.abs(np.asarray(x, dtype=float))
    t, w = np.polynomial.legendre.leggauss(int(n_quad))
    theta = 0.25 * math.pi * (t + 1.0)
    w = 0.25 * math.pi * w
    vals = fprime(ax[..., None] * np.sin(theta))
    return ax * np.sum(np.asarray(vals, dtype=float) * w, axis=-1)


def profile_transform_tabulated(r, f, x, *, n_quad: int = 96) -> np.ndarray:
    """MDR transform of a tabulated axisymmetric gap ``f(r)`` (m) on radii ``r`` (m).

    ``f'`` is taken from a cubic spline through the table; ``x`` must lie in
    ``[-r.max(), r.max()]``.
    """
    from scipy.interpolate import CubicSpline

    r = np.asarray(r, dtype=float)
    f = np.asarray(f, dtype=float)
    if r.ndim != 1 or r.shape != f.shape or r.size < 4:
        raise ParameterError(
            "r, f", "two 1D arrays of equal length >= 4", f"shapes {r.shape}, {f.shape}"
        )
    if not (np.all(np.isfinite(r)) and np.all(np.isfinite(f))):
        raise ParameterError("f", "finite values", "non-finite entries")
    if np.any(np.diff(r) <= 0) or r[0] < 0:
        raise ParameterError("r", "increasing radii >= 0", "unsorted or negative radii")
    if np.max(np.abs(x)) > r[-1] * (1 + 1e-12):
        raise ParameterError(
            "x", f"|x| <= {r[-1]:g} m (the table's extent)", float(np.max(np.abs(x)))
        )
    spline = CubicSpline(r, f).derivative()
    return profile_transform(spline, x, n_quad=n_quad)


# ------------------------------------------------------- the spring row (1D)


def _as_row(x, g) -> tuple[np.ndarray, np.ndarray, float]:
    x = np.asarray(x, dtype=float)
    g = np.asarray(g, dtype=float)
    if x.ndim != 1 or x.shape != g.shape or x.size < 2:
        raise ParameterError(
            "x, g", "two 1D arrays of equal length >= 2", f"shapes {x.shape}, {g.shape}"
        )
    dx = (x[-1] - x[0]) / (x.size - 1)
    if not dx > 0:
        raise ParameterError("x", "increasing, uniformly spaced positions", "non-increasing")
    return x, g, float(dx)


def spring_widths(f: np.ndarray, dx: float) -> np.ndarray:
    """Effective width (m) of each spring for the compression ``f = d - g`` (m).

    The exact integral of the positive part of the piecewise-linear line
    through ``f`` equals ``sum(widths * f)``: a cell with both ends in contact
    gives ``dx/2`` to each end; a cell cut by the contact edge gives its
    in-contact end half the distance ``t`` to the sub-grid root (the triangle
    ``f_i t / 2``); an infinite neighbour (a punch wall) puts the edge at the
    cell middle.  The outermost springs also own the half cell beyond the
    row, so that a closed row has the length ``n dx``.  Works along the last
    axis of ``f`` (a stack of profiles).
    """
    return _edge_weights(f, dx, lengths=False)


def contact_lengths(f: np.ndarray, dx: float) -> np.ndarray:
    """Length (m) of the contact owned by each spring for the compression ``f = d - g`` (m).

    Equals :func:`spring_widths` except in the cells cut by the contact edge
    (there the whole sub-grid length ``t``, not ``t/2``); the sum is the
    contact length, i.e. ``dF/dd / E*``.  :class:`TangentialMDR` gives each
    spring the tangential stiffness ``G*`` times this length.
    """
    return _edge_weights(f, dx, lengths=True)




def _edge_weights(f: np.ndarray, dx: float, lengths: bool) -> np.ndarray:
    """Spring widths (``lengths=False``) or contact lengths owned by each spring (True)."""
    f = np.asarray(f, dtype=float)
    pos = f > 0
    w = np.zeros_like(f)
    w[..., 0] = np.where(pos[..., 0], 0.5 * dx, 0.0)
    w[..., -1] = np.where(pos[..., -1], 0.5 * dx, 0.0)
    fl, fr = f[..., :-1], f[..., 1:]
    pl, pr = pos[..., :-1], pos[..., 1:]
    both = pl & pr
    with np.errstate(invalid="ignore", divide="ignore"):
        # in-contact end -> sub-grid root of the linear cell at t = f_l dx / (f_l - f_r);
        # an infinite neighbour (punch wall) puts the edge at the cell middle
        tl = np.where(np.isfinite(fr), fl / (fl - fr) * dx, 0.5 * dx)
        tr = np.where(np.isfinite(fl), fr / (fr - fl) * dx, 0.5 * dx)
    if lengths:  # d(area)/dd of the triangle f t / 2 is t
        el, er = tl, tr
    else:  # the triangle f t / 2 is carried by a width t / 2; a wall: rectangle f dx / 2
        el = np.where(np.isfinite(fr), 0.5 * tl, 0.5 * dx)
        er = np.where(np.isfinite(fl), 0.5 * tr, 0.5 * dx)
    w[..., :-1] += np.where(both, 0.5 * dx, np.where(pl, el, 0.0))
    w[..., 1:] += np.where(both, 0.5 * dx, np.where(pr, er, 0.0))
    return w


def normal_force(x, g, d, E_star) -> float:
    """Return the normal force (N) of the spring row at rigid indentation ``d`` (m), no adhesion.

    ``F = E* int max(d - g(x), 0) dx`` over the piecewise-linear row, edges
    resolved sub-grid.  For an axisymmetric profile this is the 3D force.

    Parameters
    ----------
    x, g : ndarray
        Spring positions (m, uniform) and gap (m).
    d : float
        Indentation (m), measured from first touch of ``g.min()``.
    E_star : float
        Effective modulus E* (Pa).
    """
    x, g, dx = _as_row(x, g)
    f = float(d) - g
    return float(E_star) * float(np.dot(spring_widths(f, dx), np.where(f > 0, f, 0.0)))


def normal_stiffness(x, g, d, E_star) -> float:
    """Return the normal stiffness ``dF/dd`` (N/m) = E* times the contact length of the row."""
    return float(E_star) * contact_length(x, g, d)


def contact_length(x, g, d) -> float:
    """Total length (m) of the row in contact at indentation ``d`` (m).

    This is a 1D MDR quantity; for rough surfaces it is **not** a contact area.
    For an axisymmetric profile it is ``2 a`` (the contact diameter).
    """
    x, g, dx = _as_row(x, g)
    return float(np.sum(contact_lengths(float(d) - g, dx)))


def contact_radius(x, g, d) -> float:
    """Contact radius a (m) of an axisymmetric, non-adhesive row: half the contact length."""
    return 0.5 * contact_length(x, g, d)


# ---------------------------------------------------- axisymmetric (smooth)


@dataclass
class _JKRCurve:
    a: np.ndarray
    d: np.ndarray
    force: np.ndarray


class AxisymmetricMDR:
    """Smooth axisymmetric MDR: force, pressure, displacement and JKR adhesion.

    The half profile ``x >= 0`` (finite values only) is interpolated by a
    not-a-knot cubic spline, which is exact for the sphere and the cone and
    gives ``g'`` for the inverse transforms.  For the flat punch the edge is
    the last finite node plus half a cell.

    Parameters
    ----------
    x, g : ndarray
        A symmetric spring row from :func:`axisymmetric_profile` (m).
    E_star : float
        Effective modulus (Pa).
    work_of_adhesion : float
        Dupré work of adhesion ``dgamma`` (J/m^2); 0 = no adhesion.
    """

    def __init__(self, x, g, E_star: float, work_of_adhesion: float = 0.0):
        from scipy.interpolate import CubicSpline

        x, g, dx = _as_row(x, g)
        self.E_star = check_positive("E_star", E_star, "Pa")
        self.work_of_adhesion = check_range(
            "work_of_adhesion", work_of_adhesion, 0.0, None, unit="J/m^2"
        )
        keep = (x >= -1e-12 * dx) & np.isfinite(g)
        xh, gh = np.abs(x[keep]), g[keep]
        if xh.size < 4:
            raise ParameterError(
                "n_springs", "at least 4 finite springs on the half row", int(xh.size)
            )
        self.dx = dx
        self.x_edge = float(xh[-1])
        # A punch wall (inf beyond): the edge is half a cell further out.
        self.wall = bool(np.any(~np.isfinite(g)))
        if self.wall:
            self.x_edge = float(xh[-1] + 0.5 * dx)
        self._g = CubicSpline(xh, gh, bc_type="not-a-knot", extrapolate=True)
        self._gp = self._g.derivative()
        self._G = self._g.antiderivative()
        self._G0 = float(self._G(0.0))

    # --- primitive pieces -------------------------------------------------
    def g(self, x):
        """Return the transformed gap (m) at ``|x|``."""
        return self._g(np.abs(x))

    def _int_g(self, a):
        return self._G(a) - self._G0

    def _check_a(self, a):
        if np.any(np.asarray(a) > self.x_edge * (1 + 1e-12)):
            raise NoContactError(
                f"contact radius {float(np.max(a)):.6g} m exceeds the "
                f"spring row (x_max = {self.x_edge:.6g} m); increase x_max"
            )

    # --- non-adhesive -------------------------------------------------------
    def radius(self, d: float) -> float:
        """Contact radius (m) at indentation ``d`` (m) without adhesion."""
        from scipy.optimize import brentq

        if d <= 0:
            return 0.0
        if self.wall:
            return self.x_edge
        hi = self.x_edge
        if float(self._g(hi)) < d:
            self._check_a(hi * 1.0001)
        return float(brentq(lambda a: float(self._g(a)) - d, 0.0, hi, xtol=1e-15 * hi, rtol=1e-15))

    def force(self, d: float) -> float:
        """Return the normal force (N) at indentation ``d`` (m), with adhesion if any."""
        if self.work_of_adhesion > 0:
            return self.jkr_at_indentation(d)[1]
        a = self.radius(d)
        return 2.0 * self.E_star * (d * a - float(self._int_g(a)))

    # --- adhesive (Heß's rule) ---------------------------------------------
    def _edge_gap(self, a):
        """Critical spring elongation sqrt(2 pi a dgamma / E*) (m)."""
        return np.sqrt(2.0 * math.pi * np.asarray(a) * self.work_of_adhesion / self.E_star)

    def jkr_indentation(self, a):
        """Indentation (m) for contact radius ``a`` (m): ``d = g(a) - sqrt(2 pi a dgamma/E*)``."""
        self._check_a(a)
        return self._g(a) - self._edge_gap(a)

    def jkr_force(self, a):
        """Force (N) for contact radius ``a`` (m): ``F = 2E*(d a - int_0^a g dx)``."""
        d = self.jkr_indentation(a)
        return 2.0 * self.E_star * (d * np.asarray(a) - self._int_g(a))

    def jkr_curve(self, n: int = 400, a_max: float | None = None) -> _JKRCurve:
        """Force-indentation curve parametrised by the contact radius, unstable branch included."""
        a_max = self.x_edge if a_max is None else a_max
        a = np.linspace(a_max / n, a_max, n)
        return _JKRCurve(a=a, d=self.jkr_indentation(a), force=self.jkr_force(a))

    def _jkr_slopes(self, a):
        """``dd/da`` (dimensionless) and ``dF/da`` (N/m) along the JKR curve."""
        a = np.asarray(a, dtype=float)
        edge = self._edge_gap(a)
        dd = self._gp(a) - edge / (2.0 * a)
        return dd, 2.0 * self.E_star * (dd * a - edge)

    def _stationary(self, which: int) -> float:
        """Contact radius (m) where ``d(a)`` (which=0) or ``F(a)`` (which=1) is minimal.

        Found as the root of the analytic slope (spline derivative), so the
        fixed-grips force is not limited by the sqrt(eps) flatness of a minimum.
        """
        from scipy.optimize import brentq

        a_hi = self.x_edge
        a = np.geomspace(a_hi * 1e-8, a_hi, 600)
        s = self._jkr_slopes(a)[which]
        up = np.nonzero((s[:-1] < 0) & (s[1:] >= 0))[0]
        if up.size == 0:
            raise NoContactError("adhesive minimum not inside the spring row; increase x_max")
        i = int(up[0])
        return float(
            brentq(
                lambda x: float(self._jkr_slopes(x)[which]),
                a[i],
                a[i + 1],
                xtol=1e-15 * a[i + 1],
                rtol=1e-15,
            )
        )

    def pull_off(self, control: str = "force") -> dict:
        """Pull-off (N, negative = tensile) under ``"force"`` or ``"displacement"`` control.

        Force control: the minimum of F(a).  Displacement (fixed grips): the
        force where ``d(a)`` is minimal (the jump-out instability).

        Returns
        -------
        dict
            ``force`` (N), ``indentation`` (m), ``contact_radius`` (m).
        """
        if self.work_of_adhesion <= 0:
            raise ParameterError(
                "work_of_adhesion", "a value > 0 for a pull-off force", self.work_of_adhesion
            )
        if control not in ("force", "displacement"):
            raise ParameterError("control", "one of ['force', 'displacement']", control)
        a = self._stationary(1 if control == "force" else 0)
        return {
            "force": float(self.jkr_force(a)),
            "indentation": float(self.jkr_indentation(a)),
            "contact_radius": a,
        }

    def jkr_at_indentation(self, d: float) -> tuple[float, float]:
        """Contact radius (m) and force (N) on the stable (larger-a) JKR branch at ``d`` (m).

        Raises :class:`NoContactError` when ``d`` is below the fixed-grips
        pull-off indentation (the surfaces have separated).
        """
        from scipy.optimize import brentq

        a_c = self._stationary(0)
        d_c = float(self.jkr_indentation(a_c))
        if d < d_c:
            raise NoContactError(
                f"indentation {d:.6g} m is below the pull-off indentation {d_c:.6g} m"
            )
        hi = self.x_edge
        if float(self.jkr_indentation(hi)) < d:
            self._check_a(hi * 1.0001)
        a = brentq(
            lambda s: float(self.jkr_indentation(s)) - d, a_c, hi, xtol=1e-15 * hi, rtol=1e-15
        )
        return float(a), float(self.jkr_force(a))

    # --- inverse transforms --------------------------------------------------
    def _contact_state(self, d: float) -> tuple[float, float]:
        """Contact radius a (m) and the edge value ``q(a-)/E* = d - g(a-)`` (m)."""
        if self.work_of_adhesion > 0:
            a, _ = self.jkr_at_indentation(d)
            return a, float(d - self._g(a))
        a = self.radius(d)
        if self.wall:
            return a, float(d - self._g(self.x_edge - 0.5 * self.dx))
        return a, 0.0

    def pressure(self, r, d: float) -> np.ndarray:
        """Contact pressure p(r) (Pa, compressive positive) at indentation ``d`` (m).

        ``p(r) = -(1/pi) int_r^a q'(x)/sqrt(x^2-r^2) dx`` with ``q = E*(d - g)``
        and a jump ``q(a-)`` at the edge, which gives the ``1/sqrt(a^2-r^2)``
        edge singularity of the flat punch and of JKR.  The substitution
        ``x = r cosh t`` removes the inverse square root.
        """
        r = np.atleast_1d(np.asarray(r, dtype=float))
        a, jump = self._contact_state(d)
        p = np.zeros_like(r)
        inside = r < a
        # r -> 0: clip at 1e-9 a (T <= 21.4) so that the Gauss rule stays
        # accurate; the cone's log singularity then saturates there.
        ri = np.maximum(r[inside], 1e-9 * a)
        T = np.arccosh(np.maximum(a / ri, 1.0))
        t = T[:, None] * _GL_X[None, :]
        integral = T * np.sum(self._gp(ri[:, None] * np.cosh(t)) * _GL_W, axis=1)
        with np.errstate(divide="ignore"):
            edge = jump / np.sqrt(a * a - r[inside] ** 2)
        p[inside] = self.E_star / math.pi * (integral + edge)
        return p

    def displacement(self, r, d: float) -> np.ndarray:
        """Surface displacement w(r) (m, into the body) of the 3D half-space.

        ``w(r) = (2/pi) int_0^min(r,a) w1D(x)/sqrt(r^2-x^2) dx`` with
        ``w1D = d - g`` in contact and 0 outside; ``x = r sin t`` removes the
        singularity.
        """
        r = np.atleast_1d(np.asarray(r, dtype=float))
        a, _ = self._contact_state(d)
        out = np.empty_like(r)
        rr = np.maximum(r, 1e-300)
        tm = np.arcsin(np.minimum(a / rr, 1.0))
        t = tm[:, None] * _GL_X[None, :]
        xs = rr[:, None] * np.sin(t)
        out[:] = 2.0 / math.pi * tm * np.sum((d - self._g(xs)) * _GL_W, axis=1)
        return out


# --------------------------------------------------------------- tangential


class TangentialMDR:
    """Spring row with per-spring Coulomb friction and memory (Cattaneo-Mindlin).

    Each spring i in contact carries a normal force ``E* w_i f_i`` and a
    tangential force ``G* l_i s_i`` (``f_i = d - g_i`` its compression,
    ``w_i`` its width from :func:`spring_widths`, ``l_i`` the contact length
    it owns, equal to ``w_i`` except in the cells cut by the contact edge,
    so that the sticking stiffness is ``G*`` times the contact length and
    full sliding gives exactly ``mu F_N``; ``s_i`` its tangential
    elongation).  Coulomb's law per spring, ``|G* l_i s_i| <= mu E* w_i f_i``, is
    enforced after every step: springs that would exceed it slip and keep the
    limiting elongation.  Springs entering contact start unstretched; springs
    leaving contact forget their state.  Any quasi-static history (loading,
    unloading, oscillation, varying normal load) is followed this way.

    Parameters
    ----------
    x, g : ndarray
        Spring positions and gap (m).
    E_star, G_star : float
        Effective normal and (MDR) tangential moduli (Pa).
    mu : float
        Coulomb friction coefficient (dimensionless, >= 0).

    Attributes
    ----------
    stiffness_x : float
        Current tangential stiffness of the sticking springs (N/m).
    """

    def __init__(self, x, g, E_star: float, G_star: float, mu: float):
        self.x, self.g, self.dx = _as_row(x, g)
        self.E_star = check_positive("E_star", E_star, "Pa")
        self.G_star = check_positive("G_star", G_star, "Pa")
        self.mu = check_range("mu", mu, 0.0, None)
        self.reset()

    def reset(self) -> None:
        """Forget the history: no contact, unstretched springs, u = 0."""
        self.s = np.zeros_like(self.x)
        self.in_contact = np.zeros(self.x.shape, dtype=bool)
        self.stick = np.zeros(self.x.shape, dtype=bool)
        self.u = 0.0
        self.d = 0.0
        self.stiffness_x = 0.0
        self.force_n = 0.0
        self.force_x = 0.0

    def step(self, d: float, u: float) -> tuple[float, float]:
        """Move the indenter to indentation ``d`` (m) and tangential displacement ``u`` (m).

        Returns
        -------
        F_n, F_x : float
            Normal and tangential force (N).
        """
        f = float(d) - self.g
        contact = f > 0
        du = float(u) - self.u
        w = spring_widths(f, self.dx)  # carries the normal force
        ln = contact_lengths(f, self.dx)  # carries the tangential stiffness
        kept = contact & self.in_contact
        s = np.where(kept, self.s + du, 0.0)
        with np.errstate(invalid="ignore", divide="ignore"):
            # Coulomb: |G* l s| <= mu E* w f; l = w except in the cells cut by the edge
            limit = np.where(contact, self.mu * self.E_star * w * f / (self.G_star * ln), 0.0)
        slip = np.abs(s) >= limit
        s = np.where(slip, np.sign(s) * limit, s)
        self.s, self.in_contact, self.u, self.d = s, contact, float(u), float(d)
        self.stick = contact & ~slip
        self.stiffness_x = self.G_star * float(np.sum(ln[self.stick]))
        self.force_n = self.E_star * float(np.dot(w, np.where(contact, f, 0.0)))
        self.force_x = self.G_star * float(np.dot(ln, s))
        return self.force_n, self.force_x
