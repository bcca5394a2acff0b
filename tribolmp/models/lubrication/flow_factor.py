"""Squeeze film of a rough apparent contact.

Flow factors and a resolved 2D rough Reynolds solve (SI).

A rigid nominal flat approaches a rough surface of apparent area A through a
Newtonian film.  The local gap is ``h(x, y) = max(u - z(x, y), 0)`` (``u``:
separation of the flat from the mean plane, ``z``: heights about their mean).
Local Reynolds: ``-div(h^3/(12 eta) grad p) = V`` where the film is open
(``V = -du/dt``), no flow through contact spots, ``p = 0`` on the rim.

Averaged over the roughness (Patir & Cheng 1978) the flux is
``-k_eff/(12 eta) grad p`` with an effective conductance ``k_eff`` (m^3;
``k_eff = phi_p u^3`` in Patir-Cheng's notation) and the source is the rate
of change of the mean film thickness, ``-dh_T/dt = (1 - a_c) V`` (``a_c``:
fraction of the area where the rigid gap is closed).  On a nominally flat
apparent contact ``k_eff`` is uniform, so the nominal problem is the
Poisson problem ``-lap P = 1`` times ``12 eta (1 - a_c) V / k_eff`` and the
film resistance of the apparent contact is

    c = F / V = 12 eta (1 - a_c) I_A / k_eff ,   I_A = int P dA ,

``I_A = 0.0351442537 L^4`` for a square of side L (the double Fourier
series of :func:`square_poisson_integral`) and ``pi a^4 / 8`` for a disc of
radius a.  For a smooth gap (``k_eff = u^3``) this is the classical squeeze
film of a flat plate.

Two conductances are provided:

* ``"bruggeman"`` (default): the self-consistent effective medium of an
  isotropic 2D random conductor, ``< (k - k_eff)/(k + k_eff) > = 0`` over the
  gap distribution with ``k = h^3``.  It is exact to second order in the
  fluctuation of ``k`` for any isotropic 2D field (the second-order
  perturbation result ``<k> - <dk^2>/(2<k>)`` does not depend on the
  correlation function in 2D) and seals (``k_eff = 0``) at ``a_c = 1/2``,
  the percolation threshold of a symmetric 2D medium.  It needs only the
  one-point gap distribution, which an MDR profile of the Geike-Popov kind
  keeps (same height distribution as the 2D surface).
* ``"patir-cheng"``: the published fit ``phi_p = 1 - 0.9 exp(-0.56 u/sigma)``
  for isotropic Gaussian roughness (valid for u/sigma > 0.5), for comparison.

Both are checked in the tests against :func:`rough_reynolds_squeeze`, the
finite-volume solution of the local Reynolds equation on the resolved gap.

References
----------
Patir N, Cheng HS. J Lubr Technol 100 (1978) 12, doi:10.1115/1.3453103.
Bruggeman DAG. Ann Phys 416 (1935) 636, doi:10.1002/andp.19354160705.
"""

from __future__ import annotations

import math

import numpy as np

from ...errors import ParameterError
from ..base import Result, timed

__all__ = [
    "SQUARE_POISSON",
    "square_poisson_integral",
    "shape_integral",
    "bruggeman_conductance",
    "patir_cheng_flow_factor",
    "CONDUCTANCES",
    "film_resistance",
    "rough_reynolds_squeeze",
]

#: int P dA / L^4 for -lap P = 1 on the unit square, P = 0 on its edges
#: ((64/pi^6) sum over odd m, n of 1/(m^2 n^2 (m^2 + n^2)); see :func:`square_poisson_integral`).
SQUARE_POISSON = 0.03514425373836

CONDUCTANCES = ("bruggeman", "patir-cheng", "smooth")


def square_poisson_integral(terms: int = 2000) -> float:
    """``int P dA / L^4`` for the unit square by its double Fourier series (dimensionless)."""
    m = np.arange(1, 2 * terms, 2, dtype=float)
    m2 = m * m
    return float(
        64.0 / math.pi**6 * np.sum(1.0 / (m2[:, None] * m2[None, :] * (m2[:, None] + m2[None, :])))
    )


