"""Link turnover and mass transfer between the bodies of an MCA run.

:class:`BondTurnover` counts links broken and formed from the per-automaton
bond counts (``c_nbond``, from ``compute nbond/atom``).  Every link changes
the count of its two automata, so between two frames

    broken >= -sum(min(dn, 0)) / 2,    formed >= sum(max(dn, 0)) / 2,

with equality when no automaton both lost and gained links in the interval
(otherwise the two cancel in its count).  The counts are therefore lower
bounds, tighter for more frequent dumps.

:class:`MassTransfer` classifies each automaton of the two bodies, frame by
frame, by the body it moves with: its lateral velocity, averaged over a
window, relative to the slider's velocity V over the same window, is
*lower* (< V/3), *layer* (V/3 ... 2V/3) or *upper* (> 2V/3).  A lower-body
automaton that ends up moving with the upper body has been transferred (and
vice versa).  From the state changes:

* detachment: an automaton leaves the body it moved with;
* reattachment: an automaton joins a body (from the layer or the other body);
* transfer: an automaton joins the *other* body.

It also counts automata that crossed the original interface (position-based
mixing, independent of the velocity classification).
"""

from __future__ import annotations

import math

import numpy as np
from MDAnalysis.analysis.base import AnalysisBase

from ..errors import DataFileError
from ..params import check_int, check_range
from .diffusion import Unwrapper, surface_selection
from .outputs import MOL_LOWER, MOL_SLIDER, MOL_UPPER, NM, FromOutput, MCAMeta
from .profiles import interface_height

__all__ = ["BondTurnover", "MassTransfer", "STATE_LOWER", "STATE_LAYER", "STATE_UPPER", "count_events"]

#: Velocity states of an automaton.
STATE_LOWER, STATE_LAYER, STATE_UPPER = 0, 1, 2


class BondTurnover(FromOutput, AnalysisBase):
    """Links broken and formed per interval, from changes of ``c_nbond``.

    Parameters
    ----------
    universe : MDAnalysis.Universe
        From :func:`~tribolmp.analysis.outputs.open_trajectory`.
    meta : MCAMeta
        The run's metadata.

    Attributes
    ----------
    results
        MDAnalysis ``Results`` holding the following fields.
    time_s, bonds
        Frame times (s) and the number of links (sum of c_nbond / 2).
    broken, formed
        Links broken / formed in each interval (lower bounds), length T-1.
    broken_total, formed_total
    broken_per_s, formed_per_s
        Turnover (links/s) over the analysed span.
    break_rate_per_link
        ``broken_per_s`` divided by the mean number of links (1/s).
    """

    def __init__(self, universe, meta: MCAMeta, **kwargs):
        super().__init__(universe.trajectory, **kwargs)
        self._meta = meta

    def _prepare(self):
        n = self.n_frames
        self._time = np.zeros(n)
        self._bonds = np.zeros(n)
        self._broken = np.zeros(max(n - 1, 0))
        self._formed = np.zeros(max(n - 1, 0))
        self._prev = None

    def _single_frame(self):
        ts = self._ts
        i = self._frame_index
        nb = np.rint(ts.data["c_nbond"]).astype(np.int64)
        self._time[i] = ts.time * 1e-12
        self._bonds[i] = nb.sum() / 2
        if self._prev is not None:
            dn = nb - self._prev
            self._broken[i - 1] = -dn[dn < 0].sum() / 2
            self._formed[i - 1] = dn[dn > 0].sum() / 2
        self._prev = nb

    def _conclude(self):
        r = self.results
        span = self._time[-1] - self._time[0] if self.n_frames > 1 else 0.0
        r.time_s = self._time
        r.bonds = self._bonds
        r.broken = self._broken
        r.formed = self._formed
        r.broken_total = float(self._broken.sum())
        r.formed_total = float(self._formed.sum())
        r.broken_per_s = r.broken_total / span if span > 0 else float("nan")
        r.formed_per_s = r.formed_total / span if span > 0 else float("nan")
        mean_links = float(self._bonds.mean()) if self.n_frames else 0.0
        r.break_rate_per_link = r.broken_per_s / mean_links if mean_links > 0 else float("nan")
        r.units = {"time_s": "s", "broken_per_s": "1/s", "formed_per_s": "1/s", "break_rate_per_link": "1/s"}


