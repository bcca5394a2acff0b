"""Height-binned profiles of an MCA run: velocity (shear layer) and composition (mixing).

Both are MDAnalysis ``AnalysisBase`` subclasses over the universe returned by
:func:`~tribolmp.analysis.outputs.open_trajectory`.  Heights are measured
along the interface normal (``meta.normal_axis``, ``y`` by default), in the
absolute LAMMPS frame, and reported in metres.  The *original interface*
``interface_height_m`` is where the upper-body fraction crosses 1/2 in the
reference frame (frame 0, before sliding mixes the bodies).

Layer widths use one definition for both profiles: fit the time-averaged
profile with a monotone (isotonic, count-weighted) sequence and take the
distance between its 10 % and 90 % crossings.  For a linear ramp of width
``w`` this is ``0.8 w``; for an error-function profile of standard deviation
``s`` it is ``2 * 1.2816 s``.
"""

from __future__ import annotations

import numpy as np
from MDAnalysis.analysis.base import AnalysisBase

from ..errors import DataFileError, ParameterError
from ..params import check_range
from .outputs import MOL_SLIDER, MOL_UPPER, NM, FromOutput, MCAMeta
from .stats import crossing_heights, isotonic_fit

__all__ = ["VelocityProfile", "CompositionProfile", "interface_height", "layer_width"]


def layer_width(z, f, w, lo: float = 0.1, hi: float = 0.9) -> tuple[float, float, float]:
    """10 %-90 % width of a profile rising from 0 to 1.

    Parameters
    ----------
    z : array_like
        Bin centres (m), increasing.
    f : array_like
        Profile values (normalised to rise from 0 to 1).
    w : array_like
        Weights (counts) per bin; bins with zero weight are ignored.
    lo, hi : float
        Levels.

    Returns
    -------
    width, z_lo, z_hi : float
        ``z_hi - z_lo`` and the two crossing heights (m); NaN when the fitted
        profile does not span both levels.
    """
    z, f, w = (np.asarray(a, dtype=float) for a in (z, f, w))
    keep = w > 0
    if keep.sum() < 2:
        return float("nan"), float("nan"), float("nan")
    fit = isotonic_fit(f[keep], w[keep])
    z_lo, z_hi = crossing_heights(z[keep], fit, [lo, hi])
    return float(z_hi - z_lo), float(z_lo), float(z_hi)


def interface_height(heights, mols) -> float:
    """Original interface height: the plane that best separates the two bodies.

    The height ``t`` minimising the number of lower-side automata (mol 1, 2)
    above it plus upper-side automata (mol 3, 4) below it; when a range of
    heights is equally good, its midpoint.  For a flat interface this is the
    middle of the gap between the two surface rows; for rough surfaces it
    balances the asperities of both bodies.  Bin-free, so it does not depend
    on how the profiles are binned.

    Parameters
    ----------
    heights : array_like
        Heights of all automata (any length unit; the result has the same).
    mols : array_like
        Molecule ids.
    """
    h = np.asarray(heights, dtype=float)
    up = np.isin(np.asarray(mols), (MOL_UPPER, MOL_SLIDER))
    if up.all() or not up.any():
        return float("nan")
    order = np.argsort(h, kind="stable")
    hs, us = h[order], up[order]
    # cost of a cut just above sorted point i: upper at or below i + lower above i
    cost = np.cumsum(us) + (np.count_nonzero(~us) - np.cumsum(~us))
    best = np.nonzero(cost == cost.min())[0]
    lo = hs[best[0]]
    hi = hs[min(best[-1] + 1, hs.size - 1)]
    return float(0.5 * (lo + hi))


