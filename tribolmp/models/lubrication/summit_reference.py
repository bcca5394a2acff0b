"""Resolved Reynolds reference for the near-contact summits of a rough squeeze film (SI).

The mixed-lubrication model (:func:`~.dynamics.mixed_approach`) adds to the
nominal film of the apparent area one resistance per summit for the
near-contact singularity of the film.  This module provides the independent
reference it is checked against:

* :func:`summit_gap` -- a nominally flat gap of clearance ``H`` with
  paraboloidal summit caps ``h = min(H, h_j + |x - x_j|^2 / 2 R_j)``
  (summit ``j`` of radius ``R_j`` with its top at gap ``h_j``);
* :func:`graded_axis` -- cell edges along one axis, refined around the
  summits so that the inner squeeze region ``r_c = sqrt(2 R_j h_j)`` of each
  summit is resolved by many cells however small ``h_j`` is;
* :func:`tensor_reynolds_squeeze` -- the finite-volume solution of the
  local squeeze Reynolds equation ``-div(h^3/(12 eta) grad p) = V`` on such a
  tensor-product (non-uniform) grid, ``p = 0`` on the rim of the square;
* :func:`summit_reference` -- the two combined, with a grid-refinement
  (Richardson) estimate of the discretisation error;
* :func:`cap_on_disc_resistance` -- the closed form for one cap at the
  centre of a disc (axisymmetric, the radial flux is exactly V r / 2):
  ``c = 6 pi eta R^2 (1/h - 2/H + h/H^2) + (3 pi/2) eta (r_o^4 - a^4)/H^3``
  with ``a^2 = 2 R (H - h)``.

The reference knows nothing of the dampers: it discretises the Reynolds
equation on the resolved gap.  With the default ``refine = 2`` the finest
cell is ``r_c/24``; the grid error is stated by :func:`summit_reference`.
"""

from __future__ import annotations

import math

import numpy as np

from ...errors import ParameterError
from ..base import Result, timed

__all__ = [
    "summit_gap",
    "graded_axis",
    "tensor_reynolds_squeeze",
    "summit_reference",
    "cap_on_disc_resistance",
    "fourier_gap",
]


def fourier_gap(coefficients, length: float, separation: float):
    """Gap ``u - z(x, y)`` of a flat above a band-limited periodic surface, at any points.

    ``z = Re sum B[k, l] exp(2 pi i (k x + l y) / L)`` with the coefficients of
    :func:`tribolmp.models.contact.rough.fourier_coefficients` (the surface that
    ``surface_from_coefficients`` samples on uniform grids), evaluated exactly
    at arbitrary tensor-grid points by two matrix products.

    Returns
    -------
    callable
        ``gap(x, y)`` for ``x`` of shape (n, 1) and ``y`` of shape (1, m) (m).
    """
    B = np.asarray(coefficients)
    kmax = (B.shape[0] - 1) // 2
    k = np.arange(-kmax, kmax + 1)

    def gap(x, y):
        ex = np.exp(2j * np.pi * np.outer(np.ravel(x), k) / length)
        ey = np.exp(2j * np.pi * np.outer(np.ravel(y), k) / length)
        z = np.real(ex @ B @ ey.T)
        return (separation - z).reshape(np.broadcast(x, y).shape)

    return gap


def summit_gap(x, y, clearance: float, centres, radii, tops) -> np.ndarray:
    """Gap (m) of a flat at ``clearance`` H above a base plane with paraboloidal summit caps.

    Parameters
    ----------
    x, y : ndarray
        Sample coordinates (m), broadcast against each other.
    clearance : float or callable
        H, gap between the flat and the base plane (m); or ``clearance(x, y)``,
        the gap of a rough base (e.g. :func:`fourier_gap`).
    centres : sequence of (float, float)
        Summit positions (m).
    radii : sequence of float
        Summit radii R_j (m).
    tops : sequence of float
        Gap h_j (m) at the top of each summit (0 < h_j <= H).
    """
    if callable(clearance):  # a rough base: its gap at (x, y)
        h = np.asarray(clearance(x, y), dtype=float) * np.ones(np.broadcast(x, y).shape)
    else:
        h = np.full(np.broadcast(x, y).shape, float(clearance))
    for (xc, yc), R, hj in zip(centres, radii, tops, strict=True):
        h = np.minimum(h, hj + ((x - xc) ** 2 + (y - yc) ** 2) / (2.0 * R))
    return h


