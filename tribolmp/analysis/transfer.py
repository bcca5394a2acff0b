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
*lower* (< V/3), *layer* (V/3 ... 2V/3) or *upper* (> 2V/3).  A state is
only a change of *membership* when it persists: an automaton's membership
changes to a new state at the first frame of a run of that state lasting at
least the persistence time (default: the time the slider takes to move two
automaton diameters).  Vibrations, a passing asperity or the washboard of two
lattices flip the instantaneous state for a few frames; they are not
transfer.  From the membership changes:

* transfer: an automaton becomes a member of the *other* body (directly or
  through the layer);
* detachment: it stops being a member of its own body; return: it becomes a
  member of its own body again;
* wear: the net loss of each body's material, N_members(start) -
  N_members(end), with its counting error sqrt(n_out + n_in) (Poisson; the
  one-event resolution 1 when nothing was counted).

Rates are counts per unit time and per unit sliding distance, with counting
(Poisson) errors sqrt(n).  None is derived from another by an identity.

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
from .outputs import LINK_COLUMNS, MOL_LOWER, MOL_SLIDER, MOL_UPPER, NM, FromOutput, MCAMeta
from .profiles import interface_height

__all__ = [
    "BondTurnover",
    "MassTransfer",
    "STATE_LOWER",
    "STATE_LAYER",
    "STATE_UPPER",
    "count_events",
    "persistent_membership",
    "counting_rate",
]

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
        r.units = {
            "time_s": "s",
            "broken_per_s": "1/s",
            "formed_per_s": "1/s",
            "break_rate_per_link": "1/s",
        }


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


def persistent_membership(states: np.ndarray, own: np.ndarray, persistence: int) -> np.ndarray:
    """Membership of each automaton: the state of its latest run lasting >= ``persistence`` frames.

    Parameters
    ----------
    states : ndarray of int, shape (T, N)
        Instantaneous states per frame.
    own : ndarray of int, shape (N,)
        Initial membership (each automaton's own body).
    persistence : int
        Frames a state must hold, uninterrupted, to become the membership.
        A run still going at the last frame counts only if it already lasted
        that long (a change must have *persisted*, not merely begun).

    Returns
    -------
    ndarray of int, shape (T, N)
        Membership per frame; it changes at the first frame of a persistent run.
    """
    states = np.asarray(states)
    T, N = states.shape
    P = max(1, int(persistence))
    run = np.ones((T, N), dtype=np.int64)  # length of the run of equal states starting at t
    for t in range(T - 2, -1, -1):
        run[t] = np.where(states[t] == states[t + 1], run[t + 1] + 1, 1)
    start = np.ones((T, N), dtype=bool)
    start[1:] = states[1:] != states[:-1]
    accepted = start & (run >= P)
    idx = np.where(accepted, np.arange(T)[:, None], -1)
    last = np.maximum.accumulate(idx, axis=0)
    cols = np.broadcast_to(np.arange(N), (T, N))
    return np.where(last >= 0, states[np.clip(last, 0, None), cols], np.asarray(own)[None, :])


def counting_rate(n: float, exposure: float) -> tuple[float, float]:
    """Rate n/exposure and its Poisson error sqrt(max(n, 1))/exposure (NaN when exposure <= 0).

    With nothing counted the error is the one-event resolution of the
    exposure, not zero: a run of that length could not have told 0 from 1.
    """
    if not exposure > 0:
        return float("nan"), float("nan")
    return float(n) / exposure, math.sqrt(max(abs(float(n)), 1.0)) / exposure