class _HeightBinned:
    """Mixin: bins along the normal, fixed from the reference frame."""

    def _setup_bins(self, meta: MCAMeta, bin_width_m: float | None, reference_frame: int,
                    column_width_m: float | None = None) -> None:
        self._meta = meta
        self._axis = meta.normal_axis
        w = meta.automaton_diameter_m if bin_width_m is None else bin_width_m
        self._bin_nm = check_range("bin_width_m", w, 0.0, None, lo_open=True, unit="m") / NM
        self._ref = int(reference_frame)
        cw = 2 * meta.automaton_diameter_m if column_width_m is None else column_width_m
        self._col_target_nm = (
            check_range("column_width_m", cw, 0.0, None, lo_open=True, unit="m") / NM
        )

    def _prepare_bins(self) -> None:
        traj = self._trajectory
        ts = traj[self._ref]
        h = ts.positions[:, self._axis].astype(float)
        w = self._bin_nm
        lo = np.floor(h.min() / w) * w - 2 * w
        hi = np.ceil(h.max() / w) * w + 2 * w
        self._edges = np.arange(lo, hi + 0.5 * w, w)
        self._nb = self._edges.size - 1
        mols = ts.data["mol"].astype(int)
        self._mols = mols
        self._L_nm = float(ts.dimensions[0])
        self._ncol = max(1, int(round(self._L_nm / self._col_target_nm)))
        self._y0_nm = interface_height(h, mols)
        if not np.isfinite(self._y0_nm):
            raise DataFileError(
                "trajectory: mol: expected lower (1, 2) and "
                "upper (3, 4) bodies stacked along the normal"
            )

    def _bin_index(self, h) -> np.ndarray:
        return np.clip(np.floor((h - self._edges[0]) / self._bin_nm).astype(int), 0, self._nb - 1)

    def _col_bin_index(self, x, h) -> np.ndarray:
        """Flat index column * n_bins + height bin (columns of equal width along the periodic x)."""
        col = np.clip(
            np.floor(np.mod(x, self._L_nm) / (self._L_nm / self._ncol)).astype(int),
            0,
            self._ncol - 1,
        )
        return col * self._nb + self._bin_index(h)

    @property
    def _column_width_m(self) -> float:
        return self._L_nm / self._ncol * NM

    @property
    def _centres_m(self) -> np.ndarray:
        return 0.5 * (self._edges[1:] + self._edges[:-1]) * NM

    def _windows(self, n_frames: int, n_windows: int) -> list[slice]:
        k = max(1, min(n_windows, n_frames))
        bounds = np.linspace(0, n_frames, k + 1).astype(int)
        return [slice(a, b) for a, b in zip(bounds[:-1], bounds[1:]) if b > a]