def graded_axis(length: float, centres, fine, coarse: float, growth: float = 0.06):
    """Cell edges on ``[0, length]``: size ``fine_j`` at each centre, growing to ``coarse``.

    The target cell size is ``s(x) = min(coarse, min_j(fine_j + growth |x - c_j|))``
    (a geometric grading of ratio about ``1 + growth``).  The edges are the
    images of equally spaced points under the inverse of the cell-count map
    ``N(x) = int_0^x dx'/s(x')``, so the refinement stays centred on every
    c_j (a march from one end followed by a rescaling would shift it by up
    to half a coarse cell, many times the finest cell).

    Returns
    -------
    ndarray
        Increasing edge positions (m), first 0, last ``length``.
    """
    c = np.asarray(centres, dtype=float).ravel()
    f = np.broadcast_to(np.asarray(fine, dtype=float), c.shape)
    pts = [np.linspace(0.0, length, 4001)]
    for cj, fj in zip(c, f):
        off = np.geomspace(0.01 * fj, length, 600)
        pts.append(np.clip(np.concatenate([cj - off, [cj], cj + off]), 0.0, length))
    xs = np.unique(np.concatenate(pts))
    if c.size:
        dist = np.abs(xs[None, :] - c[:, None])
        s = np.minimum(coarse, np.min(f[:, None] + growth * dist, axis=0))
    else:
        s = np.full(xs.shape, float(coarse))
    # N(x) by the exact integral of 1/s over each piece where s is linear (s is
    # piecewise linear in x, and the samples include every centre)
    ds, dxs = np.diff(s), np.diff(xs)
    lin = np.abs(ds) > 1e-12 * s[:-1]
    with np.errstate(divide="ignore", invalid="ignore"):
        piece = np.where(lin, dxs / np.where(lin, ds, 1.0) * np.log(s[1:] / s[:-1]), dxs / s[:-1])
    N = np.concatenate([[0.0], np.cumsum(piece)])
    n = max(3, int(math.ceil(N[-1])))
    e = np.interp(np.linspace(0.0, N[-1], n + 1), N, xs)
    e[0], e[-1] = 0.0, length
    return e