def shape_integral(shape: str, length: float) -> float:
    """``I_A = int P dA`` (m^4) of the apparent contact.

    ``"square"`` of side L or ``"disc"`` of diameter L.
    """
    if shape == "square":
        return SQUARE_POISSON * length**4
    if shape == "disc":
        return math.pi * (0.5 * length) ** 4 / 8.0
    raise ParameterError("apparent_shape", "one of ['square', 'disc']", shape)


def bruggeman_conductance(gaps, axis: int = -1) -> np.ndarray:
    """Effective film conductance ``k_eff`` (m^3) of an isotropic 2D rough gap (Bruggeman).

    Solves ``mean((k - k_eff)/(k + k_eff)) = 0`` with ``k = h^3`` over the
    samples along ``axis`` (bisection in ln k_eff, 200 halvings of the
    bracket's log width at most, so converged to round-off).  Returns 0 where
    the closed fraction reaches 1/2 (the film is sealed).

    Parameters
    ----------
    gaps : array_like
        Local gaps h >= 0 (m); zeros are contact spots.
    axis : int
        Sample axis.
    """
    h = np.moveaxis(np.asarray(gaps, dtype=float), axis, -1)
    k = np.clip(h, 0.0, None) ** 3
    open_ = k > 0
    closed = 1.0 - open_.mean(axis=-1)
    kmax = k.max(axis=-1)
    kmin = np.where(open_, k, np.inf).min(axis=-1)
    sealed = (closed >= 0.5) | ~np.isfinite(kmin)
    lo = np.log(np.where(sealed, 1.0, kmin))
    hi = np.log(np.where(sealed, 1.0, kmax))
    # the root lies in [min k, max k] over the open samples when a_c < 1/2
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        km = np.exp(mid)[..., None]
        f = np.mean((k - km) / (k + km), axis=-1)
        lo = np.where(f > 0, mid, lo)
        hi = np.where(f > 0, hi, mid)
        if np.all(hi - lo < 1e-13):
            break
    return np.where(sealed, 0.0, np.exp(0.5 * (lo + hi)))


def patir_cheng_flow_factor(separation, sigma) -> np.ndarray:
    """Patir-Cheng pressure flow factor ``1 - 0.9 exp(-0.56 u/sigma)``.

    Isotropic, for u/sigma > 0.5.
    """
    return 1.0 - 0.9 * np.exp(-0.56 * np.asarray(separation, dtype=float) / float(sigma))


def film_resistance(gaps, viscosity: float, shape: str, length: float, *, method: str = "bruggeman",
                    separation=None, sigma: float | None = None, axis: int = -1):
    """Film resistance ``c = F/V`` (N s/m) of a rough apparent contact.

    ``c = 12 eta (1 - a_c) I_A / k_eff`` (see the module notes); ``inf`` where
    the film is sealed (``k_eff = 0``).

    Parameters
    ----------
    gaps : array_like
        Local rigid gap samples h >= 0 (m) along ``axis``.
    viscosity : float
        eta (Pa s).
    shape, length : str, float
        Apparent contact (see :func:`shape_integral`).
    method : {"bruggeman", "patir-cheng", "smooth"}
        Conductance.
    separation : array_like, optional
        u (m) for ``patir-cheng``/``smooth``; default: the mean gap.
    sigma : float, optional
        rms roughness (m) for ``patir-cheng``; default: std of the gaps.

    Returns
    -------
    (c, k_eff, closed_fraction) : tuple of ndarrays
    """
    h = np.moveaxis(np.asarray(gaps, dtype=float), axis, -1)
    closed = np.mean(h <= 0.0, axis=-1)
    u = np.mean(h, axis=-1) if separation is None else np.asarray(separation, dtype=float)
    if method == "bruggeman":
        k = bruggeman_conductance(h)
    elif method == "smooth":
        k = u**3
    elif method == "patir-cheng":
        s = float(np.std(h)) if sigma is None else float(sigma)
        k = patir_cheng_flow_factor(u, s) * u**3
    else:
        raise ParameterError("flow_factor", f"one of {list(CONDUCTANCES)}", method)
    i_area = shape_integral(shape, length)  # I_A (m^4)
    with np.errstate(divide="ignore"):
        c = np.where(
            k > 0, 12.0 * viscosity * (1.0 - closed) * i_area / np.where(k > 0, k, 1.0), np.inf
        )
    return c, k, closed