class VelocityProfile(_HeightBinned, FromOutput, AnalysisBase):
    """Time-averaged sliding velocity v_x(h) and the sheared-layer depth.

    Parameters
    ----------
    universe : MDAnalysis.Universe
        From :func:`~tribolmp.analysis.outputs.open_trajectory`.
    meta : MCAMeta
        The run's metadata.
    bin_width_m : float, optional
        Bin width along the normal (m); default one automaton diameter.
    velocity_reference : {"slider", "meta"}
        Normalise by the measured mean velocity of the slider (mol 4;
        exact after the ramp) or by ``meta.velocity_m_s``.
    reference_frame : int
        Frame defining the bins and the original interface (default 0).
    n_windows : int
        The analysed frames are also split into this many consecutive
        windows, each giving a layer depth and position (persistence).

    Attributes
    ----------
    results
        MDAnalysis ``Results`` holding the following fields.
    heights_m, vx_m_s, counts
        Bin centres (m), mean v_x per bin (m/s), automaton-frames per bin.
    layer_depth_m, layer_bottom_m, layer_top_m, layer_center_m
        10 %-90 % width of v_x/V and its bounds (m, absolute heights).
    layer_offset_m
        Layer centre minus the original interface height (m): near 0 when
        the shear localises at the interface, about +-(body height) when
        slip moved to the driver or the base.
    interface_height_m, reference_velocity_m_s
    window_time_s, window_layer_depth_m, window_layer_offset_m
    column_width_m, column_layer_depth_m, layer_depth_columns_m, layer_depth_columns_err_m
        The same 10-90 % width in each x column of ``column_width_m``
        (default 2 d), and its mean over the columns with the standard error
        of that mean: a wavy slip line is sharp in every column, while the
        x-averaged ``layer_depth_m`` turns its waviness into an apparent layer.
    """

    def __init__(self, universe, meta: MCAMeta, *, bin_width_m=None, velocity_reference="slider",
                 reference_frame=0, n_windows=5, column_width_m=None, **kwargs):
        super().__init__(universe.trajectory, **kwargs)
        self._setup_bins(meta, bin_width_m, reference_frame, column_width_m)
        if velocity_reference not in ("slider", "meta"):
            raise ParameterError(
                "velocity_reference", "one of ['slider', 'meta']", velocity_reference
            )
        self._vref = velocity_reference
        self._n_windows = int(n_windows)

    def _prepare(self):
        self._prepare_bins()
        n = self.n_frames
        self._sum = np.zeros((n, self._nb))
        self._cnt = np.zeros((n, self._nb))
        self._csum = np.zeros(self._ncol * self._nb)
        self._ccnt = np.zeros(self._ncol * self._nb)
        self._vslider = np.full(n, np.nan)
        self._time = np.zeros(n)

    def _single_frame(self):
        ts = self._ts
        i = self._frame_index
        h = ts.positions[:, self._axis].astype(float)
        vx = ts.velocities[:, 0].astype(float)  # nm/ns == m/s
        b = self._bin_index(h)
        self._sum[i] = np.bincount(b, vx, self._nb)
        self._cnt[i] = np.bincount(b, None, self._nb)
        cb = self._col_bin_index(ts.positions[:, 0].astype(float), h)
        self._csum += np.bincount(cb, vx, self._ncol * self._nb)
        self._ccnt += np.bincount(cb, None, self._ncol * self._nb)
        slider = ts.data["mol"].astype(int) == MOL_SLIDER
        if slider.any():
            self._vslider[i] = vx[slider].mean()
        self._time[i] = ts.time * 1e-12

    def _profile(self, sl):
        s, c = self._sum[sl].sum(axis=0), self._cnt[sl].sum(axis=0)
        v = np.where(c > 0, s / np.maximum(c, 1), np.nan)
        return v, c

    def _layer(self, v, c, vref):
        ok = c > 0
        f = np.where(ok, v / vref, 0.0)
        return layer_width(self._centres_m, f, np.where(ok, c, 0))

    def _conclude(self):
        r = self.results
        if self._vref == "slider" and np.isfinite(self._vslider).any():
            vref = float(np.nanmean(self._vslider))
        else:
            vref = self._meta.velocity_m_s
        if not vref > 0:
            raise DataFileError(f"trajectory: slider velocity: expected > 0 m/s, got {vref!r}")
        v, c = self._profile(slice(None))
        width, lo, hi = self._layer(v, c, vref)
        y0 = self._y0_nm * NM
        r.heights_m = self._centres_m
        r.vx_m_s = v
        r.counts = c
        r.reference_velocity_m_s = vref
        r.interface_height_m = y0
        r.layer_depth_m = width
        r.layer_bottom_m = lo
        r.layer_top_m = hi
        r.layer_center_m = 0.5 * (lo + hi)
        r.layer_offset_m = 0.5 * (lo + hi) - y0
        # slip on a single plane still gives a 10-90 % width of ~0.8-1.7 bins (interpolation
        # between bin centres): only a width of two bins or more is a resolved layer
        r.bin_width_m = self._bin_nm * NM
        r.layer_resolved = bool(np.isfinite(width) and width >= 2 * r.bin_width_m)
        r.time_s = self._time
        wt, wd, wo = [], [], []
        for sl in self._windows(self.n_frames, self._n_windows):
            vv, cc = self._profile(sl)
            ww, a, b = self._layer(vv, cc, vref)
            wt.append(self._time[sl].mean())
            wd.append(ww)
            wo.append(0.5 * (a + b) - y0)
        r.window_time_s = np.asarray(wt)
        r.window_layer_depth_m = np.asarray(wd)
        r.window_layer_offset_m = np.asarray(wo)
        # per x column: a wavy slip line is sharp in every column, while the
        # x-averaged profile above turns its waviness into an apparent layer
        cs = self._csum.reshape(self._ncol, self._nb)
        cc = self._ccnt.reshape(self._ncol, self._nb)
        cols = []
        for j in range(self._ncol):
            vj = np.where(cc[j] > 0, cs[j] / np.maximum(cc[j], 1), np.nan)
            cols.append(self._layer(vj, cc[j], vref))
        cols = np.asarray(cols)
        r.column_width_m = self._column_width_m
        r.column_layer_depth_m = cols[:, 0]
        r.column_layer_center_m = 0.5 * (cols[:, 1] + cols[:, 2])
        ok = np.isfinite(cols[:, 0])
        r.columns_resolved = int(ok.sum())
        r.layer_depth_columns_m = float(cols[ok, 0].mean()) if ok.any() else float("nan")
        r.layer_depth_columns_err_m = (
            float(cols[ok, 0].std(ddof=1) / np.sqrt(ok.sum())) if ok.sum() > 1 else float("nan")
        )
        r.units = {"heights_m": "m", "vx_m_s": "m/s", "layer_depth_m": "m", "layer_offset_m": "m",
                   "interface_height_m": "m", "reference_velocity_m_s": "m/s", "time_s": "s",
                   "column_width_m": "m", "column_layer_depth_m": "m", "layer_depth_columns_m": "m",
                   "layer_depth_columns_err_m": "m"}