def tensor_reynolds_squeeze(gap, dx, dy, viscosity: float, velocity: float = 1.0) -> Result:
    """Finite-volume squeeze Reynolds solve on a tensor-product grid of rectangular cells.

    ``-div(h^3/(12 eta) grad p) = V`` with ``p = 0`` on the outer rim (the
    edges of the rectangle).  The conductance of the face between two cells
    is that of the two half cells in series, ``l / (dx_a/(2 k_a) + dx_b/(2 k_b))``
    (``l``: face length), so the scheme is conservative; on a uniform grid it
    is :func:`~.flow_factor.rough_reynolds_squeeze`.  All cells must be open
    (h > 0): this reference is for the approach before contact.

    Parameters
    ----------
    gap : ndarray, shape (n, m)
        Gap at the cell centres (m), axis 0 along x.
    dx, dy : ndarray, shapes (n,), (m,)
        Cell widths (m).
    viscosity : float
        eta (Pa s).
    velocity : float
        Approach speed V (m/s).

    Returns
    -------
    Result
        ``force`` (N), ``resistance`` (N s/m), ``pressure`` (Pa), ``cells``.
    """
    from scipy import sparse
    from scipy.sparse.linalg import spsolve

    h = np.asarray(gap, dtype=float)
    dx, dy = np.asarray(dx, float), np.asarray(dy, float)
    if h.ndim != 2 or h.shape != (dx.size, dy.size) or min(h.shape) < 3:
        raise ParameterError(
            "gap", "a 2D array (len(dx), len(dy)) of at least 3 x 3 cells", h.shape
        )
    if not np.all(h > 0):
        raise ParameterError("gap", "h > 0 in every cell (no contact)", float(h.min()))
    res = Result(method="finite-volume Reynolds, graded tensor grid")
    with timed(res):
        n, m = h.shape
        k = h**3 / (12.0 * viscosity)
        idx = np.arange(n * m).reshape(n, m)
        rows, cols, vals = [], [], []
        diag = np.zeros(n * m)
        # x faces: between (i, j) and (i+1, j), face length dy_j
        gx = dy[None, :] / (0.5 * dx[:-1, None] / k[:-1] + 0.5 * dx[1:, None] / k[1:])
        # y faces: between (i, j) and (i, j+1), face length dx_i
        gy = dx[:, None] / (0.5 * dy[None, :-1] / k[:, :-1] + 0.5 * dy[None, 1:] / k[:, 1:])
        for gf, ia, ib in ((gx, idx[:-1], idx[1:]), (gy, idx[:, :-1], idx[:, 1:])):
            ia, ib, gf = ia.ravel(), ib.ravel(), gf.ravel()
            rows += [ia, ib]
            cols += [ib, ia]
            vals += [-gf, -gf]
            np.add.at(diag, ia, gf)
            np.add.at(diag, ib, gf)
        # Dirichlet rim: the half cell to the edge, l / (dx/(2k))
        dflat = diag.reshape(n, m)
        dflat[0, :] += dy * 2.0 * k[0, :] / dx[0]
        dflat[-1, :] += dy * 2.0 * k[-1, :] / dx[-1]
        dflat[:, 0] += dx * 2.0 * k[:, 0] / dy[0]
        dflat[:, -1] += dx * 2.0 * k[:, -1] / dy[-1]
        A = sparse.csc_matrix(
            (
                np.concatenate(vals + [diag]),
                (np.concatenate(rows + [idx.ravel()]), np.concatenate(cols + [idx.ravel()])),
            ),
            shape=(n * m, n * m),
        )
        area = (dx[:, None] * dy[None, :]).ravel()
        p = spsolve(A, velocity * area)
        force = float(np.sum(p * area))
    res.update(
        force=force,
        resistance=force / velocity if velocity else float("nan"),
        pressure=p.reshape(n, m),
        cells=int(n * m),
        units={"force": "N", "resistance": "N s/m", "pressure": "Pa"},
    )
    return res


def _grid(length, centres, radii, tops, refine):
    """Graded edges (x, y) resolving every summit's inner region r_c = sqrt(2 R h)."""
    rc = np.sqrt(2.0 * np.asarray(radii, float) * np.asarray(tops, float))
    fine = rc / (12.0 * refine)
    coarse = length / (96.0 * refine)
    growth = 0.06 / refine
    cx = [c[0] for c in centres]
    cy = [c[1] for c in centres]
    return (
        graded_axis(length, cx, fine, coarse, growth),
        graded_axis(length, cy, fine, coarse, growth),
    )


def summit_reference(
    length: float,
    clearance: float,
    centres,
    radii,
    tops,
    viscosity: float,
    *,
    refine: float = 2.0,
    error_estimate: bool = True,
) -> Result:
    """Reynolds film resistance (N s/m) of a square flat-with-summits gap, resolved.

    Solves :func:`tensor_reynolds_squeeze` on :func:`summit_gap` sampled at
    the centres of a grid graded around the summits (finest cell
    ``r_c/(12 refine)``, coarsest ``L/(96 refine)``, growth ``0.06/refine``;
    ``refine = 2``: about 1e5 cells for one summit, 0.5 s).
    With ``error_estimate`` it also solves at ``refine/2`` and reports the
    Richardson estimate of the error of the fine result (second order:
    ``(c_fine - c_coarse)/3``) as ``grid_error`` (relative).

    Returns
    -------
    Result
        ``resistance`` (N s/m), ``grid_error`` (relative, signed: c_exact ~
        resistance - grid_error * resistance), ``cells``, ``coarse_resistance``.
    """
    if not callable(clearance) and not all(0.0 < t <= clearance for t in tops):
        raise ParameterError("tops", f"summit gaps in (0, clearance = {clearance:g} m]", list(tops))
    res = Result(method="graded finite-volume Reynolds")

    def solve(rf):
        ex, ey = _grid(length, centres, radii, tops, rf)
        xc, yc = 0.5 * (ex[1:] + ex[:-1]), 0.5 * (ey[1:] + ey[:-1])
        h = summit_gap(xc[:, None], yc[None, :], clearance, centres, radii, tops)
        return tensor_reynolds_squeeze(h, np.diff(ex), np.diff(ey), viscosity)

    with timed(res):
        fine = solve(refine)
        coarse = solve(0.5 * refine) if error_estimate else None
    c = fine.resistance
    res.update(
        resistance=c,
        cells=fine.cells,
        coarse_resistance=coarse.resistance if coarse is not None else float("nan"),
        grid_error=(c - coarse.resistance) / 3.0 / c if coarse is not None else float("nan"),
        units={"resistance": "N s/m"},
    )
    return res