def count_events(states: np.ndarray, own: np.ndarray) -> dict[str, np.ndarray]:
    """Count state changes of automata between consecutive frames.

    Parameters
    ----------
    states : ndarray of int, shape (T, N)
        :data:`STATE_LOWER`, :data:`STATE_LAYER` or :data:`STATE_UPPER` per frame.
    own : ndarray of int, shape (N,)
        The state of each automaton's own body (lower or upper).

    Returns
    -------
    dict
        Per interval (length T-1): ``detach`` (left a body state),
        ``reattach`` (entered a body state), ``transfer`` (entered the other
        body's state), ``returned`` (entered its own body's state from elsewhere).
    """
    a, b = states[:-1], states[1:]
    changed = a != b
    body = lambda s: s != STATE_LAYER  # noqa: E731
    other = np.where(own == STATE_LOWER, STATE_UPPER, STATE_LOWER)
    return {
        "detach": (changed & body(a)).sum(axis=1),
        "reattach": (changed & body(b)).sum(axis=1),
        "transfer": (changed & (b == other[None, :])).sum(axis=1),
        "returned": (changed & (b == own[None, :])).sum(axis=1),
    }


class MassTransfer(FromOutput, AnalysisBase):
    """Transfer, detachment and reattachment of automata between the bodies.

    Parameters
    ----------
    universe : MDAnalysis.Universe
        From :func:`~tribolmp.analysis.outputs.open_trajectory`.
    meta : MCAMeta
        The run's metadata.
    window : int, optional
        Frames over which an automaton's velocity is averaged before it is
        classified; default: enough frames for the slider to move one
        automaton diameter (so that vibration does not flip states), but at
        most a third of the analysed frames (``results.window_limited``).
        Events shorter than the window are missed: the counts are lower bounds.
    surface_depth_m : float, optional
        Depth on each side of the original interface defining the surface
        automata that normalise the rates (m); default 2 d.

    Attributes
    ----------
    results
        MDAnalysis ``Results`` holding the following fields.
    time_s, sliding_distance_m
        Times of the classified frames (s), slider displacement over them (m).
    n_surface
        Surface automata N_s (normalisation).
    states
        (T, N) state per classified frame for the automata of both bodies.
    transferred_lower_to_upper, transferred_upper_to_lower
        Per frame: lower-body automata moving with the upper body, and vice versa.
    detach_events, reattach_events, transfer_events, return_events
    detachment_rate
        Detachments per surface automaton per second (1/s).
    reattachment_rate
        Reattachments per detached (layer) automaton per second (1/s).
    transfer_rate
        Transfers per surface automaton per metre of sliding (1/m).
    net_transfer_rate
        Net growth of (lower-in-upper minus upper-in-lower) per surface
        automaton per metre (1/m, signed).
    wear_rate
        ``transfer_rate * V``: transfers per surface automaton per second (1/s).
    crossed_lower_up, crossed_upper_down
        Per frame: automata beyond the original interface by more than half
        a diameter, minus that number in the reference frame.
    """

    def __init__(self, universe, meta: MCAMeta, *, window=None, surface_depth_m=None, **kwargs):
        super().__init__(universe.trajectory, **kwargs)
        self._meta = meta
        self._auto_window = window is None
        if window is None:
            step = meta.velocity_m_s * meta.dump_interval_s
            window = max(1, math.ceil(meta.automaton_diameter_m / step))
        self._w = check_int("window", window, 1)
        depth = 2 * meta.automaton_diameter_m if surface_depth_m is None else surface_depth_m
        self._depth_nm = check_range("surface_depth_m", depth, 0.0, None, lo_open=True, unit="m") / NM

    def _prepare(self):
        ax = self._meta.normal_axis
        ts0 = self._trajectory[0]
        h0 = ts0.positions[:, ax].astype(float)
        mols = ts0.data["mol"].astype(int)
        self._y0 = interface_height(h0, mols)
        self._body = np.nonzero(np.isin(mols, (MOL_LOWER, MOL_UPPER)))[0]
        self._slider = np.nonzero(mols == MOL_SLIDER)[0]
        self._own = np.where(mols[self._body] == MOL_LOWER, STATE_LOWER, STATE_UPPER)
        self._is_lower = mols[self._body] == MOL_LOWER
        self._n_surface = surface_selection(h0, mols, self._y0, self._depth_nm).size
        n = self.n_frames
        self._time = np.zeros(n)
        self._xs = np.zeros((n, self._body.size))  # unwrapped sliding coordinate (nm)
        self._xslider = np.full(n, np.nan)
        self._crossed = np.zeros((n, 2))
        self._crossed0 = self._count_crossed(h0, mols)
        self._unwrap = None

    def _count_crossed(self, h, mols):
        half = 0.5 * self._meta.automaton_diameter_m / NM
        up = ((mols == MOL_LOWER) & (h > self._y0 + half)).sum()
        down = ((mols == MOL_UPPER) & (h < self._y0 - half)).sum()
        return np.array([up, down], dtype=float)

    def _single_frame(self):
        ts = self._ts
        i = self._frame_index
        x = ts.positions[:, 0:1].astype(float)  # sliding direction is x
        L = np.asarray(ts.dimensions[0:1], dtype=float)
        if self._unwrap is None:
            self._unwrap = Unwrapper(x)
            xu = self._unwrap.x
        else:
            xu = self._unwrap.update(x, L)
        self._xs[i] = xu[self._body, 0]
        if self._slider.size:
            self._xslider[i] = xu[self._slider, 0].mean()
        self._time[i] = ts.time * 1e-12
        h = ts.positions[:, self._meta.normal_axis].astype(float)
        self._crossed[i] = self._count_crossed(h, ts.data["mol"].astype(int)) - self._crossed0

    def _conclude(self):
        r = self.results
        T = self.n_frames
        r.window_limited = False
        if self._auto_window and self._w > max(1, T // 3):
            # a short run: classify over a third of it rather than not at all
            self._w = max(1, T // 3)
            r.window_limited = True
        w = self._w
        if T <= w + 1:
            raise DataFileError(f"trajectory: frames: expected more than window+1 = {w + 1} analysed frames, got {T}")
        dt = self._time[w:] - self._time[:-w]
        u = (self._xs[w:] - self._xs[:-w]) * NM / dt[:, None]  # m/s, shape (T-w, N)
        if np.isfinite(self._xslider).all():
            vs = (self._xslider[w:] - self._xslider[:-w]) * NM / dt
            distance = float((self._xslider[-1] - self._xslider[w]) * NM)
        else:
            vs = np.full(T - w, self._meta.velocity_m_s)
            distance = float(self._meta.velocity_m_s * (self._time[-1] - self._time[w]))
        vs = np.where(vs > 0, vs, self._meta.velocity_m_s)
        states = np.full(u.shape, STATE_LAYER, dtype=np.int8)
        states[u < vs[:, None] / 3] = STATE_LOWER
        states[u > 2 * vs[:, None] / 3] = STATE_UPPER
        ev = count_events(states, self._own)
        t = self._time[w:]
        span = float(t[-1] - t[0])
        ns = max(self._n_surface, 1)
        layer_pop = float((states == STATE_LAYER).sum(axis=1).mean())
        lo_in_up = ((states == STATE_UPPER) & self._is_lower[None, :]).sum(axis=1)
        up_in_lo = ((states == STATE_LOWER) & ~self._is_lower[None, :]).sum(axis=1)
        net = float((lo_in_up[-1] - lo_in_up[0]) - (up_in_lo[-1] - up_in_lo[0]))
        r.time_s = t
        r.sliding_distance_m = distance
        r.window = w
        r.n_surface = int(self._n_surface)
        r.states = states
        r.transferred_lower_to_upper = lo_in_up
        r.transferred_upper_to_lower = up_in_lo
        r.layer_population = float(layer_pop)
        for key in ("detach", "reattach", "transfer", "returned"):
            r[f"{key}_events"] = int(ev[key].sum())
        r.detachment_rate = r.detach_events / (ns * span) if span > 0 else float("nan")
        r.reattachment_rate = r.reattach_events / (layer_pop * span) if (span > 0 and layer_pop > 0) else float("nan")
        r.transfer_rate = r.transfer_events / (ns * distance) if distance > 0 else float("nan")
        r.net_transfer_rate = net / (ns * distance) if distance > 0 else float("nan")
        r.wear_rate = r.transfer_rate * (distance / span) if span > 0 else float("nan")
        r.crossed_lower_up = self._crossed[:, 0]
        r.crossed_upper_down = self._crossed[:, 1]
        r.interface_height_m = self._y0 * NM
        d = self._meta.automaton_diameter_m
        if self._meta.density_kg_m3:
            m = self._meta.density_kg_m3 * math.pi * d**3 / 6
            r.automaton_mass_kg = m
            r.transferred_mass_kg_per_m = r.transfer_events * m / distance if distance > 0 else float("nan")
        r.units = {"time_s": "s", "sliding_distance_m": "m", "detachment_rate": "1/s", "reattachment_rate": "1/s",
                   "transfer_rate": "1/m", "net_transfer_rate": "1/m", "wear_rate": "1/s",
                   "automaton_mass_kg": "kg", "transferred_mass_kg_per_m": "kg/m"}