class MassTransfer(FromOutput, AnalysisBase):
    """Transfer between the bodies and wear from persistent changes of membership.

    Parameters
    ----------
    universe : MDAnalysis.Universe
        From :func:`~tribolmp.analysis.outputs.open_trajectory`.
    meta : MCAMeta
        The run's metadata.
    window : int, optional
        Frames over which an automaton's velocity is averaged before it is
        classified; default: enough frames for the slider to move one
        automaton diameter, but at most a third of the analysed frames
        (``results.window_limited``).
    persistence_s : float, optional
        Time a new state must hold, uninterrupted, to count as a change of
        membership (s).  Default: the time the slider takes to move two
        automaton diameters, at least ``window`` frames and at most a quarter
        of the analysed span (``results.persistence_limited``).
    surface_depth_m : float, optional
        Depth on each side of the original interface defining the surface
        automata that normalise ``transfer_rate`` (m); default 2 d.

    Attributes
    ----------
    results
        MDAnalysis ``Results`` holding the following fields.
    time_s, span_s, sliding_distance_m
        Times of the classified frames (s), their span (s) and the slider
        displacement over them (m).
    window, persistence_frames, persistence_s
    n_surface
        Surface automata N_s (normalisation of ``transfer_rate``).
    states, membership
        (T, N) instantaneous state and persistent membership per classified
        frame for the automata of both bodies (mol 2, 3).
    transfer_events, return_events, detach_events
        Membership changes into the other body, back into the own body, and
        out of the own body.
    transfer_per_s, transfer_per_s_err, transfer_per_m, transfer_per_m_err
        Transfer events per second and per metre slid, Poisson errors.
    transfer_rate
        Transfers per surface automaton per metre slid (1/m).
    net_transfer_lower_to_upper
        Lower-body automata that are members of the upper body at the end
        minus at the start, minus the same for upper-body automata in the lower.
    wear_lower, wear_upper
        Net loss of members of each body over the span (automata).
    wear_lower_per_s, wear_lower_per_m (and _err), wear_upper_per_s, wear_upper_per_m (and _err)
        Net loss per second and per metre slid (automata/s, automata/m).
    wear_lower_kg_per_m, wear_upper_kg_per_m
        The same in mass, when the automaton mass is known.
    crossed_lower_up, crossed_upper_down
        Per frame: automata beyond the original interface by more than half
        a diameter, minus that number in the reference frame.
    """

    def __init__(
        self,
        universe,
        meta: MCAMeta,
        *,
        window=None,
        persistence_s=None,
        surface_depth_m=None,
        **kwargs,
    ):
        super().__init__(universe.trajectory, **kwargs)
        self._meta = meta
        self._auto_window = window is None
        if window is None:
            step = meta.velocity_m_s * meta.dump_interval_s
            window = max(1, math.ceil(meta.automaton_diameter_m / step))
        self._w = check_int("window", window, 1)
        self._auto_persist = persistence_s is None
        if persistence_s is None:
            persistence_s = 2 * meta.automaton_diameter_m / meta.velocity_m_s
        self._persist_s = check_range("persistence_s", persistence_s, 0.0, None, unit="s")
        depth = 2 * meta.automaton_diameter_m if surface_depth_m is None else surface_depth_m
        self._depth_nm = (
            check_range("surface_depth_m", depth, 0.0, None, lo_open=True, unit="m") / NM
        )

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
        self._linked = None

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
        cross = next((ts.data[c] for c in LINK_COLUMNS["n_cross_body_links"] if c in ts.data), None)
        links = next(
            (ts.data[c] for c in LINK_COLUMNS["n_links"] if c in ts.data), ts.data.get("c_nbond")
        )
        if cross is not None and links is not None:
            if self._linked is None:
                self._linked = np.zeros((self.n_frames, self._body.size), dtype=bool)
            c = np.rint(np.asarray(cross)[self._body])
            own = np.rint(np.asarray(links)[self._body]) - c
            # linked to the other body: more of its links go there than stay in its own body
            self._linked[i] = c > own
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
            raise DataFileError(
                "trajectory: frames: expected more than "
                f"window+1 = {w + 1} analysed frames, got {T}"
            )
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
        r.membership_source = "velocity"
        if self._linked is not None:
            # the mca law dumps each automaton's links to the other body:
            # linked there = in the other body, whatever its velocity (an
            # automaton welded to the counter-body but momentarily at rest)
            other_state = np.where(self._own == STATE_LOWER, STATE_UPPER, STATE_LOWER).astype(
                np.int8
            )
            linked = self._linked[w:]
            states = np.where(linked, other_state[None, :], states)
            r.membership_source = "velocity and links to the other body"
        t = self._time[w:]
        span = float(t[-1] - t[0])
        frame_dt = float(np.median(np.diff(t))) if t.size > 1 else float("nan")
        P = (
            max(w, int(math.ceil(self._persist_s / frame_dt - 1e-9)))
            if np.isfinite(frame_dt) and frame_dt > 0
            else w
        )
        r.persistence_limited = False
        if self._auto_persist and P > max(1, states.shape[0] // 4):
            P = max(1, states.shape[0] // 4)
            r.persistence_limited = True
        mem = persistent_membership(states, self._own, P)
        own = self._own[None, :]
        other = np.where(self._own == STATE_LOWER, STATE_UPPER, STATE_LOWER)[None, :]
        a, b = mem[:-1], mem[1:]
        changed = a != b
        n_transfer = int((changed & (b == other)).sum())
        n_return = int((changed & (b == own)).sum())
        n_detach = int((changed & (a == own)).sum())
        ns = max(self._n_surface, 1)
        lo_in_up = ((mem == STATE_UPPER) & self._is_lower[None, :]).sum(axis=1)
        up_in_lo = ((mem == STATE_LOWER) & ~self._is_lower[None, :]).sum(axis=1)
        r.time_s = t
        r.span_s = span
        r.sliding_distance_m = distance
        r.window = w
        r.persistence_frames = int(P)
        r.persistence_s = float(P * frame_dt) if np.isfinite(frame_dt) else float("nan")
        r.n_surface = int(self._n_surface)
        r.states = states
        r.membership = mem
        r.transfer_events = n_transfer
        r.return_events = n_return
        r.detach_events = n_detach
        r.transfer_per_s, r.transfer_per_s_err = counting_rate(n_transfer, span)
        r.transfer_per_m, r.transfer_per_m_err = counting_rate(n_transfer, distance)
        r.transfer_rate, r.transfer_rate_err = counting_rate(n_transfer, ns * distance)
        r.net_transfer_lower_to_upper = int(
            (lo_in_up[-1] - lo_in_up[0]) - (up_in_lo[-1] - up_in_lo[0])
        )
        r.transferred_lower_to_upper = lo_in_up
        r.transferred_upper_to_lower = up_in_lo
        d = self._meta.automaton_diameter_m
        m_auto = self._meta.raw.get("automaton_mass_kg")
        if m_auto is None and self._meta.density_kg_m3:
            vol = math.pi * d**2 / 4 * d if self._meta.dimension == 2 else math.pi * d**3 / 6
            m_auto = self._meta.density_kg_m3 * vol
        r.automaton_mass_kg = float(m_auto) if m_auto else float("nan")
        for state, name in ((STATE_LOWER, "lower"), (STATE_UPPER, "upper")):
            members = (mem == state).sum(axis=1)
            n_out = int((changed & (a == state)).sum())
            n_in = int((changed & (b == state)).sum())
            loss = int(members[0] - members[-1])
            r[f"wear_{name}"] = loss
            r[f"wear_{name}_out_events"] = n_out
            r[f"wear_{name}_in_events"] = n_in
            for unit, exposure in (("s", span), ("m", distance)):
                if exposure > 0:
                    r[f"wear_{name}_per_{unit}"] = loss / exposure
                    r[f"wear_{name}_per_{unit}_err"] = math.sqrt(max(n_in + n_out, 1)) / exposure
                else:
                    r[f"wear_{name}_per_{unit}"] = r[f"wear_{name}_per_{unit}_err"] = float("nan")
            r[f"wear_{name}_kg_per_m"] = r[f"wear_{name}_per_m"] * r.automaton_mass_kg
            r[f"wear_{name}_kg_per_m_err"] = r[f"wear_{name}_per_m_err"] * r.automaton_mass_kg
        r.crossed_lower_up = self._crossed[:, 0]
        r.crossed_upper_down = self._crossed[:, 1]
        r.interface_height_m = self._y0 * NM
        r.units = {
            "time_s": "s",
            "span_s": "s",
            "sliding_distance_m": "m",
            "persistence_s": "s",
            "transfer_per_s": "1/s",
            "transfer_per_m": "1/m",
            "transfer_rate": "1/m",
            "wear_lower_per_s": "1/s",
            "wear_lower_per_m": "1/m",
            "wear_upper_per_s": "1/s",
            "wear_upper_per_m": "1/m",
            "wear_lower_kg_per_m": "kg/m",
            "wear_upper_kg_per_m": "kg/m",
            "automaton_mass_kg": "kg",
        }
