"""The lower body's surface profile h(x, t) from its column mass (issue 14, contract C1).

The height of the lower body at column ``x`` is the amount of its material
in that column divided by the bulk density of the material:

    h(x, t) = y_bottom + N(x, t) / (n_bulk w W)

with ``N`` the number of lower-side automata (base, mol 1, and lower body,
mol 2: the material of the lower body, wherever it went) whose centre lies in
the column of width ``w`` along x, ``n_bulk`` their number density in the
undisturbed bulk of frame 0 (automata per m^2 in 2D, per m^3 in 3D), ``W``
the transverse width (1 in 2D, the periodic z length in 3D) and
``y_bottom`` the bottom edge of the base.  A mass-based height counts
overhangs, voids and debris carried in the column, so it is defined for any
configuration, unlike the top-most automaton; it is the height that a
conserved-mass continuum model (Eq. 23) evolves.

The discreteness of the automata adds a shot noise to every column that is
nearly white in time (automata crossing a column boundary by vibration); the
Eq. 23 fit (:func:`tribolmp.analysis.eq23.fit_eq23`) starts its
autocovariance at lag 1 for that reason.
"""

from __future__ import annotations

import math

import numpy as np
from MDAnalysis.analysis.base import AnalysisBase

from ..errors import DataFileError
from ..params import check_range
from .outputs import MOL_BASE, MOL_LOWER, NM, FromOutput, MCAMeta
from .profiles import interface_height

__all__ = ["SurfaceProfile"]