def rough_reynolds_squeeze(
    gap, pixel_size: float, viscosity: float, velocity: float = 1.0
) -> Result:
    """Finite-volume solution of the local squeeze Reynolds equation on a resolved rough gap.

    ``-div(h^3/(12 eta) grad p) = V`` on the open cells of an ``n x m`` grid
    of square cells, no flux into closed cells (h <= 0), ``p = 0`` on the
    outer rim (half a cell outside the edge cells).  Face conductances are the
    harmonic means of the cell values (the exact series conductance of two
    half cells), so the scheme is conservative and second order for a smooth
    gap.  Open regions not connected to the rim hold trapped, incompressible
    fluid: they are excluded and reported as ``trapped_fraction``.

    Parameters
    ----------
    gap : ndarray, shape (n, m)
        Local gaps (m).
    pixel_size : float
        Cell side (m).
    viscosity : float
        eta (Pa s).
    velocity : float
        Approach speed V (m/s).

    Returns
    -------
    Result
        ``force`` (N, fluid pressure integrated over the open cells),
        ``resistance`` (N s/m), ``pressure`` (Pa, NaN in closed/trapped cells),
        ``closed_fraction``, ``trapped_fraction``.
    """
    from scipy import ndimage, sparse
    from scipy.sparse.linalg import spsolve

    h = np.asarray(gap, dtype=float)
    if h.ndim != 2 or min(h.shape) < 3:
        raise ParameterError("gap", "a 2D array of at least 3 x 3 cells", h.shape)
    res = Result(method="finite-volume rough Reynolds")
    with timed(res):
        open_ = h > 0
        lab, nlab = ndimage.label(open_)
        rim = np.zeros_like(open_)
        rim[[0, -1], :] = True
        rim[:, [0, -1]] = True
        connected = np.isin(lab, np.unique(lab[rim & open_]))
        active = open_ & connected
        idx = -np.ones(h.shape, dtype=np.int64)
        idx[active] = np.arange(int(active.sum()))
        k = np.where(active, h, 0.0) ** 3 / (12.0 * viscosity)
        rows, cols, vals = [], [], []
        diag = np.zeros(int(active.sum()))
        for sl_a, sl_b in (((slice(None, -1), slice(None)), (slice(1, None), slice(None))),
                           ((slice(None), slice(None, -1)), (slice(None), slice(1, None)))):
            ka, kb = k[sl_a], k[sl_b]
            both = active[sl_a] & active[sl_b]
            cf = np.where(both, 2.0 * ka * kb / np.where(both, ka + kb, 1.0), 0.0)[both]
            ia, ib = idx[sl_a][both], idx[sl_b][both]
            rows += [ia, ib]
            cols += [ib, ia]
            vals += [-cf, -cf]
            np.add.at(diag, ia, cf)
            np.add.at(diag, ib, cf)
        # Dirichlet rim: conductance of the half cell, 2 k (face length / half distance = 2)
        for edge in ((0, slice(None)), (-1, slice(None)), (slice(None), 0), (slice(None), -1)):
            e_act = active[edge]
            np.add.at(diag, idx[edge][e_act], 2.0 * k[edge][e_act])
        nact = diag.size
        A = sparse.csr_matrix(
            (
                np.concatenate(vals + [diag]),
                (
                    np.concatenate(rows + [np.arange(nact)]),
                    np.concatenate(cols + [np.arange(nact)]),
                ),
            ),
            shape=(nact, nact),
        )
        rhs = np.full(nact, velocity * pixel_size**2)
        p_act = spsolve(A.tocsc(), rhs) if nact else np.zeros(0)
        p = np.full(h.shape, np.nan)
        p[active] = p_act
        force = float(np.sum(p_act) * pixel_size**2)
    res.update(
        force=force,
        resistance=force / velocity if velocity else float("nan"),
        pressure=p,
        closed_fraction=float(1.0 - open_.mean()),
        trapped_fraction=float((open_ & ~connected).mean()),
        length=float(h.shape[0] * pixel_size),
        units={"force": "N", "resistance": "N s/m", "pressure": "Pa"},
    )
    res.message = f"{nact} open cells, {nlab} open region(s)"
    return res