class CompositionProfile(_HeightBinned, FromOutput, AnalysisBase):
    """Fraction of upper-body automata per height: mixing and penetration.

    The lower side is mol 1 (base) and 2 (lower body); the upper side mol
    3 (upper body) and 4 (slider).

    Parameters
    ----------
    universe : MDAnalysis.Universe
        From :func:`~tribolmp.analysis.outputs.open_trajectory`.
    meta : MCAMeta
        The run's metadata.
    bin_width_m : float, optional
        Bin width (m); default one automaton diameter.
    threshold : float
        Concentration defining penetration: upper-body material reaches
        ``penetration_upper_m`` below the original interface where its
        fitted fraction falls to ``threshold``; likewise lower-body
        material above it (fraction ``1 - threshold``).
    reference_frame : int
        Frame defining the bins and the original interface.
    n_windows : int
        Windows for the time-resolved mixed width (persistence).

    Attributes
    ----------
    results
        MDAnalysis ``Results`` holding the following fields.
    heights_m, upper_fraction, counts
        Bin centres (m), time-averaged upper-body fraction, automaton-frames.
    mixed_width_m
        10 %-90 % width of the upper-body fraction (m).
    penetration_upper_m, penetration_lower_m
        Depth (m) that each body reached into the other, at ``threshold``.
    interface_height_m
    window_time_s, window_mixed_width_m
    mixed_width_frame0_m, mixed_width_excess_m
        Width of the reference frame (the initial roughness, before any
        mixing) and ``mixed_width_m`` minus it.
    column_width_m, column_mixed_width_m, column_mixed_width_frame0_m
    mixed_width_columns_m, mixed_width_columns_err_m
        Per x column: the mixed width minus the same column's frame-0 width,
        averaged over the columns (standard error of the mean): neither the
        initial roughness nor a wavy interface counts as mixing.
    """

    def __init__(self, universe, meta: MCAMeta, *, bin_width_m=None, threshold=0.05,
                 reference_frame=0, n_windows=5, column_width_m=None, **kwargs):
        super().__init__(universe.trajectory, **kwargs)
        self._setup_bins(meta, bin_width_m, reference_frame, column_width_m)
        self._thr = check_range("threshold", threshold, 0.0, 0.5, lo_open=True, hi_open=True)
        self._n_windows = int(n_windows)

    def _prepare(self):
        self._prepare_bins()
        n = self.n_frames
        self._up = np.zeros((n, self._nb))
        self._all = np.zeros((n, self._nb))
        self._cup = np.zeros(self._ncol * self._nb)
        self._call = np.zeros(self._ncol * self._nb)
        self._time = np.zeros(n)
        # frame 0 (the reference): the initial roughness, before any mixing, in the same columns
        ts = self._trajectory[self._ref]
        h0 = ts.positions[:, self._axis].astype(float)
        up0 = np.isin(ts.data["mol"].astype(int), (MOL_UPPER, MOL_SLIDER))
        cb0 = self._col_bin_index(ts.positions[:, 0].astype(float), h0)
        self._cup0 = np.bincount(cb0[up0], None, self._ncol * self._nb)
        self._call0 = np.bincount(cb0, None, self._ncol * self._nb)
        b0 = self._bin_index(h0)
        self._up0 = np.bincount(b0[up0], None, self._nb)
        self._all0 = np.bincount(b0, None, self._nb)

    def _single_frame(self):
        ts = self._ts
        i = self._frame_index
        h = ts.positions[:, self._axis].astype(float)
        mol = ts.data["mol"].astype(int)
        b = self._bin_index(h)
        up = np.isin(mol, (MOL_UPPER, MOL_SLIDER))
        self._up[i] = np.bincount(b[up], None, self._nb)
        self._all[i] = np.bincount(b, None, self._nb)
        cb = self._col_bin_index(ts.positions[:, 0].astype(float), h)
        self._cup += np.bincount(cb[up], None, self._ncol * self._nb)
        self._call += np.bincount(cb, None, self._ncol * self._nb)
        self._time[i] = ts.time * 1e-12

    def _width(self, up, al) -> float:
        """10-90 % width (m) of the isotonic fit of one upper-fraction profile (counts per bin)."""
        keep = al > 0
        if keep.sum() < 2:
            return float("nan")
        fit = isotonic_fit(up[keep] / al[keep], al[keep])
        a, b = crossing_heights(self._centres_m[keep], fit, [0.1, 0.9])
        return float(b - a)

    def _fit(self, sl):
        up, al = self._up[sl].sum(axis=0), self._all[sl].sum(axis=0)
        frac = np.where(al > 0, up / np.maximum(al, 1), np.nan)
        keep = al > 0
        z = self._centres_m[keep]
        fit = isotonic_fit(frac[keep], al[keep])
        return frac, al, z, fit

    def _conclude(self):
        r = self.results
        y0 = self._y0_nm * NM
        frac, al, z, fit = self._fit(slice(None))
        z10, z90, zt_lo, zt_hi = crossing_heights(z, fit, [0.1, 0.9, self._thr, 1 - self._thr])
        r.heights_m = self._centres_m
        r.upper_fraction = frac
        r.counts = al
        r.interface_height_m = y0
        r.mixed_width_m = float(z90 - z10)
        r.penetration_upper_m = float(y0 - zt_lo)
        r.penetration_lower_m = float(zt_hi - y0)
        r.threshold = self._thr
        r.time_s = self._time
        wt, ww = [], []
        for sl in self._windows(self.n_frames, self._n_windows):
            _, _, zz, ff = self._fit(sl)
            a, b = crossing_heights(zz, ff, [0.1, 0.9])
            wt.append(self._time[sl].mean())
            ww.append(b - a)
        r.window_time_s = np.asarray(wt)
        r.window_mixed_width_m = np.asarray(ww)
        # the initial roughness: frame 0's width (x-averaged: the roughness itself; per column:
        # only the discretisation floor of a sharp step), subtracted from the mixed widths
        r.mixed_width_frame0_m = self._width(self._up0, self._all0)
        r.mixed_width_excess_m = r.mixed_width_m - r.mixed_width_frame0_m
        cu = self._cup.reshape(self._ncol, self._nb)
        ca = self._call.reshape(self._ncol, self._nb)
        cu0 = self._cup0.reshape(self._ncol, self._nb)
        ca0 = self._call0.reshape(self._ncol, self._nb)
        wc = np.array([self._width(cu[j], ca[j]) for j in range(self._ncol)])
        w0 = np.array([self._width(cu0[j], ca0[j]) for j in range(self._ncol)])
        r.column_width_m = self._column_width_m
        r.column_mixed_width_m = wc
        r.column_mixed_width_frame0_m = w0
        ex = wc - w0
        ok = np.isfinite(ex)
        r.columns_resolved = int(ok.sum())
        r.mixed_width_columns_m = float(ex[ok].mean()) if ok.any() else float("nan")
        r.mixed_width_columns_err_m = (
            float(ex[ok].std(ddof=1) / np.sqrt(ok.sum())) if ok.sum() > 1 else float("nan")
        )
        r.units = {
            "heights_m": "m",
            "upper_fraction": "1",
            "mixed_width_m": "m",
            "penetration_upper_m": "m",
            "penetration_lower_m": "m",
            "interface_height_m": "m",
            "time_s": "s",
            "mixed_width_frame0_m": "m",
            "mixed_width_excess_m": "m",
            "column_width_m": "m",
            "mixed_width_columns_m": "m",
            "mixed_width_columns_err_m": "m",
        }
