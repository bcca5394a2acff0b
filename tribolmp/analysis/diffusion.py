"""Lateral diffusion of surface automata in the frame of their own body."""

from __future__ import annotations

import numpy as np
from MDAnalysis.analysis.base import AnalysisBase

from ..errors import DataFileError, ParameterError
from ..params import check_range
from .outputs import MOL_BASE, MOL_LOWER, MOL_SLIDER, MOL_UPPER, NM, FromOutput, MCAMeta
from .profiles import interface_height
from .stats import linear_fit, msd_fft

__all__ = ["LateralDiffusion", "Unwrapper", "surface_selection"]


class Unwrapper:
    """Continuous (unwrapped) lateral coordinates across periodic boundaries.

    Each update adds the minimum-image displacement since the previous frame,
    which is exact as long as no automaton moves more than half a box length
    between two analysed frames.

    Parameters
    ----------
    x0 : ndarray, shape (N, k)
        Wrapped coordinates at the first frame.
    """

    def __init__(self, x0: np.ndarray):
        self.prev = np.array(x0, dtype=float)
        self.x = np.array(x0, dtype=float)

    def update(self, x: np.ndarray, lengths: np.ndarray) -> np.ndarray:
        """Advance to wrapped coordinates ``x`` in a box of edge ``lengths``; returns unwrapped."""
        x = np.asarray(x, dtype=float)
        d = x - self.prev
        d -= lengths * np.round(d / lengths)
        self.x += d
        self.prev = x
        return self.x


def surface_selection(heights, mols, y0, depth) -> np.ndarray:
    """Return indices of lower/upper-body automata within ``depth`` of the interface ``y0``."""
    heights = np.asarray(heights, dtype=float)
    mols = np.asarray(mols)
    near = np.abs(heights - y0) < depth
    return np.nonzero(near & np.isin(mols, (MOL_LOWER, MOL_UPPER)))[0]


