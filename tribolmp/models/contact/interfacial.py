"""Interfacial stiffness per unit area of a rough interface: the periodic 3D BEM (contract C5).

The apparent contact of a large body is a mosaic of rough patches; each patch
of the interface responds like a periodic cell, so its normal stiffness per
unit nominal area is

    K = -dp/d(u_mean)   (Pa/m = N/m^3),

the tangent of the nominal pressure against the mean interfacial separation
(Persson 2007; Pastewka et al. 2013; PHYSICS.md §8).  It is computed here by
the periodic constrained-CG BEM of :mod:`.bem`: the incremental stiffness of
the cell divided by its area.  The result also says whether the contact was
*resolved* (the mean contact patch spans at least :data:`MIN_PIXELS_PER_PATCH`
pixels); unresolved numbers are returned but flagged.

References
----------
B. N. J. Persson, Phys. Rev. Lett. 99, 125502 (2007). doi:10.1103/PhysRevLett.99.125502
L. Pastewka, N. Prodanov, B. Lorenz, M. H. Müser, M. O. Robbins, B. N. J. Persson,
Phys. Rev. E 87, 062809 (2013). doi:10.1103/PhysRevE.87.062809
"""

from __future__ import annotations

import time
from collections.abc import Sequence

import numpy as np

from ...errors import ParameterError
from ..base import Result, check_positive

__all__ = ["interfacial_stiffness", "patch_statistics", "MIN_PIXELS_PER_PATCH"]

#: A contact patch of fewer pixels is not resolved (issue 17: "tens of pixels per patch").
MIN_PIXELS_PER_PATCH = 20.0


def patch_statistics(contact: np.ndarray) -> tuple[int, float]:
    """Count the contact patches (periodic 4-connectivity) and their mean size in pixels."""
    from scipy import ndimage

    c = np.asarray(contact, dtype=bool)
    if not c.any():
        return 0, 0.0
    lab, n = ndimage.label(c)
    # Periodic cell: patches cut by the boundary are one patch; merge labels across the edges.
    parent = np.arange(n + 1)

    def find(a):
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    for a_edge, b_edge in ((lab[0, :], lab[-1, :]), (lab[:, 0], lab[:, -1])):
        for a, b in zip(a_edge, b_edge):
            if a and b:
                ra, rb = find(a), find(b)
                if ra != rb:
                    parent[ra] = rb
    roots = {find(i) for i in range(1, n + 1)}
    return len(roots), float(np.count_nonzero(c)) / len(roots)


def interfacial_stiffness(
    heights, pixel_size: float, E_star: float, pressures: Sequence[float], *, tol: float = 1e-10
) -> Result:
    """Periodic-BEM interfacial stiffness per area ``-dp/d(mean gap)`` at each nominal pressure.

    Parameters
    ----------
    heights : ndarray, shape (n, n)
        Rigid rough surface (m), a periodic cell of side ``n * pixel_size``;
        larger values touch first.
    pixel_size : float
        Grid spacing (m).
    E_star : float
        Effective modulus (Pa).
    pressures : sequence of float
        Nominal pressures (Pa), each below ``E_star``.
    tol : float
        BEM convergence tolerance (relative L1 change of the pressure).

    Returns
    -------
    Result
        Arrays in input order: ``pressure`` (Pa), ``stiffness_per_area``
        (Pa/m; ``inf`` for a closed cell), ``stiffness`` (N/m, of the cell),
        ``mean_gap`` (m, mean interfacial separation), ``area_fraction`` (1),
        ``pixels_per_patch`` (1), ``resolved`` (bool, ``pixels_per_patch >=
        MIN_PIXELS_PER_PATCH``), ``time_s`` (s, per pressure); ``units``.
    """
    from .bem import solve_bem
    from .rough import check_heightmap

    h = check_heightmap(heights, pixel_size)
    if h.shape[0] != h.shape[1]:
        raise ParameterError("heights", "a square (n, n) periodic height map", f"shape {h.shape}")
    dx = check_positive("pixel_size", pixel_size, "m")
    E = check_positive("modulus", E_star, "Pa")
    P = np.array([check_positive("pressure", p, "Pa") for p in pressures], dtype=float)
    if P.size == 0:
        raise ParameterError("pressures", "at least one pressure", "an empty list")
    if np.any(P >= E):
        bad = float(P[P >= E][0])
        raise ParameterError("pressures", f"pressures below the modulus ({E:g} Pa)", bad)
    area = (h.shape[0] * dx) ** 2
    keys = ("stiffness", "mean_gap", "area_fraction", "pixels_per_patch", "time_s")
    out = {k: np.empty(P.size) for k in keys}
    p0 = None
    for j in np.argsort(P):  # ascending loads warm-start from the previous pressure field
        t0 = time.perf_counter()
        r = solve_bem(h, dx, E, float(P[j]), periodic=True, tol=tol, p0=p0)
        p0 = r.p
        out["stiffness"][j] = r.stiffness
        out["mean_gap"][j] = r.mean_gap
        out["area_fraction"][j] = r.area_fraction
        out["pixels_per_patch"][j] = patch_statistics(r.p > 0)[1]
        out["time_s"][j] = time.perf_counter() - t0
    return Result(
        pressure=P,
        stiffness_per_area=out["stiffness"] / area,
        resolved=out["pixels_per_patch"] >= MIN_PIXELS_PER_PATCH,
        nominal_area=area,
        method="bem-periodic",
        units={"pressure": "Pa", "stiffness_per_area": "Pa/m", "stiffness": "N/m", "mean_gap": "m",
               "area_fraction": "1", "pixels_per_patch": "1", "time_s": "s", "nominal_area": "m^2"},
        **out,
    )