def cap_on_disc_resistance(
    outer_radius: float, clearance: float, radius: float, top: float, viscosity: float
) -> float:
    """Exact thin-film resistance (N s/m) of one paraboloidal cap at the centre of a disc.

    Gap ``h(r) = min(H, h + r^2/2R)`` on ``r < r_o``, ``p(r_o) = 0``.  The radial
    flux through every circle is ``V r / 2``, so ``F = 6 pi eta V int r^3/h^3 dr``:

        c = 6 pi eta R^2 (1/h - 2/H + h/H^2) + (3 pi / 2) eta (r_o^4 - a^4) / H^3 ,

    with ``a^2 = 2 R (H - h)`` (the cap's rim, which must lie inside the disc).
    """
    H, h, R = float(clearance), float(top), float(radius)
    a2 = 2.0 * R * (H - h)
    if not (0.0 < h <= H) or a2 > outer_radius**2:
        raise ParameterError("top", "0 < top <= clearance with the cap inside the disc", top)
    cap = 6.0 * math.pi * viscosity * R**2 * (1.0 / h - 2.0 / H + h / H**2)
    flat = 1.5 * math.pi * viscosity * (outer_radius**4 - a2**2) / H**3
    return cap + flat


def sampled_gap(length: float, clearance: float, centres, radii, tops, samples: int = 1024):
    """Sample :func:`summit_gap` at the centres of a uniform ``samples^2`` grid, flattened (m).

    These are the height samples a nominal (averaged) film model sees: the
    one-point distribution of the gap over the apparent area.
    """
    xs = (np.arange(samples) + 0.5) * (length / samples)
    return summit_gap(xs[:, None], xs[None, :], clearance, centres, radii, tops).ravel()


#: Test and benchmark geometries (L = 100 um, flat base, summit caps of height b = 2 um above
#: the base, top summit first): name -> (centres / L, radii (m), cap heights / b).
CASES = {
    # one small cap, rim radius a = 0.08 L, off centre
    "1 cap a/L=0.08": ([(0.37, 0.58)], [1.6e-5], [1.0]),
    # one large cap, a = 0.2 L, at the centre (cap area 12.6 % of the square)
    "1 cap a/L=0.2": ([(0.5, 0.5)], [1e-4], [1.0]),
    # three summits of different radii and heights (a = 0.2, 0.12, 0.2 L)
    "3 caps": ([(0.3, 0.35), (0.7, 0.6), (0.35, 0.75)], [1e-4, 5e-5, 2e-4], [1.0, 0.75, 0.5]),
}


def case_geometry(name: str, clearance_ratio: float, length: float = 1e-4, cap: float = 2e-6):
    """(centres, radii, tops, clearance) of :data:`CASES` ``name`` with the top at ``q b``."""
    c, radii, heights = CASES[name]
    h_top = clearance_ratio * cap
    H = cap + h_top
    centres = [(cx * length, cy * length) for cx, cy in c]
    tops = [H - hb * cap for hb in heights]
    return centres, list(radii), tops, H