class LateralDiffusion(FromOutput, AnalysisBase):
    """Lateral MSD of surface automata relative to their body; D from MSD = 2 n D t.

    Surface automata are those of the lower (mol 2) and upper (mol 3) bodies
    within ``surface_depth_m`` of the original interface in the first analysed
    frame.  Lateral coordinates are unwrapped across the periodic boundaries,
    and the body's motion is subtracted, so that the sliding of the upper body
    is not counted as diffusion.  ``n`` is the number of lateral dimensions (1
    in a 2D run, 2 in 3D).  The fit ``MSD(t) = 2 n D t + c`` over lag times in
    ``fit_range`` allows a constant ``c`` for the short-time vibration plateau.

    Parameters
    ----------
    universe : MDAnalysis.Universe
        From :func:`~tribolmp.analysis.outputs.open_trajectory`.
    meta : MCAMeta
        The run's metadata.
    surface_depth_m : float, optional
        Selection depth on each side of the interface (m); default 2 d.
    reference : {"group", "body", "anchor"}
        Frame of the body: the mean displacement of the selected surface
        automata of that body (default; removes the mean shear drift of the
        layer, with the exact finite-N correction N/(N-1)), of all automata of
        that body, or of its rigid anchor (base for the lower body, slider for
        the upper).
    fit_range : (float, float)
        Lag times used in the fit, as fractions of the analysed time span.
    exponent_range : (float, float)
        The MSD is diffusive when its log-slope over the fit window lies in
        this range (default 0.8-1.2) *and* the rms displacement at the end
        of the window exceeds one automaton diameter; otherwise
        ``diffusion_m2_s`` is NaN (``rates.json``: null) and
        ``diffusion_reason`` says why.  A slope near 2 is ballistic motion or
        shear dispersion (automata carried at different velocities by the
        sheared layer), which a linear fit would turn into a spurious D.

    Attributes
    ----------
    results
        MDAnalysis ``Results`` holding the following fields.
    lag_s, msd_m2
        Lag times (s) and the MSD of both bodies together (m^2).
    msd_lower_m2, msd_upper_m2
        Per-body MSDs (m^2).
    diffusion_m2_s, diffusion_err_m2_s
        D (m^2/s; NaN unless ``diffusive``) and half the difference of D
        fitted on the two halves of the run (a stationarity-aware error bar).
    diffusive, diffusion_reason, msd_exponent, rms_displacement_m, fit_window_s
        The regime test and its inputs; ``diffusion_fit_m2_s`` is the linear
        fit whatever the regime (diagnostic only).
    diffusion_lower_m2_s, diffusion_upper_m2_s
    n_surface, lateral_dims
    """

    def __init__(self, universe, meta: MCAMeta, *, surface_depth_m=None, reference="group",
                 fit_range=(0.0, 0.25), exponent_range=(0.8, 1.2), **kwargs):
        super().__init__(universe.trajectory, **kwargs)
        self._meta = meta
        depth = 2 * meta.automaton_diameter_m if surface_depth_m is None else surface_depth_m
        self._depth_nm = (
            check_range("surface_depth_m", depth, 0.0, None, lo_open=True, unit="m") / NM
        )
        if reference not in ("group", "body", "anchor"):
            raise ParameterError("reference", "one of ['group', 'body', 'anchor']", reference)
        self._reference = reference
        lo, hi = fit_range
        check_range("fit_range[0]", lo, 0.0, 1.0)
        check_range("fit_range[1]", hi, 0.0, 1.0, lo_open=True)
        if not lo < hi:
            raise ParameterError("fit_range", "lo < hi in [0, 1]", fit_range)
        self._fit_range = (float(lo), float(hi))
        a_lo, a_hi = exponent_range
        if not (0 < a_lo < 1 < a_hi):
            raise ParameterError("exponent_range", "lo < 1 < hi, lo > 0", exponent_range)
        self._alpha_range = (float(a_lo), float(a_hi))
        self._lat = list(meta.lateral_axes)

    def _prepare(self):
        ax = self._meta.normal_axis
        ts0 = self._trajectory[0]
        h0 = ts0.positions[:, ax].astype(float)
        mols0 = ts0.data["mol"].astype(int)
        self._y0 = interface_height(h0, mols0)
        self._unwrap = None
        self._time = np.zeros(self.n_frames)

    def _select(self, ts):
        """Pick the surface automata in the first analysed frame and allocate storage."""
        h = ts.positions[:, self._meta.normal_axis].astype(float)
        self._mols = ts.data["mol"].astype(int)
        self._sel = surface_selection(h, self._mols, self._y0, self._depth_nm)
        self._sel_mol = self._mols[self._sel]
        if min((self._sel_mol == MOL_LOWER).sum(), (self._sel_mol == MOL_UPPER).sum()) < 2:
            raise DataFileError(
                "trajectory: surface automata: expected >= 2 per "
                "body within surface_depth_m of the interface, "
                f"got {(self._sel_mol == MOL_LOWER).sum()} lower "
                f"and {(self._sel_mol == MOL_UPPER).sum()} upper"
            )
        n, k = self.n_frames, len(self._lat)
        self._xsel = np.zeros((n, self._sel.size, k))
        self._ref = {m: np.zeros((n, k)) for m in (MOL_LOWER, MOL_UPPER)}

    def _single_frame(self):
        ts = self._ts
        i = self._frame_index
        x = ts.positions[:, self._lat].astype(float)
        lengths = np.asarray(ts.dimensions[self._lat], dtype=float)
        if self._unwrap is None:
            self._select(ts)
            self._unwrap = Unwrapper(x)
            xu = self._unwrap.x
        else:
            xu = self._unwrap.update(x, lengths)
        self._xsel[i] = xu[self._sel]
        for body, anchor in ((MOL_LOWER, MOL_BASE), (MOL_UPPER, MOL_SLIDER)):
            if self._reference == "group":
                m = self._sel[self._sel_mol == body]
            elif self._reference == "body":
                m = np.nonzero(self._mols == body)[0]
            else:
                m = np.nonzero(self._mols == anchor)[0]
                if m.size == 0:
                    raise DataFileError(
                        f"trajectory: mol {anchor}: expected anchor "
                        "automata for reference='anchor', got none"
                    )
            self._ref[body][i] = xu[m].mean(axis=0)
        self._time[i] = ts.time * 1e-12

    def _msd(self, body, sl):
        m = self._sel_mol == body
        rel = self._xsel[sl][:, m, :] - self._ref[body][sl][:, None, :]
        msd = msd_fft(rel)
        n = int(m.sum())
        if self._reference == "group" and n > 1:
            # deviations from the group mean have variance (1 - 1/N) of the true one
            msd = msd * n / (n - 1)
        return msd * NM**2, n

    def _fit(self, lag, msd):
        use = self._window(lag)
        slope, _, _ = linear_fit(lag[use], msd[use])
        return slope / (2 * len(self._lat))

    def _window(self, lag):
        lo, hi = self._fit_range
        span = lag[-1] if lag.size else 0.0
        use = (lag > 0) & (lag >= lo * span) & (lag <= hi * span)
        if use.sum() < 2:
            use = lag > 0
            use &= np.cumsum(use) <= 2
        return use

    def _regime(self, lag, msd):
        """Return the MSD regime over the fit window.

        (log-slope of MSD against lag, rms displacement at the window's end (m), window (s)).
        """
        use = self._window(lag) & (msd > 0)
        if use.sum() < 2:
            return float("nan"), float("nan"), [float("nan"), float("nan")]
        alpha, _, _ = linear_fit(np.log(lag[use]), np.log(msd[use]))
        last = np.nonzero(use)[0][-1]
        return float(alpha), float(np.sqrt(msd[last])), [float(lag[use][0]), float(lag[last])]

    def _conclude(self):
        r = self.results
        T = self.n_frames
        if T < 4:
            raise DataFileError(
                f"trajectory: frames: expected >= 4 analysed frames for an MSD, got {T}"
            )
        lag = self._time[:T] - self._time[0]
        out = {}
        for body, name in ((MOL_LOWER, "lower"), (MOL_UPPER, "upper")):
            msd, n = self._msd(body, slice(None))
            out[name] = (msd, n)
        n_l, n_u = out["lower"][1], out["upper"][1]
        msd_all = (out["lower"][0] * n_l + out["upper"][0] * n_u) / (n_l + n_u)
        D = self._fit(lag, msd_all)
        halves = []
        for sl in (slice(0, T // 2), slice(T // 2, T)):
            lag_h = self._time[sl] - self._time[sl][0]
            ml, _ = self._msd(MOL_LOWER, sl)
            mu, _ = self._msd(MOL_UPPER, sl)
            halves.append(self._fit(lag_h, (ml * n_l + mu * n_u) / (n_l + n_u)))
        alpha, rms, window = self._regime(lag, msd_all)
        d = self._meta.automaton_diameter_m
        reasons = []
        if not (np.isfinite(alpha) and self._alpha_range[0] <= alpha <= self._alpha_range[1]):
            reasons.append(
                f"MSD grows as t^{alpha:.2f} over the fit window (diffusion needs an exponent in "
                f"[{self._alpha_range[0]:g}, {self._alpha_range[1]:g}]; "
                "> 1.2: ballistic or shear dispersion)"
            )
        if not rms > d:
            reasons.append(
                f"rms displacement {rms:.3g} m at the end of the fit window is below one automaton "
                f"diameter {d:.3g} m (no escape from the cage)"
            )
        r.lag_s = lag
        r.msd_m2 = msd_all
        r.msd_lower_m2 = out["lower"][0]
        r.msd_upper_m2 = out["upper"][0]
        r.msd_exponent = float(alpha)
        r.rms_displacement_m = float(rms)
        r.fit_window_s = window
        r.diffusive = not reasons
        r.diffusion_reason = "; ".join(reasons)
        r.diffusion_fit_m2_s = float(D)
        r.diffusion_m2_s = float(D) if r.diffusive else float("nan")
        r.diffusion_err_m2_s = float(abs(halves[0] - halves[1]) / 2)
        r.diffusion_lower_m2_s = float(self._fit(lag, out["lower"][0]))
        r.diffusion_upper_m2_s = float(self._fit(lag, out["upper"][0]))
        r.n_surface = int(self._sel.size)
        r.lateral_dims = len(self._lat)
        r.interface_height_m = self._y0 * NM
        r.reference = self._reference
        r.units = {
            "lag_s": "s",
            "msd_m2": "m^2",
            "diffusion_m2_s": "m^2/s",
            "diffusion_err_m2_s": "m^2/s",
        }
