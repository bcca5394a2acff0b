"""Inverse problem: the characteristic length of friction from measured F(amplitude).

Both models are linear in their amplitude ``A`` and background ``B`` once the
length ``L`` is fixed: ``y = A shape(a / L) + B``.  The fit therefore
minimises the residual sum of squares ``RSS(L)`` over ``L`` alone (variable
projection, with non-negative ``A, B``), and the uncertainty of ``L`` is read
from the *profile* of ``RSS(L)`` rather than from a linearised covariance: a
short or noisy data set gives a flat profile and hence a wide (or unbounded)
interval instead of a confident wrong value.

Fitted quantity: ``force_sq_N2`` data are fitted as ``F^2`` (as in Fig. 8),
``force_N`` data as ``F``; the two models are compared in the same space by
AIC (equal numbers of parameters, so this is the residual comparison).
"""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ...errors import DataFileError, ParameterError
from ...rng import as_generator
from ..base import MethodRegistry, Result, timed
from .models import CONVENTION_TEXT, pinning_shape_fast, to_per_contact

__all__ = ["MeasuredCurve", "read_curve_csv", "write_curve_csv", "fit_length", "SHAPES", "FIT_MODELS"]

#: model name -> shape(s, quantity) with quantity "force" or "force_sq".
SHAPES = MethodRegistry("tribospectroscopy model")


@SHAPES.register("potential")
def _potential_shape(s: np.ndarray, quantity: str) -> np.ndarray:
    g = pinning_shape_fast(s)
    return g if quantity == "force_sq" else np.sqrt(g)


@SHAPES.register("stiffness")
def _stiffness_shape(s: np.ndarray, quantity: str) -> np.ndarray:
    f = np.maximum(0.0, 1.0 - s)
    return f * f if quantity == "force_sq" else f


FIT_MODELS = ("stiffness", "potential", "auto")


@dataclass(frozen=True)
class MeasuredCurve:
    """Friction force against amplitude, amplitudes already per contact.

    Attributes
    ----------
    amplitude : ndarray
        Per-contact amplitudes ``a`` (m).
    value : ndarray
        ``F`` (N) or ``F^2`` (N^2), see ``quantity``.
    quantity : str
        ``"force"`` or ``"force_sq"``.
    convention : str
        Convention of the amplitudes in the source file.
    source : str
        File name (for messages).
    """

    amplitude: np.ndarray
    value: np.ndarray
    quantity: str
    convention: str = "per-contact"
    source: str = "<data>"


def read_curve_csv(path: str | Path, convention: str = "per-contact") -> MeasuredCurve:
    """Read a CSV with ``amplitude_m`` and ``force_N`` or ``force_sq_N2`` columns.

    Parameters
    ----------
    path : str or Path
        The CSV file (header row required; extra columns are ignored).
    convention : {"per-contact", "probe"}
        Convention of ``amplitude_m``; amplitudes are converted to per contact.

    Raises
    ------
    DataFileError
        Missing file or columns, non-numeric or non-finite cells, negative
        amplitudes or forces, fewer than 3 rows or fewer than 2 distinct amplitudes.
    """
    name = str(path)
    try:
        text = Path(path).read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise DataFileError(f"{name}: expected a readable UTF-8 CSV file, got {getattr(exc, 'strerror', None) or exc}") from None
    rows = list(csv.reader(line for line in text.splitlines() if line.strip() and not line.lstrip().startswith("#")))
    if not rows:
        raise DataFileError(f"{name}: expected a header with amplitude_m and force_N or force_sq_N2, got an empty file")
    header = [h.strip() for h in rows[0]]
    if "amplitude_m" not in header:
        raise DataFileError(f"{name}: column amplitude_m: expected in the header, got columns {header}")
    if "force_sq_N2" in header:
        col, quantity = "force_sq_N2", "force_sq"
    elif "force_N" in header:
        col, quantity = "force_N", "force"
    else:
        raise DataFileError(f"{name}: column force_N or force_sq_N2: expected in the header, got columns {header}")
    ia, iv = header.index("amplitude_m"), header.index(col)
    amp, val = [], []
    for lineno, row in enumerate(rows[1:], start=2):
        for idx, cname, out in ((ia, "amplitude_m", amp), (iv, col, val)):
            cell = row[idx].strip() if idx < len(row) else ""
            try:
                x = float(cell)
            except ValueError:
                raise DataFileError(f"{name}: line {lineno}: {cname}: expected a finite number, got {cell!r}") from None
            if not math.isfinite(x):
                raise DataFileError(f"{name}: line {lineno}: {cname}: expected a finite number, got {cell!r}")
            if x < 0:
                raise DataFileError(f"{name}: line {lineno}: {cname}: expected a value >= 0, got {cell!r}")
            out.append(x)
    if len(amp) < 3 or len(set(amp)) < 2:
        raise DataFileError(f"{name}: expected at least 3 data rows with 2 distinct amplitudes, got {len(amp)} rows")
    a = to_per_contact(np.array(amp), convention)
    return MeasuredCurve(a, np.array(val), quantity, convention, name)