class SurfaceProfile(FromOutput, AnalysisBase):
    """Column-mass height profile of the lower body, h(x, t), along the sliding axis x.

    Parameters
    ----------
    universe : MDAnalysis.Universe
        From :func:`~tribolmp.analysis.outputs.open_trajectory`.
    meta : MCAMeta
        The run's metadata.
    column_width_m : float, optional
        Target column width (m); the box length is divided into
        ``round(L / column_width_m)`` equal columns.  Default: one automaton
        diameter (the smallest scale the material resolves).
    bulk_margin_m : float, optional
        The bulk density is measured in frame 0 between ``bulk_margin_m``
        above the base's bottom and ``bulk_margin_m`` below the lowest point
        of the interface region (default 2 d).

    Attributes
    ----------
    results
        MDAnalysis ``Results`` with ``x_m`` (column centres, m), ``t_s``
        (frame times, s), ``h_m`` (nt, nx) heights (m), ``counts`` (nt, nx),
        ``column_width_m``, ``bulk_density`` (automata per m^2 in 2D, per
        m^3 in 3D), ``y_bottom_m``, ``rms_m`` (per frame, m) and ``units``.
    """

    def __init__(
        self, universe, meta: MCAMeta, *, column_width_m=None, bulk_margin_m=None, **kwargs
    ):
        super().__init__(universe.trajectory, **kwargs)
        self._meta = meta
        d = meta.automaton_diameter_m
        w = d if column_width_m is None else column_width_m
        self._w_target = check_range("column_width_m", w, 0.0, None, lo_open=True, unit="m")
        m = 2 * d if bulk_margin_m is None else bulk_margin_m
        self._margin_nm = check_range("bulk_margin_m", m, 0.0, None, unit="m") / NM

    def _prepare(self):
        ax = self._meta.normal_axis
        ts0 = self._trajectory[0]
        L = float(ts0.dimensions[0])  # nm
        self._L = L
        self._nx = max(4, int(round(L * NM / self._w_target)))
        self._w = L / self._nx
        h0 = ts0.positions[:, ax].astype(float)
        mols = ts0.data["mol"].astype(int)
        self._lower = np.isin(mols, (MOL_BASE, MOL_LOWER))
        if self._lower.sum() < self._nx:
            raise DataFileError(
                f"trajectory: mol: expected lower-side automata (mol 1, 2) in every column, "
                f"got {int(self._lower.sum())} for {self._nx} columns"
            )
        y0 = interface_height(h0, mols)
        radius = (
            float(np.median(ts0.data["radius"]))
            if "radius" in ts0.data
            else 0.5 * self._meta.automaton_diameter_m / NM
        )
        # the interface region reaches down to the deepest valley of the initial roughness: measure
        # the bulk density below it (the lowest upper-body automaton bounds the valleys from below)
        up = ~self._lower
        top = min(y0, float(h0[up].min()) if up.any() else y0)
        y_bottom, hi, n_in, how = self._bulk_window(h0[self._lower], top, radius)
        self._bulk_method = how
        width = 1.0
        if self._meta.dimension == 3:
            lat = [a for a in range(3) if a not in (0, ax)][0]
            width = float(ts0.dimensions[lat])
        self._bulk = n_in / (L * (hi - y_bottom) * width)  # automata per nm^2 (2D) or nm^3 (3D)
        self._width = width
        self._y_bottom = y_bottom
        n = self.n_frames
        self._counts = np.zeros((n, self._nx))
        self._time = np.zeros(n)

    def _bulk_window(self, h, top, radius):
        """Return the bulk window used for the density.

        (bottom edge (nm), top edge (nm), automata between them, method).

        A lattice (the initial configuration the driver builds) is cut between its rows: rows are
        the clusters of heights separated by gaps > d/4; the bulk is the contiguous run of rows from
        the bottom that are as full as the lowest rows and lie below ``top - margin``, from half a
        row spacing below the first to half a spacing above the last, so it holds whole rows and the
        density is exact for a perfect lattice.  Otherwise (no row structure) the density is the
        count in a window ``margin`` inside the material, which is biased by up to one row / window.
        """
        d = self._meta.automaton_diameter_m / NM
        hs = np.sort(h)
        gaps = np.diff(hs)
        cut = np.nonzero(gaps > 0.25 * d)[0]
        starts = np.r_[0, cut + 1]
        ends = np.r_[cut + 1, hs.size]
        centres = np.array([hs[a:b].mean() for a, b in zip(starts, ends)])
        sizes = ends - starts
        limit = top - self._margin_nm
        # whole rows only: contiguous from the bottom, each as full as the lowest rows (the rough
        # surface's partly filled rows and anything within the margin of the interface are left out)
        full = sizes >= 0.95 * np.median(sizes[: min(3, sizes.size)])
        keep = np.cumprod(full & (centres + 0.5 * d <= limit)).astype(bool)
        if keep.sum() >= 3:
            a = float(np.median(np.diff(centres[keep])))
            bottom = centres[0] - 0.5 * a
            upper = centres[keep][-1] + 0.5 * a
            return float(bottom), float(upper), int(sizes[keep].sum()), "whole lattice rows"
        y_bottom = float(hs[0]) - radius
        for margin in (self._margin_nm, 0.5 * self._margin_nm, 0.25 * self._margin_nm, 0.0):
            lo, hi = y_bottom + margin, top - margin
            if hi - lo > 2 * radius:
                n_in = int(((h >= lo) & (h < hi)).sum())
                # the window's density applied from the bottom edge
                return (
                    y_bottom,
                    y_bottom + (hi - lo),
                    n_in,
                    f"window {margin * NM:.3g} m inside the material",
                )
        raise DataFileError(
            f"trajectory: lower body: expected material between its bottom and the interface, got "
            f"{max(top - y_bottom, 0.0) * NM:.3g} m")

    def _single_frame(self):
        i = self._frame_index
        ts = self._ts
        x = ts.positions[self._lower, 0].astype(float)
        col = np.floor(np.mod(x, self._L) / self._w).astype(int)
        col = np.clip(col, 0, self._nx - 1)
        self._counts[i] = np.bincount(col, minlength=self._nx)
        self._time[i] = ts.time * 1e-12

    def _conclude(self):
        r = self.results
        h_nm = self._y_bottom + self._counts / (self._bulk * self._w * self._width)
        r.x_m = (np.arange(self._nx) + 0.5) * self._w * NM
        r.t_s = self._time.copy()
        r.h_m = h_nm * NM
        r.counts = self._counts.astype(np.int64)
        r.column_width_m = self._w * NM
        dim = self._meta.dimension
        r.bulk_density = self._bulk / NM**dim
        r.y_bottom_m = self._y_bottom * NM
        r.bulk_method = self._bulk_method
        r.rms_m = (h_nm - h_nm.mean(axis=1, keepdims=True)).std(axis=1) * NM
        r.units = {
            "x_m": "m",
            "t_s": "s",
            "h_m": "m",
            "column_width_m": "m",
            "bulk_density": "1/m^2" if dim == 2 else "1/m^3",
            "y_bottom_m": "m",
            "rms_m": "m",
        }
        if not math.isfinite(float(r.h_m.sum())):
            raise DataFileError("trajectory: positions: expected finite heights, got NaN/inf")
