"""The contact springs under the rigid body: a thin layer over the MDR contact model.

Everything mechanical comes from :mod:`tribolmp.models.contact.mdr` (profiles,
normal force, per-spring widths, :class:`TangentialMDR`); this module only
inverts the normal law (load -> indentation) and tabulates the load-dependent
quantities the body dynamics needs.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ...errors import NoContactError, ParameterError

__all__ = ["ContactSprings", "profile_from_geometry"]


def profile_from_geometry(kind: str, normal_force: float, E_star: float, *, n_springs: int = 401,
                          radius: float | None = None, half_angle_deg: float | None = None,
                          exponent: float | None = None, coefficient: float | None = None):
    """MDR spring row (x, g) for an axisymmetric indenter, sized to hold ``normal_force``.

    The row half-length is 1.5 times the contact radius at ``normal_force`` (N)
    estimated from the closed forms (Hertz, cone, punch), so that the springs
    resolve the contact.  Returns ``(x, g)`` in m.
    """
    from ..contact.mdr import axisymmetric_profile

    N = max(float(normal_force), 1e-30)
    if kind == "sphere":
        a = (3.0 * N * radius / (4.0 * E_star)) ** (1.0 / 3.0)
    elif kind == "cone":
        a = math.sqrt(N * math.tan(math.radians(half_angle_deg)) / (math.pi * E_star) * 2.0)
    elif kind == "flat":
        a = radius
    elif kind == "power":
        # F ~ 2 E* kappa c a^(n+1) n/(n+1): invert the power law's force-radius relation
        from ..contact.mdr import kappa

        a = (N * (exponent + 1) / (2 * E_star * exponent * kappa(exponent) * coefficient)) ** (
            1.0 / (exponent + 1)
        )
    else:
        raise ParameterError("profile", "one of ['sphere', 'cone', 'flat', 'power']", kind)
    return axisymmetric_profile(
        kind,
        n_springs,
        1.5 * a,
        radius=radius,
        half_angle_deg=half_angle_deg,
        exponent=exponent,
        coefficient=coefficient,
    )


@dataclass
class ContactSprings:
    """One MDR contact (spring row) with the load-dependent quantities the dynamics needs.

    Parameters
    ----------
    x, g : ndarray
        Spring positions and transformed gap (m), from the contact model.
    E_star, G_star : float
        Effective normal and MDR tangential moduli (Pa).
    mu : float
        Local Coulomb coefficient of each spring.
    """

    x: np.ndarray
    g: np.ndarray
    E_star: float
    G_star: float
    mu: float
    _table: tuple | None = field(default=None, repr=False)

    def indentation(self, load: float) -> float:
        """Indentation d (m) at which the MDR normal force equals ``load`` (N)."""
        from scipy.optimize import brentq

        from ..contact.mdr import normal_force

        if load <= 0.0:
            return 0.0
        g0 = float(np.min(self.g))
        span = float(np.max(self.g[np.isfinite(self.g)]) - g0)
        hi = g0 + max(span, 1e-15)
        f_hi = normal_force(self.x, self.g, hi, self.E_star)
        if f_hi < load:
            if not np.all(np.isfinite(self.g)):  # flat punch: force is linear beyond full contact
                hi = g0 + load / f_hi * (hi - g0) * 1.000001 if f_hi > 0 else hi
            else:
                raise NoContactError(
                    "contact: the spring row is too short to "
                    f"carry {load:g} N (max {f_hi:g} N); widen x_max"
                )
        return brentq(
            lambda d: normal_force(self.x, self.g, d, self.E_star) - load,
            g0,
            hi,
            xtol=1e-16,
            rtol=1e-13,
        )

    def normal_force(self, d: float) -> float:
        """MDR normal force (N) at indentation ``d`` (m)."""
        from ..contact.mdr import normal_force

        return normal_force(self.x, self.g, d, self.E_star)

    def springs(self, load: float) -> tuple[np.ndarray, np.ndarray]:
        """Per-spring normal forces (N) and tangential stiffnesses (N/m) at ``load``.

        Normal forces ``E* w_i f_i``, tangential stiffnesses ``G* l_i``.

        ``w_i`` is the spring width and ``l_i`` the contact length it owns, as
        in :class:`TangentialMDR` (they differ only in the cells cut by the
        contact edge), so that these springs are exactly those of the contact model.
        """
        from ..contact import mdr

        d = self.indentation(load)
        f = d - self.g
        dx = (self.x[-1] - self.x[0]) / (self.x.size - 1)
        w = mdr.spring_widths(f, dx)
        # TangentialMDR's per-spring contact lengths (no public name yet in the contact model)
        ln = mdr.contact_lengths(f, dx)
        return self.E_star * w * np.where(f > 0, f, 0.0), self.G_star * ln

    def tangential(self):
        """Return a fresh :class:`~tribolmp.models.contact.mdr.TangentialMDR` on this row."""
        from ..contact.mdr import TangentialMDR

        return TangentialMDR(self.x, self.g, self.E_star, self.G_star, self.mu)

    def stiffness(self, load: float) -> float:
        """Return the initial tangential stiffness (N/m) at ``load``: all contact springs sticking.

        Taken from :attr:`TangentialMDR.stiffness_x` after a normal approach
        without tangential motion (``2 G* a`` for an axisymmetric contact).
        """
        if load <= 0.0:
            return 0.0
        t = self.tangential()
        t.step(self.indentation(load), 0.0)
        return float(t.stiffness_x)

    def stiffness_table(self, load_max: float, n: int = 64):
        """Callable ``k(N)`` (N/m) interpolating :meth:`stiffness` on ``[0, load_max]``.

        Used for varying loads.
        """
        loads = load_max * np.linspace(0.0, 1.0, n) ** 3  # dense near 0, where k ~ N^(1/3)
        ks = np.array([self.stiffness(L) for L in loads])
        return lambda N: float(np.interp(N, loads, ks))