def write_curve_csv(path: str | Path, amplitude, force) -> Path:
    """Write ``amplitude_m,force_N,force_sq_N2`` rows (the format :func:`read_curve_csv` reads)."""
    path = Path(path)
    f = np.asarray(force, dtype=float)
    with path.open("w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["amplitude_m", "force_N", "force_sq_N2"])
        for a, fi in zip(np.asarray(amplitude, dtype=float), f):
            w.writerow([repr(float(a)), repr(float(fi)), repr(float(fi * fi))])
    return path


def _project_many(a, y, lengths, shape, quantity: str, background: bool, w=None):
    """Best non-negative (A, B) for each fixed L (closed-form 2x2 least squares).

    Returns arrays (weighted rss, A, B) over ``lengths``.  With the
    non-negativity constraints the optimum is either the unconstrained one or
    lies on an edge (A = 0 or B = 0), each again a 1-parameter closed form.
    """
    w = np.ones_like(y) if w is None else w
    L = np.atleast_1d(np.asarray(lengths, dtype=float))
    f = shape(a[None, :] / L[:, None], quantity) * w  # (nL, n)
    yw, one = y * w, w
    sff, sfy = np.einsum("ij,ij->i", f, f), f @ yw
    syy = float(yw @ yw)
    tiny = 1e-300
    # A only (B = 0)
    A1 = np.maximum(sfy, 0.0) / np.maximum(sff, tiny)
    best_rss = syy - 2 * A1 * sfy + A1 * A1 * sff
    best_A, best_B = A1, np.zeros_like(A1)
    if background:
        s11, s1y, sf1 = float(one @ one), float(one @ yw), f @ one
        B2 = max(s1y, 0.0) / s11  # B only (A = 0)
        rss2 = syy - 2 * B2 * s1y + B2 * B2 * s11
        det = sff * s11 - sf1 * sf1
        ok = det > 1e-12 * sff * s11
        with np.errstate(divide="ignore", invalid="ignore"):
            A3 = np.where(ok, (sfy * s11 - sf1 * s1y) / det, -1.0)
            B3 = np.where(ok, (sff * s1y - sf1 * sfy) / det, -1.0)
        rss3 = syy - 2 * (A3 * sfy + B3 * s1y) + A3 * A3 * sff + 2 * A3 * B3 * sf1 + B3 * B3 * s11
        feas3 = ok & (A3 >= 0) & (B3 >= 0)
        use2 = rss2 < best_rss
        best_rss = np.where(use2, rss2, best_rss)
        best_A = np.where(use2, 0.0, best_A)
        best_B = np.where(use2, B2, best_B)
        use3 = feas3 & (rss3 < best_rss)
        best_rss = np.where(use3, rss3, best_rss)
        best_A = np.where(use3, A3, best_A)
        best_B = np.where(use3, B3, best_B)
    return np.maximum(best_rss, 0.0), best_A, best_B


def _project(a, y, length: float, shape, quantity: str, background: bool, w=None):
    """Scalar version of :func:`_project_many`: (rss, A, B) at one L."""
    r, A, B = _project_many(a, y, [length], shape, quantity, background, w)
    return float(r[0]), float(A[0]), float(B[0])


def _crossing(fun, lo: float, hi: float) -> float:
    """Where the RSS profile crosses the threshold between two grid points (bisection in ln L)."""
    from scipy.optimize import brentq

    flo, fhi = fun(lo), fun(hi)
    if flo * fhi > 0:  # no sign change inside (the optimum sits at the threshold)
        return lo if abs(flo) < abs(fhi) else hi
    return math.exp(brentq(lambda t: fun(math.exp(t)), math.log(lo), math.log(hi), xtol=1e-12, rtol=1e-10))


def _best_length(a, y, quantity, shape, background, grid, w):
    """Global grid scan of the RSS profile, then a bounded refinement; returns (L, rss_grid, i)."""
    from scipy.optimize import minimize_scalar

    rss = _project_many(a, y, grid, shape, quantity, background, w)[0]
    i = int(np.argmin(rss))
    n_grid = grid.size
    lb, ub = np.log(grid[max(i - 1, 0)]), np.log(grid[min(i + 1, n_grid - 1)])
    best = minimize_scalar(
        lambda t: _project(a, y, math.exp(t), shape, quantity, background, w)[0],
        bounds=(lb, ub), method="bounded", options={"xatol": 1e-10},
    )
    length = math.exp(best.x)
    if rss[i] < _project(a, y, length, shape, quantity, background, w)[0]:
        length = grid[i]  # flat profile: the grid point was better
    return length, rss, i


def _fit_one(curve: MeasuredCurve, model: str, background: bool, n_grid: int, n_boot: int, rng, weighting: str) -> dict:
    from scipy.special import fdtri

    shape = SHAPES.get(model, "model")
    a, y = curve.amplitude, curve.value
    # relative weighting: residuals in units of the measured value (multiplicative noise)
    w = 1.0 / np.maximum(np.abs(y), 1e-3 * np.abs(y).max() + 1e-300) if weighting == "relative" else None
    apos = a[a > 0]
    lo, hi = apos.min() / 100.0, a.max() * 100.0
    grid = np.geomspace(lo, hi, n_grid)
    length, rss, i = _best_length(a, y, curve.quantity, shape, background, grid, w)
    rss_min, amp, bg = _project(a, y, length, shape, curve.quantity, background, w)
    n, p = a.size, 3 if background else 2
    dof = n - p
    if dof > 0:
        # 68 % profile-likelihood interval with the noise estimated from the
        # residuals: F-test threshold (exact for linear models, honest for small n).
        thresh = rss_min * (1.0 + fdtri(1, dof, 0.6827) / dof)
        prof = lambda L: _project(a, y, L, shape, curve.quantity, background, w)[0] - thresh  # noqa: E731
        # The confidence set {L : RSS(L) <= thresh} can be disconnected (the
        # pinning profile has side minima); report its hull, not the branch
        # around the optimum, so that a second branch widens the interval.
        inside = np.nonzero(rss <= thresh)[0]
        k0 = int(inside.min()) if inside.size and grid[inside.min()] < length else None
        k1 = int(inside.max()) if inside.size and grid[inside.max()] > length else None
        lo_in = grid[k0] if k0 is not None else length
        hi_in = grid[k1] if k1 is not None else length
        j0 = (k0 - 1 if k0 >= 1 else None) if k0 is not None else int(np.searchsorted(grid, length)) - 1
        j1 = (k1 + 1 if k1 + 1 < n_grid else None) if k1 is not None else int(np.searchsorted(grid, length, side="right"))
        if j0 is not None and j0 < 0:
            j0 = None
        if j1 is not None and j1 >= n_grid:
            j1 = None
        lo_L = _crossing(prof, grid[j0], lo_in) if j0 is not None else grid[0]
        hi_L = _crossing(prof, hi_in, grid[j1]) if j1 is not None else grid[-1]
        bounded = j0 is not None and j1 is not None
        if n_boot > 0 and rss_min > 0:
            # Wild bootstrap (Rademacher signs on the residuals) keeps
            # heteroscedastic noise, which the profile's single sigma does not.
            fitted = amp * shape(a / length, curve.quantity) + bg
            resid = y - fitted
            coarse = np.geomspace(lo, hi, 61)
            boots = np.array([
                _best_length(a, fitted + resid * rng.choice((-1.0, 1.0), a.size), curve.quantity, shape, background, coarse, w)[0]
                for _ in range(n_boot)
            ])
            b_lo, b_hi = np.percentile(boots, [15.87, 84.13])
            lo_L, hi_L = min(lo_L, b_lo), max(hi_L, b_hi)
            bounded = bounded and b_lo > coarse[1] and b_hi < coarse[-2]
        std = 0.5 * (hi_L - lo_L)
    else:
        lo_L, hi_L, bounded, std = grid[0], grid[-1], False, 0.5 * (grid[-1] - grid[0])
    aic = n * math.log(max(rss_min / n, 1e-300)) + 2 * p
    return dict(
        model=model,
        length_m=length,
        length_std_m=float(std),
        length_interval_m=[float(lo_L), float(hi_L)],
        bounded=bool(bounded),
        amplitude=float(amp),
        background=float(bg),
        rss=float(rss_min),
        residual=math.sqrt(rss_min / n),
        aic=aic,
        n_params=p,
    )


def fit_length(
    curve: MeasuredCurve,
    model: str = "auto",
    *,
    background: bool = True,
    n_grid: int = 241,
    n_boot: int = 40,
    weighting: str = "none",
    rng: np.random.Generator | int | None = 0,
) -> Result:
    """Fit the characteristic length of friction to a measured curve.

    Parameters
    ----------
    curve : MeasuredCurve
        Data with per-contact amplitudes (see :func:`read_curve_csv`).
    model : {"stiffness", "potential", "auto"}
        ``auto`` fits both and keeps the one with the lower AIC.
    background : bool
        Fit an amplitude-independent background ``B >= 0`` as well.
    n_grid : int
        Points of the log-spaced profile scan of ``L`` over
        ``[min a / 100, 100 max a]``.
    n_boot : int
        Wild-bootstrap refits; the reported interval is the hull of the
        profile interval and the bootstrap 16-84 % range (0 = profile only).
    weighting : {"none", "relative"}
        ``relative`` divides residuals by the measured value (use it for
        noise proportional to the signal); ``residual`` is then relative too.
    rng : Generator or int
        Random source of the bootstrap (explicit, reproducible).

    Returns
    -------
    Result
        ``length_m`` (per-contact length: ``lambda`` of the pinning model or
        ``mu N / k`` of the stiffness model), ``length_std_m`` (half-width of
        the 68 % profile interval; huge and ``bounded = False`` when the data
        cannot pin it down), ``model``, ``residual`` (rms, in N or N^2),
        ``aic``, ``force0_N``, ``background``, ``candidates`` (every model fitted).
    """
    if model not in FIT_MODELS:
        raise ParameterError("model", f"one of {list(FIT_MODELS)}", model)
    if weighting not in ("none", "relative"):
        raise ParameterError("weighting", "one of ['none', 'relative']", weighting)
    res = Result(method="variable-projection profile fit")
    with timed(res):
        names = ["stiffness", "potential"] if model == "auto" else [model]
        gen = as_generator(rng)
        cands = {m: _fit_one(curve, m, background, n_grid, n_boot, gen, weighting) for m in names}
        best = min(cands.values(), key=lambda c: c["aic"])
    q = curve.quantity
    force0 = math.sqrt(best["amplitude"]) if q == "force_sq" else best["amplitude"]
    res.update(
        length_m=best["length_m"],
        length_std_m=best["length_std_m"],
        length_interval_m=best["length_interval_m"],
        bounded=best["bounded"],
        model=best["model"],
        residual=best["residual"],
        aic=best["aic"],
        force0_N=force0,
        background=best["background"],
        fitted_quantity="force_sq_N2" if q == "force_sq" else "force_N",
        convention=curve.convention,
        amplitude_convention=CONVENTION_TEXT[curve.convention] + "; length_m is per contact",
        n_points=int(curve.amplitude.size),
        candidates={m: {k: v for k, v in c.items() if k != "model"} for m, c in cands.items()},
        message=(f"{best['model']}: L = {best['length_m']:.4g} m +- {best['length_std_m']:.2g} m"
                 + ("" if best["bounded"] else " (not identifiable from these data)")),
        weighting=weighting,
        units={"length_m": "m", "length_std_m": "m",
               "residual": "1" if weighting == "relative" else ("N^2" if q == "force_sq" else "N"),
               "force0_N": "N", "background": "N^2" if q == "force_sq" else "N"},
    )
    aics = sorted(c["aic"] for c in cands.values())
    res.delta_aic = aics[1] - aics[0] if len(aics) > 1 else None
    res.model_ambiguous = bool(res.delta_aic is not None and res.delta_aic < 2.0)
    if res.model_ambiguous:
        res.message += f"; models not distinguishable (delta AIC = {res.delta_aic:.2f} < 2)"
    if not best["bounded"] or res.model_ambiguous:
        res.status = 1
    return res


def model_curve(model: str, amplitude, length: float, amplitude_coef: float, background: float, quantity: str) -> np.ndarray:
    """Evaluate a fitted curve ``A shape(a/L) + B`` (for plots)."""
    return amplitude_coef * SHAPES.get(model, "model")(np.asarray(amplitude, float) / length, quantity) + background
