"""Contact-model parameters, the method registry and the scene adapter.

Two problems are solved by name (``method="mdr"`` or ``"bem"``):

* :func:`solve` -- an axisymmetric indenter (sphere, cone, flat punch, power
  law) at a given indentation or force, optionally adhesive (MDR only);
* :func:`solve_rough` -- a rough surface against the nominal pressure:
  stiffness, force and approach (plus the real contact area fraction for BEM).

:func:`params_from_scene` and :func:`stiffness_vs_pressure` connect both to a
:class:`tribolmp.scene.Scene`.  SI units throughout.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ...errors import BlowUpError, MissingFeatureError, ParameterError
from ...params import param, renamed, validate_dataclass
from ..base import MethodRegistry, Result
from . import mdr as _mdr
from . import reference as _ref

__all__ = [
    "REG",
    "ROUGH_REG",
    "AxisymmetricParams",
    "RoughParams",
    "solve",
    "solve_rough",
    "params_from_scene",
    "rough_params_from_scene",
    "stiffness_vs_pressure",
    "load_surface",
]

#: Axisymmetric solvers by name.
REG = MethodRegistry("contact")
#: Rough-surface solvers by name.
ROUGH_REG = MethodRegistry("rough contact")


# Old names kept: ``modulus`` (CLI --modulus), ``grid`` (CLI --grid; a bad value is named as given).
@renamed(modulus="E_star", grid="grid_points")  # docs/conventions.md
@dataclass(frozen=True)
class AxisymmetricParams:
    """An axisymmetric rigid indenter on an elastic half-space (SI units).

    Give either ``indentation`` or ``normal_force``.
    """

    profile: str = param("sphere", choices=_mdr.PROFILE_KINDS, doc="Indenter shape.")
    E_star: float = param(
        1e11, unit="Pa", lo=0.0, lo_open=True, hi=1e13, doc="Effective modulus E*."
    )
    radius: float = param(
        1e-3, unit="m", lo=0.0, lo_open=True, hi=1e3, doc="Sphere radius / punch radius."
    )
    half_angle_deg: float = param(
        80.0,
        unit="deg",
        lo=0.0,
        hi=90.0,
        lo_open=True,
        hi_open=True,
        doc="Cone half-angle from the axis.",
    )
    exponent: float = param(
        2.0, lo=0.0, lo_open=True, hi=100.0, doc="Power-law exponent n of f = c r^n."
    )
    coefficient: float = param(
        1.0, unit="m^(1-n)", lo=0.0, lo_open=True, doc="Power-law coefficient c."
    )
    indentation: float | None = param(
        None, unit="m", lo=-1e3, hi=1e3, doc="Rigid indentation d (negative only with adhesion)."
    )
    normal_force: float | None = param(
        None,
        unit="N",
        lo=0.0,
        lo_open=True,
        hi=1e12,
        doc="Prescribed normal force (alternative to d).",
    )
    work_of_adhesion: float = param(
        0.0, unit="J/m^2", lo=0.0, hi=1e6, doc="Dupre work of adhesion (JKR via Hess's rule)."
    )
    springs: int = param(2001, lo=9, hi=10**7, doc="MDR springs over the row.")
    grid_points: int = param(128, lo=16, hi=4096, doc="BEM grid points per side.")

    def __post_init__(self) -> None:
        validate_dataclass(self)
        if (self.indentation is None) == (self.normal_force is None):
            raise ParameterError(
                "indentation",
                "exactly one of indentation or normal_force",
                "both" if self.indentation is not None else "neither",
            )
        if self.indentation is not None and self.indentation <= 0 and self.work_of_adhesion == 0:
            raise ParameterError(
                "indentation", "a number in (0, 1000] m without adhesion", self.indentation
            )

    def shape(self) -> dict:
        """Keyword arguments of :func:`~tribolmp.models.contact.mdr.axisymmetric_profile`."""
        return dict(
            radius=self.radius,
            half_angle_deg=self.half_angle_deg,
            exponent=self.exponent,
            coefficient=self.coefficient,
        )

    def f(self, r):
        """Axisymmetric gap f(r) (m) of the indenter (``inf`` outside a flat punch)."""
        r = np.asarray(r, dtype=float)
        if self.profile == "sphere":
            return r * r / (2 * self.radius)
        if self.profile == "cone":
            return r / math.tan(math.radians(self.half_angle_deg))
        if self.profile == "flat":
            return np.where(r <= self.radius, 0.0, np.inf)
        return self.coefficient * r**self.exponent

    def g(self, x):
        """Closed-form MDR profile g(x) (m)."""
        x = np.abs(np.asarray(x, dtype=float))
        if self.profile == "sphere":
            return x * x / self.radius
        if self.profile == "cone":
            return 0.5 * math.pi * x / math.tan(math.radians(self.half_angle_deg))
        if self.profile == "flat":
            return np.where(x <= self.radius, 0.0, np.inf)
        return _mdr.kappa(self.exponent) * self.coefficient * x**self.exponent


@renamed(modulus="E_star")  # old name kept (docs/conventions.md)
@dataclass(frozen=True)
class RoughParams:
    """A rigid rough surface on an elastic half-space, loaded by nominal pressures (SI units)."""

    E_star: float = param(
        1e11, unit="Pa", lo=0.0, lo_open=True, hi=1e13, doc="Effective modulus E*."
    )
    pixel_size: float = param(
        2e-6, unit="m", lo=0.0, lo_open=True, hi=1.0, doc="Grid spacing of the height map."
    )
    pressures: tuple[float, ...] = param(
        (1e5, 1e6, 1e7, 1e8), unit="Pa", lo=0.0, lo_open=True, doc="Nominal pressures."
    )
    periodic: bool = param(True, doc="BEM: periodic cell (True) or rigid square punch (False).")
    realizations: int = param(16, lo=1, hi=100_000, doc="MDR ensemble size.")
    rms_height: float = param(0.5e-6, unit="m", lo=0.0, lo_open=True, doc="Generated surfaces: Rq.")
    hurst: float = param(
        0.8, lo=0.0, hi=1.0, lo_open=True, doc="Generated surfaces: Hurst exponent."
    )
    rolloff_wavelength: float = param(
        100e-6, unit="m", lo=0.0, lo_open=True, doc="Generated surfaces: roll-off wavelength."
    )
    short_cutoff_wavelength: float = param(
        4e-6, unit="m", lo=0.0, lo_open=True, doc="Generated surfaces: short cut-off."
    )
    grid_points: int = param(256, lo=4, hi=1 << 14, doc="Generated surfaces: points per side.")
    surface_file: str = param(
        "",
        doc="Height map (.npy/.asc/.xyz or any SurfaceTopography "
            "format); empty = generate from the PSD.",
    )
    surface_unit: str = param(
        "",
        doc="Length unit of surface_file when it states "
            "none (or overriding it); empty = from the file.",
    )
    surface_pixel_size: float = param(
        0.0, unit="m", lo=0.0, doc="Pixel size overriding surface_file's; 0 = from the file."
    )
    surface_detrend: str = param(
        "none", choices=("none", "mean", "plane", "curvature"), doc="Detrending of surface_file."
    )
    surface_missing: str = param(
        "refuse", choices=("refuse", "fill"), doc="Missing points of surface_file: refuse or fill."
    )
    seed: int = param(20060327, lo=0, hi=2**63 - 1, doc="Seed of the surface and ensemble draws.")

    def __post_init__(self) -> None:
        validate_dataclass(self)
        if not self.pressures:
            raise ParameterError("pressures", "at least one pressure", "an empty list")
        for p in self.pressures:
            if p >= self.E_star:
                raise ParameterError(
                    "pressures", f"pressures below the modulus ({self.E_star:g} Pa)", p
                )


# ---------------------------------------------------------------- axisymmetric


def _radius_estimate(p: AxisymmetricParams, d: float) -> float:
    """Contact radius (m) the row must cover.

    The larger of the contact at d and twice that at d = 0 (JKR).
    """
    from scipy.optimize import brentq

    if p.profile == "flat":
        return p.radius
    w = p.work_of_adhesion

    def h(a, dd):
        return float(p.g(a)) - math.sqrt(2 * math.pi * a * w / p.E_star) - dd

    def root(dd):
        # bracket from below: with adhesion h(0) = -dd may vanish, the
        # physical root is the positive one
        lo, hi = 0.0, 1e-15
        while h(hi, dd) < 0:
            lo, hi = hi, 2.0 * hi
            if hi > 1e6:
                raise ParameterError("indentation", "a contact radius below 1e6 m", dd)
        return (
            brentq(lambda a: h(a, dd), lo, hi, xtol=1e-14 * hi) if lo > 0 or h(0.0, dd) < 0 else hi
        )

    a = root(max(d, 0.0))
    if w > 0:
        a = max(a, 2.0 * root(0.0))
    return a


def _row(p: AxisymmetricParams, a_est: float) -> tuple[np.ndarray, np.ndarray]:
    """Return the spring row covering 1.25 a_est.

    For a flat punch its edge lies halfway between two springs.
    """
    n = p.springs
    if p.profile == "flat":
        m = (n - 1) // 2
        k = max(1, int(round(m / 1.25 - 0.5)))
        x_max = m * p.radius / (k + 0.5)
        return _mdr.axisymmetric_profile("flat", 2 * m + 1, x_max, radius=p.radius)
    return _mdr.axisymmetric_profile(p.profile, n, 1.25 * a_est, **p.shape())


@REG.register("mdr")
def _solve_mdr(p: AxisymmetricParams) -> Result:
    out = Result(
        method="mdr",
        units={
            "force": "N",
            "contact_radius": "m",
            "indentation": "m",
            "pull_off_force": "N",
            "stiffness": "N/m",
        },
    )
    if p.indentation is None:
        d = _indentation_for_force(p)
    else:
        d = p.indentation
    if p.work_of_adhesion > 0:
        x, g = _row(p, _radius_estimate(p, d))
        model = _mdr.AxisymmetricMDR(x, g, p.E_star, p.work_of_adhesion)
        if p.profile == "flat":
            edge = math.sqrt(2 * math.pi * p.radius * p.work_of_adhesion / p.E_star)
            a, F = p.radius, 2 * p.E_star * p.radius * d
            po = po_d = -2 * p.E_star * p.radius * edge
        else:
            a, F = model.jkr_at_indentation(d)
            po = model.pull_off("force")["force"]
            po_d = model.pull_off("displacement")["force"]
        out.update(
            force=F, contact_radius=a, pull_off_force=po, pull_off_force_displacement_control=po_d
        )
    else:
        x, g = _row(p, _radius_estimate(p, d))
        out.update(
            force=_mdr.normal_force(x, g, d, p.E_star),
            contact_radius=_mdr.contact_radius(x, g, d),
            stiffness=_mdr.normal_stiffness(x, g, d, p.E_star),
        )
    out.update(indentation=d, springs=int(x.size), spacing=float(x[1] - x[0]))
    return out


def _indentation_for_force(p: AxisymmetricParams) -> float:
    """Indentation (m) at the prescribed force from the closed-form references (no adhesion)."""
    F = p.normal_force
    if p.work_of_adhesion > 0:
        raise MissingFeatureError("normal_force with adhesion: give the indentation instead")
    if p.profile == "sphere":
        return float(_ref.hertz_indentation(F, p.radius, p.E_star))
    if p.profile == "cone":
        return math.sqrt(F * math.pi / (2 * p.E_star * math.tan(math.radians(p.half_angle_deg))))
    if p.profile == "flat":
        return F / (2 * p.E_star * p.radius)
    n, k = p.exponent, _mdr.kappa(p.exponent) * p.coefficient
    # F = 2 E* d a n/(n+1) with a = (d/k)^(1/n)  ->  d^(1+1/n) = F (n+1) k^(1/n) / (2 E* n)
    return (F * (n + 1) * k ** (1 / n) / (2 * p.E_star * n)) ** (n / (n + 1))


@REG.register("bem")
def _solve_bem(p: AxisymmetricParams) -> Result:
    from .bem import solve_bem

    if p.work_of_adhesion > 0:
        raise MissingFeatureError(
            "work_of_adhesion with method 'bem': the BEM "
            "reference is non-adhesive; use --method mdr"
        )
    d = p.indentation if p.indentation is not None else _indentation_for_force(p)
    a = _radius_estimate(p, d)
    n = p.grid_points
    # The punch (non-periodic) grid spans 2.5 contact radii: the contact is well inside.
    L = 2.5 * a if p.profile != "flat" else 2.2 * p.radius
    dx = L / n
    c = (np.arange(n) - n // 2) * dx
    r = np.hypot(c[:, None], c[None, :])
    fr = p.f(r)
    heights = -np.where(np.isfinite(fr), fr, 10.0 * d + float(np.max(fr[np.isfinite(fr)])))
    nit = 0
    if p.normal_force is not None:
        res = solve_bem(
            heights, dx, p.E_star, p.normal_force / (L * L), periodic=False, stiffness=False
        )
        nit = res.nit
    else:
        # Displacement control by a secant search in log F - log d: the
        # continuum force is a power of d for these homogeneous profiles,
        # so two to four warm-started load-controlled solves suffice.
        expo = {"sphere": 1.5, "cone": 2.0, "flat": 1.0}.get(
            p.profile, (p.exponent + 1) / p.exponent
        )
        logF = math.log(float(_mdr.normal_force(*_row(p, a), d, p.E_star)))
        prev = None
        p0 = None
        for _ in range(12):
            res = solve_bem(
                heights,
                dx,
                p.E_star,
                math.exp(logF) / (L * L),
                periodic=False,
                stiffness=False,
                tol=1e-12,
                p0=p0,
            )
            p0, nit = res.p, nit + res.nit
            logd = math.log(res.approach)
            if abs(logd - math.log(d)) < 1e-10:
                break
            slope = expo if prev is None or prev[1] == logd else (logF - prev[0]) / (logd - prev[1])
            prev = (logF, logd)
            logF += slope * (math.log(d) - logd)
    radius = math.sqrt(res.contact_area / math.pi)
    out = Result(
        method="bem",
        force=res.force,
        indentation=res.approach,
        contact_radius=radius,
        area_fraction=res.area_fraction,
        grid=n,
        pixel_size=dx,
        nit=nit,
        units={"force": "N", "contact_radius": "m", "indentation": "m", "pixel_size": "m"},
    )
    return out


def solve(params: AxisymmetricParams, *, method: str = "mdr", rng=None) -> Result:
    """Solve an axisymmetric contact by ``method`` (``"mdr"`` or ``"bem"``).

    Returns
    -------
    Result
        ``force`` (N), ``contact_radius`` (m; BEM: ``sqrt(area/pi)``),
        ``indentation`` (m), ``time_s``; with adhesion also
        ``pull_off_force`` (force control, N) and
        ``pull_off_force_displacement_control`` (N).
    """
    impl = REG.get(method)
    import scipy.interpolate  # noqa: F401  (lazy imports are not part of the timed solve)
    import scipy.optimize  # noqa: F401

    t0 = time.perf_counter()
    res = impl(params)
    res["time_s"] = time.perf_counter() - t0
    res.setdefault("params", params)
    res["warnings"] = _validity_warnings(params, res)
    return res


#: Above this a/R the paraboloid f = r^2/2R (Hertz, and the MDR sphere) departs from the real
#: sphere by more than a few per cent in force; beyond a/R = 1 a sphere cannot make the contact.
SPHERE_DOUBTFUL_A_OVER_R = 0.3


def _validity_warnings(p: AxisymmetricParams, res: Result) -> list[str]:
    """Refuse a contact the profile cannot make; list the doubtful ones (empty when fine)."""
    if p.profile != "sphere":
        return []
    a = float(res.get("contact_radius", 0.0))
    ratio = a / p.radius
    where = "indentation" if p.indentation is not None else "normal_force"
    if not math.isfinite(ratio) or ratio > 1.0:
        raise ParameterError(
            where,
            f"a load whose contact radius stays below the sphere radius {p.radius:.3g} m",
            f"contact radius {a:.3g} m = {ratio:.3g} R",
        )
    if ratio > SPHERE_DOUBTFUL_A_OVER_R:
        return [
            f"contact radius {a:.3g} m is {ratio:.2f} of the "
            "sphere radius: the paraboloid (small-strain) "
            f"approximation is doubtful above a/R = {SPHERE_DOUBTFUL_A_OVER_R}"
        ]
    return []


# ------------------------------------------------------------------- rough


def load_surface(
    path: str | Path,
    pixel_size: float | None = None,
    *,
    unit: str | None = None,
    detrend: str = "none",
    missing: str = "refuse",
) -> tuple[np.ndarray, float | None]:
    """Read a height map (m).

    Formats: tribolmp ``.npy`` (+ sidecar JSON), ``.asc``/``.xyz``, or any instrument file.

    Instrument files (x3p, sur, opd, datx, gwy, MetroPro, plu, nc, ...) go
    through SurfaceTopography (:func:`tribolmp.models.topography.measured.read_surface`):
    units and pixel size come from the file's metadata; ``pixel_size`` and
    ``unit`` override them only when given.  A bare ``.npy`` without sidecar
    returns ``pixel_size=None`` so that the caller supplies it.  Raises
    :class:`SurfaceFileError` (one line) for unreadable files and
    :class:`ParameterError` for bad arrays.
    """
    from ..topography.measured import read_surface
    from .rough import check_heightmap

    path = Path(path)
    if (
        path.suffix.lower() == ".npy"
        and pixel_size is None
        and not path.with_suffix(".json").exists()
    ):
        from ..topography.io import read_native

        h, _, _, _ = read_native(
            path, pixel_size=1.0
        )  # provisional spacing: the caller supplies the real one
        return check_heightmap(h), None
    surf = read_surface(path, pixel_size=pixel_size, unit=unit, detrend=detrend, missing=missing)
    return check_heightmap(surf.h), surf.pixel_size


@ROUGH_REG.register("mdr")
def _rough_mdr(h, dx, E, pressures, periodic, realizations, rng) -> Result:
    from .rough import mdr_profiles_from_heightmap, stiffness_vs_load

    t0 = time.perf_counter()
    x, g = mdr_profiles_from_heightmap(h, dx, realizations, rng)
    res = stiffness_vs_load(x, g, E, pressures, nominal_area=h.shape[0] * h.shape[1] * dx * dx)
    T = time.perf_counter() - t0
    rows = []
    for j, p in enumerate(res.pressure):
        rows.append(
            dict(
                pressure=float(p),
                force=float(res.force[j]),
                stiffness=float(res.stiffness[j]),
                stiffness_q10=float(res.stiffness_q10[j]),
                stiffness_q90=float(res.stiffness_q90[j]),
                approach=float(res.approach[j]),
                approach_q10=float(res.approach_q10[j]),
                approach_q90=float(res.approach_q90[j]),
                closed_fraction=float(res.closed_fraction[j]),
                warnings=[w for w in res.warnings if f" at {float(p):g} Pa " in w],
                time_s=T / len(res.pressure),
            )
        )
    res["rows"] = rows
    res["time_s"] = T
    return res


@ROUGH_REG.register("bem")
def _rough_bem(h, dx, E, pressures, periodic, realizations, rng) -> Result:
    from .bem import solve_bem

    if h.shape[0] != h.shape[1]:
        raise ParameterError("surface", "a square height map for method 'bem'", f"shape {h.shape}")
    t0 = time.perf_counter()
    rows, p0, nit = [], None, 0
    # Ascending pressures reuse the previous pressure field as a warm start.
    order = np.argsort(pressures)
    out = [None] * len(pressures)
    for j in order:
        r = solve_bem(h, dx, E, float(pressures[j]), periodic=periodic, p0=p0)
        p0 = r.p
        nit += r.nit + r.nit_stiffness
        out[j] = dict(
            pressure=float(pressures[j]),
            force=float(r.force),
            stiffness=float(r.stiffness),
            approach=float(r.approach),
            mean_gap=float(r.mean_gap),
            area_fraction=float(r.area_fraction),
            nit=int(r.nit),
            time_s=float(r.time_s),
        )
    rows = out
    return Result(
        rows=rows,
        pressure=np.array([r["pressure"] for r in rows]),
        force=np.array([r["force"] for r in rows]),
        stiffness=np.array([r["stiffness"] for r in rows]),
        approach=np.array([r["approach"] for r in rows]),
        area_fraction=np.array([r["area_fraction"] for r in rows]),
        periodic=bool(periodic),
        method="bem",
        warnings=[],
        nit=nit,
        time_s=time.perf_counter() - t0,
        units={
            "pressure": "Pa",
            "force": "N",
            "stiffness": "N/m",
            "approach": "m",
            "mean_gap": "m",
            "area_fraction": "1",
        },
    )


def solve_rough(
    heights,
    pixel_size: float,
    E_star: float,
    pressures,
    *,
    method: str = "mdr",
    periodic: bool = True,
    realizations: int = 16,
    rng: np.random.Generator | None = None,
) -> Result:
    """Stiffness (N/m), force (N) and approach (m) of a rough surface against nominal pressure.

    Parameters
    ----------
    heights : ndarray, shape (n, n)
        Rigid surface heights (m).
    pixel_size : float
        Grid spacing (m).
    E_star : float
        Effective modulus (Pa).
    pressures : sequence of float
        Nominal pressures (Pa), each below ``E_star``.
    method : {"mdr", "bem"}
        MDR ensemble of 1D profiles or the 3D BEM reference.
    periodic : bool
        BEM only: periodic cell, or rigid rough square punch of side ``n dx``.
    realizations : int
        MDR ensemble size.
    rng : numpy.random.Generator
        Randomness of the MDR ensemble (required for ``"mdr"``).

    Returns
    -------
    Result
        ``rows``: one dict per pressure with ``pressure``, ``force``,
        ``stiffness``, ``approach``, ``time_s``; MDR rows add
        ``stiffness_q10``/``stiffness_q90``, ``closed_fraction`` (fraction
        of the MDR lines fully in contact) and ``warnings`` (one line each
        when ``closed_fraction`` > 10 %: the stiffness is then the punch limit
        ``E* L``); BEM rows add ``area_fraction``.  The same quantities as
        arrays, the result's ``warnings`` list, and ``time_s`` in total.
    """
    from ..base import check_int, check_positive
    from .rough import check_heightmap

    impl = ROUGH_REG.get(method)
    h = check_heightmap(heights)
    dx = check_positive("pixel_size", pixel_size, "m")
    E = check_positive("modulus", E_star, "Pa")
    P = [check_positive("pressure", p, "Pa") for p in pressures]
    if not P:
        raise ParameterError("pressures", "at least one pressure", "an empty list")
    for p in P:
        if p >= E:
            raise ParameterError("pressures", f"pressures below the modulus ({E:g} Pa)", p)
    check_int("realizations", realizations, 1)
    if method == "mdr" and rng is None:
        raise ParameterError("rng", "a numpy.random.Generator for the MDR ensemble", None)
    _check_plausible_surface(h, dx)
    t0 = time.perf_counter()
    res = impl(h, dx, E, P, periodic, realizations, rng)
    res["time_s"] = time.perf_counter() - t0
    _check_finite_stiffness(res, method)
    return res


#: Heights beyond a metre are a unit mistake (a surface's roughness is nm to mm).
MAX_PLAUSIBLE_HEIGHT_M = 1.0
#: The half-space contact models assume small slopes; an rms gradient above this is no surface.
MAX_PLAUSIBLE_RMS_GRADIENT = 10.0


def _check_plausible_surface(h: np.ndarray, dx: float) -> None:
    """Refuse heights no half-space contact model can treat.

    They are refused before they overflow into a zero stiffness.
    """
    top = float(np.max(np.abs(h - h.mean())))
    if not top <= MAX_PLAUSIBLE_HEIGHT_M:
        raise ParameterError(
            "surface",
            f"height deviations <= {MAX_PLAUSIBLE_HEIGHT_M:g} m (wrong unit?)",
            f"max |h - <h>| = {top:.3g} m",
        )
    gx = np.diff(h, axis=0, append=h[:1]) / dx
    gy = np.diff(h, axis=1, append=h[:, :1]) / dx
    grad = float(np.sqrt(np.mean(gx**2 + gy**2)))
    if not grad <= MAX_PLAUSIBLE_RMS_GRADIENT:
        raise ParameterError(
            "surface",
            f"an rms gradient <= {MAX_PLAUSIBLE_RMS_GRADIENT:g} (small-slope half-space "
            "contact; wrong height unit or pixel size?)",
            f"{grad:.3g}",
        )


def _check_finite_stiffness(res: Result, method: str) -> None:
    """Refuse a rough-contact result with non-finite or zero stiffness where the surfaces touch."""
    for row in res.get("rows", []):
        k, f = row.get("stiffness"), row.get("force")
        if f is not None and f > 0 and not (k is not None and math.isfinite(k) and k > 0):
            if k is not None and math.isinf(k) and method == "bem":
                # a closed periodic cell: infinite interfacial stiffness is the exact answer
                continue
            raise BlowUpError(
                f"rough contact ({method}): stiffness {k!r} N/m at {row.get('pressure'):g} Pa "
                "is not a finite positive number"
            )


def rough_params_from_scene(scene) -> RoughParams:
    """:class:`RoughParams` from ``[roughness]``, ``[load].pressures`` and ``[contact]``."""
    rough = scene.roughness
    if rough is None:
        raise ParameterError("[roughness]", "a [roughness] section for a rough contact", "nothing")
    contact = getattr(scene, "contact", None)
    kw = dict(
        E_star=scene.effective_modulus,
        pixel_size=rough.pixel_size,
        pressures=tuple(scene.load.pressures),
        realizations=rough.realizations,
        rms_height=rough.rms_height,
        hurst=rough.hurst,
        rolloff_wavelength=rough.rolloff_wavelength,
        short_cutoff_wavelength=rough.short_cutoff_wavelength,
        grid_points=rough.grid_points,
        surface_file=rough.surface_file,
        surface_unit=getattr(rough, "surface_unit", ""),
        surface_pixel_size=getattr(rough, "surface_pixel_size", 0.0),
        surface_detrend=getattr(rough, "surface_detrend", "none"),
        surface_missing=getattr(rough, "surface_missing", "refuse"),
        seed=scene.scene.seed,
    )
    if contact is not None:
        kw["periodic"] = contact.periodic
    return RoughParams(**kw)


def params_from_scene(scene):
    """Contact parameters of a scene.

    ``[geometry].profile == "rough"`` gives :class:`RoughParams`; a sphere,
    cone or flat punch gives :class:`AxisymmetricParams` loaded by
    ``[load].normal_force``.
    """
    geo = scene.geometry
    if geo.profile == "rough":
        return rough_params_from_scene(scene)
    springs = getattr(getattr(scene, "contact", None), "springs", 2001)
    if not scene.load.normal_force > 0:
        raise ParameterError(
            "[load].normal_force",
            f"a force > 0 N for a {geo.profile} contact",
            scene.load.normal_force,
        )
    return AxisymmetricParams(
        profile=geo.profile,
        E_star=scene.effective_modulus,
        radius=geo.radius,
        half_angle_deg=geo.half_angle_deg,
        normal_force=scene.load.normal_force,
        springs=max(9, int(springs)),
    )


def rough_surface(params: RoughParams, rng: np.random.Generator) -> tuple[np.ndarray, float]:
    """Return the height map (m) and pixel size (m).

    Read from ``surface_file`` or generated from the PSD.
    """
    from .rough import generate_surface, self_affine_psd

    if params.surface_file:
        h, dx = load_surface(
            params.surface_file,
            params.surface_pixel_size or None,
            unit=params.surface_unit or None,
            detrend=params.surface_detrend,
            missing=params.surface_missing,
        )
        return h, params.pixel_size if dx is None else dx
    psd = self_affine_psd(
        params.rms_height, params.hurst, params.rolloff_wavelength, params.short_cutoff_wavelength
    )
    return generate_surface(params.grid_points, params.pixel_size, psd, rng), params.pixel_size


def stiffness_vs_pressure(
    scene_or_params,
    *,
    method: str | None = None,
    rng: np.random.Generator | None = None,
    tolerance: float | None = None,
) -> Result:
    """Rough-surface stiffness, force and approach at the scene's ``[load].pressures``.

    Parameters
    ----------
    scene_or_params : Scene or RoughParams
        The scene (``[roughness]``, ``[load]``, ``[contact]``) or ready parameters.
    method : {"mdr", "bem", "auto"}, optional
        Default: ``[contact].method`` (``"mdr"`` for bare parameters).
        ``"auto"`` picks by :func:`~.choice.choose_method` from the measured
        rough-surface speed-error table at the scene's reduced pressures
        ``p / (E* h'_rms)`` and ``tolerance``; if the MDR it picked closes more
        than 10 % of its lines at some pressure, the periodic BEM is run instead
        (stated in ``warnings``).
    rng : numpy.random.Generator, optional
        Default: a generator seeded by the scene seed.  The surface (when
        generated) and the MDR ensemble are drawn from independent children.
    tolerance : float, optional
        ``"auto"`` only: acceptable relative stiffness error (default
        ``[contact].tolerance``, else 0.3).

    Returns
    -------
    Result
        As :func:`solve_rough`, plus ``pixel_size`` (m), ``grid`` (points per
        side) and, for ``"auto"``, ``choice`` (the decision and its reason).
    """
    from ...rng import as_generator, spawn

    if isinstance(scene_or_params, RoughParams):
        params, default_method, contact = scene_or_params, "mdr", None
    else:
        params = rough_params_from_scene(scene_or_params)
        contact = getattr(scene_or_params, "contact", None)
        default_method = getattr(contact, "method", "mdr") if contact is not None else "mdr"
    method = method or default_method
    rng = as_generator(params.seed if rng is None else rng)
    surf_rng, ens_rng = spawn(rng, 2)
    h, dx = rough_surface(params, surf_rng)
    choice = None
    periodic = params.periodic
    if method == "auto":
        from .choice import choose_method, reduced_pressures
        from .rough import rms_gradient

        tol = tolerance if tolerance is not None else float(getattr(contact, "tolerance", 0.3))
        choice = choose_method(
            tol,
            reduced_pressures=reduced_pressures(
                params.pressures, params.E_star, rms_gradient(h, dx)
            ),
        )
        method = choice["method"]
        if method == "bem":
            periodic = True  # the table's BEM errors are those of the periodic cell
    res = solve_rough(
        h,
        dx,
        params.E_star,
        params.pressures,
        method=method,
        periodic=periodic,
        realizations=params.realizations,
        rng=ens_rng,
    )
    if choice is not None and method == "mdr" and res.warnings:
        from .rough import CLOSED_FRACTION_LIMIT

        warnings = list(res.warnings)
        res = solve_rough(h, dx, params.E_star, params.pressures, method="bem", periodic=True)
        res["warnings"] = warnings + [
            f"auto: MDR closed more than {CLOSED_FRACTION_LIMIT:.0%} "
            "of its lines; the periodic BEM was run instead"
        ]
        choice = dict(
            choice,
            method="bem",
            why=choice["why"] + "; MDR lines closed at run time -> periodic BEM",
        )
    if choice is not None:
        res["choice"] = choice
    res["pixel_size"] = dx
    res["grid"] = int(h.shape[0])
    return res
