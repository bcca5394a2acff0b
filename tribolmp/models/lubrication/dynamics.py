"""Film dynamics: a sphere (or a rough MDR profile) pressed through a lubricant film (SI).

Smooth sphere under a constant load W
--------------------------------------
Every squeeze law here has the form W = c(h) V^n with V = -dh/dt, so the
motion is integrated through the primitive

    Phi(h) = int c(h)^(1/n) dh ,    Phi(h_k) - Phi(h_{k+1}) = W^(1/n) dt ,

which is *exact* for a constant load at any step (the damper: Phi = alpha ln h,
h(t) = h0 exp(-W t / alpha)), never produces h < 0, and, for the shear-thinning
power law (n < 1, where the gap closes in finite time), stops at contact.
``scheme="explicit"`` (forward Euler in h) is provided only to show the
failure the seed's singular damper causes at large steps.

Rough surface: mixed lubrication at the nominal scale
-----------------------------------------------------
A 1D MDR profile (springs of stiffness E* dx at gaps g_i, the contact model's
:func:`~tribolmp.models.contact.mdr.normal_force`) carries the solid share of
the load; the film carries the rest with the resistance of the *apparent*
area, the nominal Reynolds squeeze film with the roughness as a flow factor
(:mod:`.flow_factor`), plus the local resistance of each summit as it nears
contact.  The flat is stepped implicitly in the primitive of the resistance
(see :func:`mixed_approach`), so it is stable at any step.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...errors import BlowUpError, ParameterError
from ...params import param, renamed, validate_dataclass
from ..base import MethodRegistry, Result, timed

__all__ = [
    "FilmParams",
    "SCHEMES",
    "approach",
    "exact_gap",
    "MixedParams",
    "mixed_approach",
    "summits",
    "summit_resistance",
    "mixed_resistance",
    "nominal_film_table",
]

SCHEMES = MethodRegistry("film scheme")


@renamed(load="normal_force")  # old name kept (docs/conventions.md)
@dataclass(frozen=True)
class FilmParams:
    """A sphere pressed onto a plane through a film under constant load (SI).

    Attributes
    ----------
    radius : float
        R in m.
    viscosity : float
        eta in Pa s (K for a power-law fluid when ``consistency`` is None).
    normal_force : float
        Constant load W in N (old name ``load``).
    gap0 : float
        Initial gap h0 in m.
    model : str
        ``"damper"`` (6 pi eta R^2 V/h), ``"cox-brenner"`` or ``"power-law"``.
    power_law_index : float
        n > 1/3 for ``model="power-law"``.
    consistency : float or None
        K in Pa s^n.
    duration : float
        Simulated time in s.
    steps : int
        Number of time steps.
    """

    radius: float = param(1e-3, unit="m", lo=0.0, lo_open=True, hi=1e3)
    viscosity: float = param(0.1, unit="Pa s", lo=0.0, lo_open=True, hi=1e9)
    normal_force: float = param(1.0, unit="N", lo=0.0, hi=1e12)
    gap0: float = param(1e-5, unit="m", lo=0.0, lo_open=True, hi=1e3)
    model: str = param("damper", choices=("damper", "cox-brenner", "power-law"))
    power_law_index: float = param(1.0, lo=1.0 / 3.0, lo_open=True, hi=5.0)
    consistency: float | None = param(None, unit="Pa s^n", lo=0.0, lo_open=True, hi=1e9)
    duration: float = param(1e-3, unit="s", lo=0.0, lo_open=True, hi=1e12)
    steps: int = param(100, lo=1, hi=10**8)

    def __post_init__(self) -> None:
        validate_dataclass(self)
        if self.model == "cox-brenner" and self.gap0 / self.radius > 0.1:
            raise ParameterError(
                "gap0", f"<= 0.1 R = {0.1 * self.radius:g} m for model 'cox-brenner'", self.gap0
            )

    @property
    def n(self) -> float:
        """Flow index (1 unless the power-law model is chosen)."""
        return self.power_law_index if self.model == "power-law" else 1.0

    @property
    def K(self) -> float:
        """Consistency in Pa s^n."""
        return self.viscosity if self.consistency is None else self.consistency


def _power_law_coefficient(p: FilmParams) -> float:
    """C with W = C V^n h^((1-3n)/2) (closed-form power-law squeeze force)."""
    from .reference import power_law_squeeze_force

    return power_law_squeeze_force(p.radius, p.K, p.n, 1.0, 1.0)  # h0 = 1 m, V = 1 m/s


def _primitive(p: FilmParams):
    """(Phi, Phi_inverse, collapse) with Phi(h) = int c(h)^(1/n) dh (units: N^(1/n) s)."""
    alpha = 6.0 * math.pi * p.viscosity * p.radius**2
    if p.model == "damper":
        return (lambda h: alpha * np.log(h)), (lambda y: np.exp(y / alpha)), None
    if p.model == "cox-brenner":
        R = p.radius

        def phi(h):
            h = np.asarray(h, dtype=float)
            return alpha * (np.log(h) + 0.2 / R * (h * np.log(R / h) + h) + 0.9713 * h / R)

        def inv_log(y):
            from scipy.optimize import brentq

            y = float(y)
            # solve in u = ln h; Phi is increasing in h
            lo, hi = -700.0, math.log(10.0 * p.gap0 + R)
            if float(phi(math.exp(lo))) >= y:
                # h < e^-700 m: the corrections (h/R) ln(R/h) are < 1e-300, so Phi = alpha ln h
                # exactly in float; ln h is returned, h itself underflows (stated by approach())
                return y / alpha
            return brentq(
                lambda u: float(phi(math.exp(u))) - y, lo, hi, xtol=1e-15, rtol=1e-15, maxiter=400
            )

        def inv(y):
            return math.exp(inv_log(y))

        inv.log = inv_log
        return phi, inv, None
    n = p.n
    C = _power_law_coefficient(p)
    # c(h)^(1/n) = C^(1/n) h^(-m), m = (3n-1)/(2n); Phi = C^(1/n) h^(1-m)/(1-m) (m != 1)
    m = (3.0 * n - 1.0) / (2.0 * n)
    c = C ** (1.0 / n)
    if abs(1.0 - m) < 1e-12:
        return (lambda h: c * np.log(h)), (lambda y: np.exp(y / c)), None
    e = 1.0 - m

    def phi(h):
        return c * np.asarray(h, dtype=float) ** e / e

    def inv(y):
        base = y * e / c
        if e > 0 and base <= 0:  # n < 1: the film has closed (finite-time collapse)
            return 0.0
        return base ** (1.0 / e)

    return phi, inv, (e > 0)


def exact_gap(p: FilmParams, t):
    """Exact gap h(t) (m) under constant load for ``p.model`` (0 after a film collapse)."""
    phi, inv, _ = _primitive(p)
    y0 = float(phi(p.gap0))
    W = p.normal_force ** (1.0 / p.n)
    return np.array([inv(y0 - W * float(tt)) for tt in np.atleast_1d(t)])


def _log_gap(p: FilmParams, t: np.ndarray) -> np.ndarray:
    """Ln h(t) without underflow for the damper (ln h = ln h0 - W t / alpha); else ln of the gap."""
    if p.model == "damper":
        return math.log(p.gap0) - p.normal_force * t / (6.0 * math.pi * p.viscosity * p.radius**2)
    phi, inv, _ = _primitive(p)
    if hasattr(inv, "log"):  # Cox-Brenner: ln h without underflow
        y0, W = float(phi(p.gap0)), p.normal_force ** (1.0 / p.n)
        return np.array([inv.log(y0 - W * float(tt)) for tt in np.atleast_1d(t)])
    with np.errstate(divide="ignore"):
        return np.log(exact_gap(p, t))


@SCHEMES.register("log")
def _log_scheme(p: FilmParams, t: np.ndarray) -> tuple[np.ndarray, int]:
    phi, inv, _ = _primitive(p)
    h = np.empty_like(t)
    h[0] = p.gap0
    y = float(phi(p.gap0))
    W = p.normal_force ** (1.0 / p.n)
    for k in range(1, t.size):
        y -= W * (t[k] - t[k - 1])
        h[k] = inv(y) if h[k - 1] > 0 else 0.0
    return h, t.size - 1


@SCHEMES.register("explicit")
def _explicit(p: FilmParams, t: np.ndarray) -> tuple[np.ndarray, int]:
    # Forward Euler in h: V = (W / c(h))^(1/n).  Shown for comparison only.
    from .reference import cox_brenner_force

    h = np.empty_like(t)
    h[0] = p.gap0
    C = _power_law_coefficient(p) if p.model == "power-law" else None
    for k in range(1, t.size):
        hk = h[k - 1]
        if not hk > 0:
            h[k:] = hk
            break
        if p.model == "damper":
            V = p.normal_force * hk / (6.0 * math.pi * p.viscosity * p.radius**2)
        elif p.model == "cox-brenner":
            V = p.normal_force / float(cox_brenner_force(p.radius, p.viscosity, hk, 1.0))
        else:
            V = (p.normal_force / (C * hk ** ((1.0 - 3.0 * p.n) / 2.0))) ** (1.0 / p.n)
        h[k] = hk - V * (t[k] - t[k - 1])
    return h, t.size - 1


def approach(params: FilmParams, *, scheme: str = "log", rng=None) -> Result:
    """Integrate the approach of a sphere under constant load through the film.

    Parameters
    ----------
    params : FilmParams
    scheme : {"log", "explicit"}
        ``log``: exact primitive (stable at any step, h >= 0); ``explicit``:
        forward Euler in h (can overshoot to h < 0; comparison only).

    Returns
    -------
    Result
        ``t`` (s), ``h`` (m), ``h_exact`` (m), ``max_rel_error``, ``collapsed``
        (the film closed: finite-time collapse of a shear-thinning film),
        ``min_gap`` (m), ``status`` (-1 if the gap went negative).
    """
    impl = SCHEMES.get(scheme, "scheme")
    res = Result(method=scheme)
    t = np.linspace(0.0, params.duration, params.steps + 1)
    with timed(res):
        h, nit = impl(params, t)
    h_ex = exact_gap(params, t)
    pos = h_ex > 0
    err = np.abs(h[pos] / h_ex[pos] - 1.0) if pos.any() else np.array([0.0])
    res.update(
        t=t,
        h=h,
        h_exact=h_ex,
        max_rel_error=float(np.nanmax(err)) if err.size else 0.0,
        min_gap=float(np.nanmin(h)),
        # only the shear-thinning power law closes the film in finite time; a damper
        # gap that underflows to 0.0 in float is still open (see log_h)
        collapsed=bool(_primitive(params)[2] and h[-1] == 0.0),
        log_h=np.log(np.where(h > 0, h, np.nan)) if scheme == "explicit" else _log_gap(params, t),
        nit=nit,
        units={"t": "s", "h": "m", "h_exact": "m", "min_gap": "m", "log_h": "ln(m)"},
    )
    if not np.all(np.isfinite(h)) or res.min_gap < 0:
        res.status = -1
        res.message = (
            f"gap went negative ({res.min_gap:.3g} m): the step is too large for scheme '{scheme}'"
        )
    else:
        res.message = "film collapsed (contact)" if res.collapsed else "film intact"
        under = (h == 0.0) & ~res.collapsed
        if under.any():
            res.underflow_time = float(t[np.argmax(under)])
            res.message += (
                "; the gap fell below the smallest float "
                f"(1e-308 m) at t = {res.underflow_time:.3g} s: "
                "h is reported as 0, log_h carries ln h"
            )
    return res


# ------------------------------------------------------------------ mixed lubrication


@renamed(load="normal_force")  # old name kept (docs/conventions.md)
@dataclass(frozen=True)
class MixedParams:
    """Mixed lubrication of a rough apparent contact: MDR springs plus the nominal film (SI).

    Attributes
    ----------
    viscosity : float
        eta in Pa s.
    E_star : float
        Effective modulus E* in Pa.
    normal_force : float
        Constant load W in N on the apparent contact (old name ``load``).
    gap0 : float
        Initial distance of the flat from the highest point in m.
    film_cutoff : float
        Film rupture thickness h_c in m (the summit dampers use gap + h_c).
    duration : float
        Simulated time in s.
    steps : int
        Time steps.
    apparent_length : float or None
        Side (square) or diameter (disc) of the apparent contact in m; default
        the length of the MDR line (the line represents an L x L area).
    apparent_shape : str
        ``"square"`` or ``"disc"``.
    flow_factor : str
        Film conductance of the rough gap: ``"bruggeman"`` (derived, default),
        ``"patir-cheng"`` (published fit) or ``"smooth"`` (no roughness in the film).
    nominal_film : bool
        Include the nominal squeeze film of the apparent area (switch it off
        only for a single smooth summit, e.g. a sphere, whose one damper is
        already its whole Reynolds film).
    summit_dampers : bool
        Add the local resistance of each summit (the inner, near-contact
        singularity of the film; see :func:`summit_resistance`).
    summit_model : str
        ``"matched"`` (default): with the nominal film, each summit adds only
        its excess over the nominal film, ``6 pi eta R_j^2 (1/s - 2/u + s/u^2)``
        (``s = gap_j + h_c``, ``u``: separation of the flat from the mean plane),
        the paraboloid's film cut at the mean-plane gap (derived in
        :func:`summit_resistance`; checked against resolved 2D Reynolds solves,
        docs/lubrication.md).  ``"full"``: the whole paraboloid damper
        ``6 pi eta R_j^2 / s`` on top of the nominal film (the earlier model; it
        counts the summit's outer film twice).  Without the nominal film the
        full damper is always used (it is then the whole film of the summit).
    """

    viscosity: float = param(0.1, unit="Pa s", lo=0.0, lo_open=True, hi=1e9)
    E_star: float = param(1e11, unit="Pa", lo=0.0, lo_open=True, hi=1e13)
    normal_force: float = param(1.0, unit="N", lo=0.0, hi=1e12)
    gap0: float = param(1e-6, unit="m", lo=0.0, lo_open=True, hi=1.0)
    film_cutoff: float = param(1e-9, unit="m", lo=0.0, lo_open=True, hi=1e-3)
    duration: float = param(1e-2, unit="s", lo=0.0, lo_open=True, hi=1e12)
    steps: int = param(200, lo=1, hi=10**7)
    apparent_length: float | None = param(None, unit="m", lo=0.0, lo_open=True, hi=10.0)
    apparent_shape: str = param("square", choices=("square", "disc"))
    flow_factor: str = param("bruggeman", choices=("bruggeman", "patir-cheng", "smooth"))
    nominal_film: bool = param(True)
    summit_dampers: bool = param(True)
    summit_model: str = param("matched", choices=("matched", "full"))

    def __post_init__(self) -> None:
        validate_dataclass(self)
        if not (self.nominal_film or self.summit_dampers):
            raise ParameterError(
                "nominal_film", "True when summit_dampers is False (no film at all)", False
            )


def summits(x, g):
    """Summits of an MDR gap profile: indices of local minima of g and radii R_j (m).

    The MDR image of a paraboloid r^2/2R is x^2/R, so R_j = 2 / g''(x_j).
    """
    x, g = np.asarray(x, float), np.asarray(g, float)
    dx = x[1] - x[0]
    inner = np.arange(1, g.size - 1)
    is_min = (g[inner] <= g[inner - 1]) & (g[inner] < g[inner + 1])
    idx = inner[is_min]
    curv = (g[idx - 1] - 2.0 * g[idx] + g[idx + 1]) / dx**2
    ok = curv > 0
    return idx[ok], 2.0 / curv[ok]


def _summit_terms(d, gj, radii, viscosity, hc, gbar, matched):
    """(c, Phi): summed summit resistance (N s/m) and its primitive in d (N s) at indentation d.

    ``matched``: per summit ``c_j = alpha (u - s)^2 / (s u^2)`` for s < u, else
    0 (``alpha = 6 pi eta R_j^2``, ``s = max(g_j - d, 0) + h_c``,
    ``u = gbar - d``).  While the summit is open ``u - s = delta_j =
    gbar - g_j - h_c`` is constant and ``Phi_j = -alpha (ln(s/u) + delta_j/u)``;
    once it touches (s = h_c) ``Phi_j`` continues with the primitive of
    ``alpha (u - h_c)^2/(h_c u^2)`` in u.  ``full``: ``c_j = alpha/s``,
    ``Phi_j = -alpha ln s``.  Phi is continuous and increasing in d.
    """
    alpha = 6.0 * math.pi * viscosity * np.asarray(radii, float) ** 2
    gj = np.asarray(gj, float)
    s = np.clip(gj - d, 0.0, None) + hc
    if not matched:
        return float(np.sum(alpha / s)), float(np.sum(-alpha * np.log(s)))
    u = gbar - d
    c = np.where(s < u, alpha * (u - s) ** 2 / (s * u**2), 0.0)
    delta = gbar - gj - hc
    live = delta > 0
    if not np.any(live):
        return float(np.sum(c)), 0.0
    a, dl, g_l = alpha[live], delta[live], gj[live]
    uj = gbar - g_l  # u at first touch of summit j (= delta_j + h_c)
    if hc <= 0.0:  # no cut-off (summit_resistance only): c is defined, Phi is not needed
        return float(np.sum(c)), float("nan")
    phi_touch = -a * (np.log(hc / uj) + dl / uj)

    def big_g(uu):
        return uu - 2.0 * hc * np.log(uu) - hc**2 / uu

    open_ = g_l > d
    phi = np.where(
        open_,
        -a * (np.log((np.clip(g_l - d, 0.0, None) + hc) / u) + dl / u),
        phi_touch - a / hc * (big_g(u) - big_g(uj)),
    )
    return float(np.sum(c)), float(np.sum(phi))


def summit_resistance(
    summit_gaps, radii, viscosity: float, film_cutoff: float, separation=None
) -> float:
    """Near-contact resistance (N s/m) of paraboloidal summits, as the mixed model adds it.

    One summit of radius R at gap h above a flat has the thin-film resistance
    ``6 pi eta R^2 / h`` (the paraboloid's Reynolds film, exact).  On a rough
    surface its gap only grows like ``h + r^2/2R`` out to where it meets the
    rest of the surface, and the nominal film of the apparent area already
    carries that outer part.  Cutting the paraboloid at the mean-plane gap
    ``u`` (the outer, nominal gap) and keeping only what lies above the
    nominal pressure gives, from the exact radial flux ``V r/2``,

        c = 6 pi eta int_0^{a} r^3 / h^3 dr - (nominal part)
          = 6 pi eta R^2 (1/h - 2/u + h/u^2) ,      a^2 = 2 R (u - h),

    (``= 6 pi eta R^2 (u - h)^2 / (h u^2)``; the same integral gives the flat
    plate's film for the rest of the area).  It tends to the full damper as
    h/u -> 0 and vanishes at h = u.  ``h`` is the summit's gap plus the film
    cut-off ``h_c``.

    Parameters
    ----------
    summit_gaps : array_like
        Gap of each summit top to the flat (m, >= 0).
    radii : array_like
        R_j (m).
    viscosity : float
        eta (Pa s).
    film_cutoff : float
        h_c (m).
    separation : float, optional
        u, the flat's separation from the mean plane (m).  None: the full
        damper ``sum 6 pi eta R_j^2/(h_j + h_c)`` (no nominal film to match).
    """
    gj = np.asarray(summit_gaps, float)
    if separation is None:
        return _summit_terms(0.0, gj, radii, viscosity, film_cutoff, 0.0, False)[0]
    # d = 0 reference: g_j -> summit gaps, gbar -> separation
    return _summit_terms(0.0, gj, radii, viscosity, film_cutoff, float(separation), True)[0]


def mixed_resistance(g, d, params, length: float, summit_gaps=None, summit_radii=None):
    """Film resistance (N s/m) of :func:`mixed_approach` at indentation d, evaluated exactly.

    ``c_nom + c_summits``: the nominal film of the apparent area
    (:func:`~.flow_factor.film_resistance` on the rigid gaps ``max(g - d, 0)``,
    separation ``mean(g) - d``) plus :func:`summit_resistance` (matched or
    full, ``params.summit_model``).  ``mixed_approach`` steps the same
    resistance through a tabulated primitive (spline error < 1e-5).

    Parameters
    ----------
    g : array_like
        Height samples of the gap from the highest point (m, min 0): the MDR
        profile, or the cells of a 2D gap map minus its minimum.
    d : float
        Indentation of the flat (m; -d is the clearance of the top).
    params : MixedParams
    length : float
        Side (square) or diameter (disc) of the apparent contact (m).
    summit_gaps, summit_radii : array_like, optional
        Summit heights g_j in the same frame as g (m) and radii (m); default
        the summits of g as an MDR profile (:func:`summits`, needs x: pass them).

    Returns
    -------
    (c_total, c_nominal, c_summits) : floats
    """
    from .flow_factor import film_resistance

    g = np.asarray(g, float).ravel()
    p = params
    gbar = float(np.mean(g))
    c_nom = 0.0
    if p.nominal_film:
        c_nom = float(
            film_resistance(
                np.clip(g - d, 0.0, None),
                p.viscosity,
                p.apparent_shape,
                length,
                method=p.flow_factor,
                separation=gbar - d,
                sigma=float(np.std(g)),
            )[0]
        )
    c_s = 0.0
    if p.summit_dampers:
        c_s = _summit_terms(
            d,
            summit_gaps,
            summit_radii,
            p.viscosity,
            p.film_cutoff,
            gbar,
            p.nominal_film and p.summit_model == "matched",
        )[0]
    return c_nom + c_s, c_nom, c_s


def nominal_film_table(
    g, params: MixedParams, length: float, d_lo: float, d_hi: float, points: int = 801
):
    """Nominal film resistance c(d) (N s/m) and its primitive on a grid of indentations.

    The grid is uniform in ln u (u = mean(g) - d, the flat-to-mean-plane
    separation), where c u is smooth, and the primitive
    ``Phi(d) = int_{d_lo}^d c dd'`` (N s) is the trapezoid rule in ln u.

    Returns
    -------
    (d, c, Phi, closed_fraction) : ndarrays on the grid
    """
    from .flow_factor import film_resistance

    gbar = float(np.mean(g))
    u = np.geomspace(gbar - d_lo, gbar - d_hi, points)
    d = gbar - u
    gaps = np.clip(np.asarray(g)[None, :] - d[:, None], 0.0, None)
    c, _, closed = film_resistance(
        gaps,
        params.viscosity,
        params.apparent_shape,
        length,
        method=params.flow_factor,
        separation=u,
        sigma=float(np.std(g)),
    )
    cu = c * u
    # dd = -du = -u d(ln u): Phi increases with d
    dphi = 0.5 * (cu[1:] + cu[:-1]) * -np.diff(np.log(u))
    Phi = np.concatenate([[0.0], np.cumsum(dphi)])
    return d, c, Phi, closed


def mixed_approach(x, g, params: MixedParams, *, normal_force=None, times=None) -> Result:
    """Rigid flat pressed onto a rough MDR profile through the film of the apparent contact.

    The flat at indentation d (d < 0: separated from the highest point) obeys
    the quasi-static balance

        c(d) dd/dt + F_s(d) = W ,

    ``F_s``: the MDR springs (the solid share, :func:`tribolmp.models.contact.mdr.normal_force`);
    ``c(d)``: the film resistance of the apparent area, the nominal Reynolds
    squeeze film with the roughness as a flow factor
    (:func:`~.flow_factor.film_resistance` on the rigid gaps ``max(g - d, 0)``),
    plus, with ``summit_dampers``, ``sum_j 6 pi eta R_j^2 / (g_j - d + h_c)``
    for the summits of the profile (the near-contact singularity the nominal
    average misses).  Each step is implicit in the primitive of c
    (``Phi(d_{k+1}) - Phi(d_k) = (W - F_s(d_{k+1})) dt``, monotone in
    d_{k+1}, solved by bracketing), so it is stable at any step and never
    passes the dry equilibrium.  When the closed fraction of the rigid gap
    reaches 1/2 before the springs carry W, the Bruggeman film seals
    (``sealed = True``): the fluid left is trapped and keeps ``W - F_s``.

    Parameters
    ----------
    x, g : ndarray
        Spring positions (m, uniform spacing) and MDR gap g(x) >= 0 (m, min 0).
    params : MixedParams
    normal_force : callable, optional
        ``normal_force(x, g, d, E_star) -> N``; default the contact model's MDR.
    times : array_like, optional
        Increasing output times (s) starting at 0, instead of ``steps`` equal
        steps over ``duration`` (e.g. log-spaced for a squeeze-out figure).

    Returns
    -------
    Result
        ``t`` (s), ``d`` (m), ``separation`` (m, flat to mean plane),
        ``spring_force`` (N), ``fluid_force`` (N), ``film_resistance`` (N s/m, total c(d)),
        ``nominal_resistance`` (N s/m, the apparent-area part), ``contact_time``
        (s, first spring contact, NaN if none), ``d_dry`` (m), ``sealed``,
        ``closed_fraction`` (rigid-gap closed fraction at the end), ``min_film`` (m).
    """
    from scipy.interpolate import CubicSpline
    from scipy.optimize import brentq

    from ..contact.mdr import normal_force as mdr_normal_force

    nf, source = (
        (normal_force, "user") if normal_force is not None else (mdr_normal_force, "contact.mdr")
    )
    x, g = np.asarray(x, float), np.asarray(g, float)
    p = params
    dx = float(x[1] - x[0])
    length = p.apparent_length if p.apparent_length is not None else g.size * dx
    idx, Rj = summits(x, g)
    if p.summit_dampers and idx.size == 0:
        raise ParameterError(
            "g", "a profile with at least one summit (local minimum of the gap)", "none"
        )
    Rj = Rj if p.summit_dampers else np.zeros(0)
    gj = g[idx] if p.summit_dampers else np.zeros(0)
    hc = p.film_cutoff
    matched = p.nominal_film and p.summit_model == "matched"
    gbar = float(np.mean(g))

    def summit_terms(dd):
        return _summit_terms(dd, gj, Rj, p.viscosity, hc, gbar, matched)

    def dry(dd):
        return nf(x, g, dd, p.E_star) - p.normal_force

    hi = 1e-12
    while dry(hi) < 0:
        hi *= 2.0
        if hi > 1e3 * (float(g.max()) + p.gap0):
            raise BlowUpError(f"load {p.normal_force:g} N exceeds what the profile can carry")
    d_dry = (
        brentq(dry, -1e-300 if dry(0.0) < 0 else -p.gap0, hi, xtol=1e-18, rtol=1e-14)
        if p.normal_force > 0
        else 0.0
    )
    d0 = -p.gap0
    # the film seals where half the rigid gap is closed (Bruggeman; the median of g)
    d_seal = float(np.median(g)) if p.flow_factor == "bruggeman" and p.nominal_film else math.inf
    sealed = d_seal <= d_dry
    d_top = min(d_dry, d_seal * (1.0 - 1e-9)) if sealed else d_dry
    dg, cg, Phig, closedg = nominal_film_table(g, p, length, d0, d_top)
    # Phi is smooth in ln u; spline it there (exact at the nodes, monotone to round-off)
    lnu = np.log(gbar - dg)
    on = 1.0 if p.nominal_film else 0.0
    phi_spline = CubicSpline(lnu[::-1], on * Phig[::-1])
    c_spline = CubicSpline(lnu[::-1], np.log(cg[::-1]))

    def phi_nom(dd):
        return float(phi_spline(math.log(gbar - dd)))

    if times is None:
        t = np.linspace(0.0, p.duration, p.steps + 1)
    else:
        t = np.asarray(times, dtype=float)
        if t.ndim != 1 or t.size < 2 or t[0] != 0.0 or np.any(np.diff(t) <= 0):
            raise ParameterError(
                "times", "an increasing 1D array of times starting at 0 s", getattr(t, "shape", t)
            )
    d = np.empty_like(t)
    Fs = np.zeros_like(t)
    d[0] = d0
    res = Result(method="implicit-primitive")
    with timed(res):
        for k in range(1, t.size):
            dt = t[k] - t[k - 1]
            ps0, ph0 = summit_terms(d[k - 1])[1], phi_nom(d[k - 1])

            def resid(dd):
                film = phi_nom(dd) - ph0 + summit_terms(dd)[1] - ps0
                return film / dt + nf(x, g, dd, p.E_star) - p.normal_force

            lo = d[k - 1]
            if lo >= d_top or resid(lo) >= 0:  # at/beyond equilibrium (or sealed): stay
                d[k] = lo
            elif resid(d_top) <= 0:  # reaches the end of the table within this step
                d[k] = d_top
            else:
                d[k] = brentq(resid, lo, d_top, xtol=1e-18, rtol=1e-14)
            Fs[k] = nf(x, g, d[k], p.E_star)
    Fs[0] = nf(x, g, d[0], p.E_star)
    Ff = p.normal_force - Fs
    Ff[0] = p.normal_force
    c_nom = on * np.exp(c_spline(np.log(gbar - d)))
    c_sum = np.array([summit_terms(dd)[0] for dd in d])
    film = g[None, :] - d[:, None]
    touched = np.nonzero(film.min(axis=1) <= 0)[0]
    res.update(
        t=t,
        d=d,
        separation=gbar - d,
        spring_force=Fs,
        fluid_force=Ff,
        film_resistance=c_nom + c_sum,
        nominal_resistance=c_nom,
        summit_resistance=c_sum,
        d_dry=float(d_dry),
        sealed=bool(sealed),
        closed_fraction=float(np.mean(g <= d[-1])),
        contact_time=float(t[touched[0]]) if touched.size else float("nan"),
        min_film=float(film.min()),
        summits=int(idx.size),
        apparent_length=float(length),
        nit=int(t.size - 1),
        normal_force_source=source,
        units={
            "t": "s",
            "d": "m",
            "separation": "m",
            "spring_force": "N",
            "fluid_force": "N",
            "film_resistance": "N s/m",
            "nominal_resistance": "N s/m",
            "summit_resistance": "N s/m",
            "d_dry": "m",
            "contact_time": "s",
            "min_film": "m",
            "apparent_length": "m",
        },
        message=(
            f"nominal film ({p.flow_factor}, {p.apparent_shape} {length:.3g} m)"
            + (f" + {idx.size} summit dampers" if p.summit_dampers else "")
            + f", springs from {source}"
            + (
                "; the film sealed (closed fraction 1/2) before the springs carried the load"
                if sealed
                else ""
            )
        ),
    )
    if sealed:
        res.status = 1
    return res
