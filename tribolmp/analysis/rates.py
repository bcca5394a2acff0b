"""``rates.json``: the nanoscale rates that parameterise the continuum models, as measurements.

:func:`compute_rates` runs every analysis of :mod:`tribolmp.analysis` on an
MCA output directory, writes the lower body's surface profile
``profile.npz`` (contract C1) and ``rates.json`` (SI; ``units``,
``definitions``, ``conditions`` and ``provenance`` inside).

Every value is a measurement with its error, or ``null`` with the reason in
``warnings`` (and, for the diffusion and Eq. 23 coefficients, a field of its
own).  No rate is derived from another rate by an identity: the former
``wear_rate = transfer_rate * V`` and ``step_time_s = l^2 / D`` are gone.

``mu``, ``mu_err``
    :class:`~tribolmp.analysis.friction.FrictionCoefficient`.
``mu_per_s``, ``d0_m2_s``, ``dz``, ``dx_l2`` (+ ``_err``, ``valid``, ``modes_used``)
    The Eq. 23 coefficients of the lower body's profile h(x, t)
    (:mod:`~tribolmp.analysis.eq23`); the whole fit is under ``eq23``.
``diffusion_m2_s``
    Lateral diffusion of surface automata, only in the diffusive regime
    (:class:`~tribolmp.analysis.diffusion.LateralDiffusion`).
``transfer_*``, ``cross_body_links_*``
    Persistent changes of membership to the other body
    (:class:`~tribolmp.analysis.transfer.MassTransfer`), and links formed and
    broken between the bodies when the run's law counts them (C2).
``wear_lower_*``, ``wear_upper_*``
    Net loss of each body's material.
``layer_depth_m``, ``mixed_width_m``
    Per x column, then averaged; the mixed width has the frame-0 width
    subtracted.
"""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import DataFileError
from ..jsonio import finite_or_none, jsonable
from ..records import Rates
from .outputs import read_friction_csv, read_meta

__all__ = ["compute_rates", "RATES_UNITS", "steady_frames"]

#: Unit of every numeric field of rates.json: the shared record's fields (tribolmp.records.Rates)
#: plus the analysis's own diagnostics.
RATES_UNITS = {
    **Rates.units(),
    "layer_depth_err_m": "m",
    "layer_depth_xavg_m": "m",
    "layer_offset_m": "m",
    "mixed_width_m": "m",
    "mixed_width_err_m": "m",
    "mixed_width_frame0_m": "m",
    "mixed_width_xavg_m": "m",
    "penetration_upper_m": "m",
    "penetration_lower_m": "m",
    "diffusion_err_m2_s": "m^2/s",
    "diffusion_exponent": "1",
    "diffusion_rms_m": "m",
    "transfer_rate_err": "1/m",
    "transfer_per_s": "1/s",
    "transfer_per_s_err": "1/s",
    "transfer_per_m": "1/m",
    "transfer_per_m_err": "1/m",
    "transfer_persistence_s": "s",
    "cross_body_links_formed_per_s": "1/s",
    "cross_body_links_formed_per_s_err": "1/s",
    "cross_body_links_formed_per_m": "1/m",
    "cross_body_links_formed_per_m_err": "1/m",
    "cross_body_links_broken_per_s": "1/s",
    "cross_body_links_broken_per_s_err": "1/s",
    "cross_body_links_broken_per_m": "1/m",
    "cross_body_links_broken_per_m_err": "1/m",
    "wear_lower_per_s": "1/s",
    "wear_lower_per_s_err": "1/s",
    "wear_lower_per_m": "1/m",
    "wear_lower_per_m_err": "1/m",
    "wear_upper_per_s": "1/s",
    "wear_upper_per_s_err": "1/s",
    "wear_upper_per_m": "1/m",
    "wear_upper_per_m_err": "1/m",
    "wear_lower_kg_per_m": "kg/m",
    "wear_lower_kg_per_m_err": "kg/m",
    "wear_upper_kg_per_m": "kg/m",
    "wear_upper_kg_per_m_err": "kg/m",
    "links_broken_per_s": "1/s",
    "links_broken_per_s_err": "1/s",
    "links_formed_per_s": "1/s",
    "links_formed_per_s_err": "1/s",
    "link_break_rate": "1/s",
    "link_break_rate_err": "1/s",
    "time_s": "s",
    "steady_start_s": "s",
    "mu_window_start_s": "s",
    "mu_n_independent": "1",
    "analysis_start_s": "s",
    "analysis_span_s": "s",
    "sliding_distance_m": "m",
    "velocity_m_s": "m/s",
}

#: Names that must never appear in rates.json: they were identities of other rates.
REMOVED_IDENTITIES = (
    "wear_rate",
    "step_time_s",
    "detachment_rate",
    "reattachment_rate",
    "net_transfer_rate",
)

#: C2 global tallies looked for in friction.csv (cumulative counts), by exact column name or suffix.
C2_TALLIES = (
    "cross_body_links_formed",
    "cross_body_links_broken",
    "cross_body_links_current",
    "links_total",
    "links_broken",
    "welds_formed",
)

#: What every field means (copied into rates.json).
DEFINITIONS = {
    "mu": (
        "sum F_t / sum F_n over the window starting at "
        "mu_window_start_s: the MSER-5 steady start when mu_steady "
        "(mu_estimator 'steady_mean'), else the second half "
        "of the run ('second_half_mean', NOT steady); mu_err: "
        "blocking standard error, widened to half the "
        "difference of the window's halves when not steady"
    ),
    "mu_per_s, d0_m2_s, dz, dx_l2": (
        "Eq. 23 coefficients of the lower body's column-mass profile h(x, t) "
        "(profile.npz) after analysis_start_s: per Fourier mode gamma(k) from the "
        "autocovariance (lags 1 and ~1/gamma) and S(k) extrapolated to lag 0; WLS fits "
        "gamma = mu + D0 k^2 and S gamma = Dz + Dx l^2 k^2; jackknife errors; null "
        "unless valid (reasons in eq23.reasons)"
    ),
    "diffusion_m2_s": (
        "MSD = 2 n D t of surface automata relative to "
        "their body, n lateral dims, only when the MSD's "
        "log-slope over the fit window is within 0.8-1.2 "
        "and its rms exceeds one automaton diameter; "
        "else null (diffusion_exponent, diffusion_reason)"
    ),
    "transfer_events": (
        "membership changes of body automata into the other body; membership = the velocity state "
        "(lower < V/3 < layer < 2V/3 < upper, velocity averaged over transfer_window_frames; the "
        "other body's state when the dump's mca-law columns show most of the automaton's links "
        "going to the other body) of the latest run lasting >= transfer_persistence_s"
    ),
    "transfer_per_s, transfer_per_m": (
        "transfer_events per analysed second / per metre slid; errors sqrt(n) (>= 1 event)"
    ),
    "transfer_rate": "transfer_events per surface automaton per metre slid",
    "cross_body_links_formed": (
        "links formed between automata of different bodies (different molecule ids) over the "
        "whole run, from the law's cumulative tally (C2) in friction.csv; null when the law "
        "does not count them"
    ),
    "cross_body_links_formed_per_s, _per_m": (
        "the same tally's increase over the analysed window per second / metre"
    ),
    "wear_lower_per_s, wear_lower_per_m": (
        "net loss of members of the lower body (automata) over the analysed "
        "window per second / per metre slid; error sqrt(out + in events)"
    ),
    "wear_upper_per_s, wear_upper_per_m": "the same for the upper body",
    "layer_depth_m": (
        "10-90 % width of the isotonic fit of v_x(h)/V "
        "per x column (column_width_m), averaged over "
        "columns; layer_depth_err_m: standard error of that mean; layer_depth_xavg_m: x-averaged"
    ),
    "mixed_width_m": (
        "10-90 % width of the upper-body fraction per x column minus the same column's width in "
        "frame 0 (the initial roughness), averaged; mixed_width_frame0_m: x-averaged frame-0 width"
    ),
    "step_length_m": (
        "a length, not a rate: layer_depth_m if resolved (>= 2 bins and >= d), "
        "else the automaton diameter"
    ),
    "links_broken_per_s, links_formed_per_s": (
        "turnover of all links from c_nbond changes between dump frames "
        "(lower bounds), errors sqrt(n); link_break_rate per mean link"
    ),
}


def steady_frames(
    times_s: np.ndarray, start_s: float, min_frames: int = 8
) -> tuple[np.ndarray, str]:
    """Frames to analyse: those at or after ``start_s``, at least the last ``min_frames``.

    Returns
    -------
    frames : ndarray of int
    note : str
        Empty, or why the steady start could not be honoured.
    """
    n = times_s.size
    idx = np.nonzero(times_s >= start_s)[0]
    if idx.size >= min_frames or idx.size == n:
        return idx, ""
    k = min(n, max(min_frames, n // 2))
    return np.arange(n - k, n), (
        f"only {idx.size} dump frames after the friction "
        f"steady start {start_s:.3g} s; analysed the last {k}"
    )


def _c2_tallies(fr: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """Return the C2 cumulative tallies present in friction.csv, by canonical name."""
    out = {}
    for name in C2_TALLIES:
        for col in fr:
            if col == name or col.endswith("_" + name) or col.endswith("." + name):
                out[name] = np.asarray(fr[col], dtype=float)
                break
    return out


def _turnover(bt, counting_rate) -> dict[str, Any]:
    """Link turnover of all links (lower bounds from c_nbond) with counting errors."""
    keys = (
        "links_broken_per_s",
        "links_broken_per_s_err",
        "links_formed_per_s",
        "links_formed_per_s_err",
        "link_break_rate",
        "link_break_rate_err",
    )
    if bt is None:
        return dict.fromkeys(keys)
    span = float(bt.time_s[-1] - bt.time_s[0]) if len(bt.time_s) > 1 else float("nan")
    out = {}
    for name, total in (("broken", bt.broken_total), ("formed", bt.formed_total)):
        v, e = counting_rate(total, span)
        out[f"links_{name}_per_s"], out[f"links_{name}_per_s_err"] = (
            finite_or_none(v),
            finite_or_none(e),
        )
    links = float(np.mean(bt.bonds)) if len(bt.bonds) else 0.0
    v, e = (
        counting_rate(bt.broken_total, span * links) if links > 0 else (float("nan"), float("nan"))
    )
    out["link_break_rate"], out["link_break_rate_err"] = finite_or_none(v), finite_or_none(e)
    return out


def _law(meta) -> str | None:
    raw = meta.raw
    law = (
        raw.get("law")
        or (raw.get("params") or {}).get("law")
        or (raw.get("params") or {}).get("bond_style")
    )
    return None if law is None else str(law)


def compute_rates(out_dir, *, start_s: float | None = None, bin_width_m: float | None = None,
                  window: int | None = None, persistence_s: float | None = None,
                  column_width_m: float | None = None, write: bool = True) -> dict:
    """Analyse an MCA output directory; write ``out_dir/profile.npz`` and ``out_dir/rates.json``.

    Parameters
    ----------
    out_dir : str or Path
        Holds ``meta.json``, ``friction.csv`` and ``traj.lammpstrj``.
    start_s : float, optional
        Start of the analysed (steady) part (s); default: the steady-state
        start detected on mu(t) by :class:`FrictionCoefficient`.
    bin_width_m : float, optional
        Height-bin width of the profiles (m); default one automaton diameter.
    window : int, optional
        Velocity-averaging window of :class:`MassTransfer` (frames).
    persistence_s : float, optional
        Persistence time of a membership change (s); default: the slider
        moves two automaton diameters.
    column_width_m : float, optional
        Width of the x columns of the layer and mixing profiles (m); default 2 d.
    write : bool
        Write the files (default) or only return the dict.

    Returns
    -------
    dict
        The content of ``rates.json`` (see the module docstring), plus
        ``path`` and ``profile_path`` when written.
    """
    import MDAnalysis

    from .. import __version__
    from .diffusion import LateralDiffusion
    from .eq23 import COEFFICIENTS, fit_eq23, write_profile
    from .friction import FrictionCoefficient
    from .outputs import open_trajectory, resume_frames
    from .profiles import CompositionProfile, VelocityProfile
    from .surface import SurfaceProfile
    from .transfer import BondTurnover, MassTransfer, counting_rate

    out = Path(out_dir)
    meta = read_meta(out)
    warnings_: list[str] = []
    fr = read_friction_csv(out)
    try:
        fc = FrictionCoefficient(fr, start_s=start_s).run().results
    except DataFileError as exc:  # e.g. the bodies never came into contact
        fc = None
        warnings_.append(f"friction: {exc}")
    if fc is not None and fc.status:
        warnings_.append(f"friction: {fc.message}")
    u = open_trajectory(out, meta)
    frames_all, steps = resume_frames(u)
    times = steps * meta.dt_s
    # the trajectory analyses use the same window as mu: the steady part, or (no steady state) the
    # second half that the flagged fallback estimate averages
    t_start = start_s if start_s is not None else (fc.window_start_s if fc is not None else 0.0)
    sel, note = steady_frames(times, t_start)
    if note:
        warnings_.append(note)
    frames = frames_all[sel]

    def attempt(name, make, use=None):
        # one failing analysis (e.g. too few frames) must not lose the others
        use = frames if use is None else use
        if use.size < 4:
            warnings_.append(f"{name}: skipped, only {use.size} dump frames (need >= 4)")
            return None
        try:
            return make().run(frames=use).results
        except DataFileError as exc:
            warnings_.append(f"{name}: {exc}")
            return None

    kw_cols = {"column_width_m": column_width_m}
    vp = attempt(
        "velocity profile", lambda: VelocityProfile(u, meta, bin_width_m=bin_width_m, **kw_cols)
    )
    cp = attempt(
        "composition profile",
        lambda: CompositionProfile(u, meta, bin_width_m=bin_width_m, **kw_cols),
    )
    bt = attempt("bond turnover", lambda: BondTurnover(u, meta))
    ld = attempt("diffusion", lambda: LateralDiffusion(u, meta))
    mt = attempt(
        "transfer", lambda: MassTransfer(u, meta, window=window, persistence_s=persistence_s)
    )
    sp = attempt("surface profile", lambda: SurfaceProfile(u, meta), use=frames_all)

    def get(res, key):
        return None if res is None or key not in res else finite_or_none(res[key])

    def series(res, key):
        return None if res is None else [finite_or_none(v) for v in res[key]]

    d = meta.automaton_diameter_m
    # ---- layer (per column) and mixing (per column, frame 0 subtracted)
    layer = get(vp, "layer_depth_columns_m")
    resolved = vp is not None and layer is not None and layer >= 2 * vp.bin_width_m
    if resolved and layer >= d:
        l_step, l_src = layer, "layer_depth_m"
    else:
        l_step, l_src = d, "automaton_diameter_m"
        warnings_.append(
            "step_length_m: no sheared layer of two bins or more resolved per column (slip on a "
            "single plane); using the automaton diameter"
        )
    mw = get(cp, "mixed_width_columns_m")
    if mw is not None and mw < 0:
        warnings_.append(
            f"mixed_width_m: {mw:.3g} m < 0: the interface "
            "is sharper than the initial roughness in "
            "frame 0 (roughness flattened, no mixing beyond it resolved)"
        )
    # ---- diffusion only in the diffusive regime
    D = D_err = None
    d_reason = "not measured"
    if ld is not None:
        d_reason = str(ld.diffusion_reason)
        if ld.diffusive:
            D, D_err = get(ld, "diffusion_m2_s"), get(ld, "diffusion_err_m2_s")
            if D is not None and D <= 0:
                d_reason = f"fitted D = {D:.3g} m^2/s is not positive"
                D = D_err = None
        if D is None:
            warnings_.append(f"diffusion_m2_s: null: {d_reason}")
    # ---- cross-body links (C2 tallies), for the laws that count them
    tallies = _c2_tallies(fr)
    cb: dict[str, Any] = {}
    law = _law(meta)
    if "cross_body_links_formed" in tallies:
        tf = np.asarray(fr["time_s"], dtype=float)
        in_win = tf >= (float(times[sel][0]) if sel.size else 0.0)
        span_w = float(tf[in_win][-1] - tf[in_win][0]) if in_win.sum() > 1 else float("nan")
        dist_w = (float(fr["top_x_m"][in_win][-1] - fr["top_x_m"][in_win][0])
                  if "top_x_m" in fr and in_win.sum() > 1 else float("nan"))
        for name in ("cross_body_links_formed", "cross_body_links_broken"):
            if name not in tallies:
                continue
            c = tallies[name]
            cb[name] = int(round(c[-1]))
            n_w = float(c[in_win][-1] - c[in_win][0]) if in_win.sum() > 1 else float("nan")
            cb[f"{name}_window"] = finite_or_none(n_w)
            for unit, exposure in (("s", span_w), ("m", dist_w)):
                v, e = (
                    counting_rate(n_w, exposure)
                    if np.isfinite(n_w)
                    else (float("nan"), float("nan"))
                )
                cb[f"{name}_per_{unit}"] = finite_or_none(v)
                cb[f"{name}_per_{unit}_err"] = finite_or_none(e)
        for name in ("cross_body_links_current", "links_total", "links_broken", "welds_formed"):
            if name in tallies:
                cb[name] = int(round(tallies[name][-1]))
        cb["cross_body_links_source"] = "friction.csv C2 tallies of the law " + (law or "?")
    else:
        cb["cross_body_links_formed"] = None
        cb["cross_body_links_broken"] = None
        if law == "mca":
            reason = (
                "the mca law counts them (C2 tallies of `compute "
                "pair mca`), but this run's friction.csv has "
                "no cross_body_links_formed column: the deck did not print the tallies"
            )
        else:
            reason = (
                f"law {law!r} does not count links between the "
                "bodies: its dump (c_nbond) and log give links "
                "per automaton without their partners, so links "
                "between the bodies cannot be told from links "
                "within a body (the mca law's C2 tallies do)"
            )
        cb["cross_body_links_reason"] = reason
        warnings_.append(f"cross_body_links_formed: null: {reason}")
    # ---- the surface profile and its Eq. 23 fit
    eq: dict[str, Any] | None = None
    profile_path = out / "profile.npz"
    if sp is not None:
        if write:
            write_profile(profile_path, sp.x_m, sp.t_s, sp.h_m, counts=sp.counts,
                          column_width_m=sp.column_width_m, bulk_density=sp.bulk_density)
        t0_fit = float(times[sel][0]) if sel.size else float(sp.t_s[0])
        n_fit = int((sp.t_s >= t0_fit).sum())
        try:
            # 20 jackknife blocks (the calibrated default) when the run has
            # >= 80 frames, else fewer (>= 4)
            eq = fit_eq23(
                sp.x_m, sp.t_s, sp.h_m, start_s=t0_fit, n_blocks=min(20, max(4, n_fit // 4))
            )
        except DataFileError as exc:
            warnings_.append(f"eq23: {exc}")
            eq = None
    eq_top: dict[str, Any] = {}
    for c in COEFFICIENTS:
        v = None if eq is None else eq[c]
        e = None if eq is None else eq[f"{c}_err"]
        if v is not None and v < 0:
            # a valid fit whose estimate is negative: consistent with 0
            # within its error, but not a rate
            eq["reasons"][c] = (
                f"estimate {v:.3g} < 0 ({abs(v) / e:.1f} sigma below 0): not a physical value"
            )
            v = e = None
        eq_top[c], eq_top[f"{c}_err"] = v, e
    valid = {c: eq_top[c] is not None for c in COEFFICIENTS}
    for c in COEFFICIENTS:
        if not valid[c]:
            why = "no profile" if eq is None else eq["reasons"].get(c, "")
            warnings_.append(f"{c}: null: {why}")

    time_s = meta.time_s if meta.time_s is not None else float(fr["time_s"][-1])
    conditions = {
        "pressure_Pa": meta.pressure_Pa,
        "sliding_velocity_m_s": meta.velocity_m_s,
        "law": law,
        "dim": meta.dimension,
    }
    rates: dict[str, Any] = {
        "mu": get(fc, "mu"),
        "mu_err": get(fc, "mu_err"),
        "mu_steady": bool(fc.steady) if fc is not None else False,
        "steady_start_s": get(fc, "steady_start_s"),
        "mu_estimator": None if fc is None else str(fc.estimator),
        "mu_window_start_s": get(fc, "window_start_s"),
        "mu_n_independent": get(fc, "n_independent"),
        **eq_top,
        "valid": valid,
        "modes_used": [] if eq is None else list(eq["modes_used"]),
        "layer_depth_m": layer,
        "layer_depth_err_m": get(vp, "layer_depth_columns_err_m"),
        "layer_depth_xavg_m": get(vp, "layer_depth_m"),
        "layer_offset_m": get(vp, "layer_offset_m"),
        "layer_resolved": bool(resolved),
        "column_width_m": get(vp, "column_width_m"),
        "mixed_width_m": get(cp, "mixed_width_columns_m"),
        "mixed_width_err_m": get(cp, "mixed_width_columns_err_m"),
        "mixed_width_frame0_m": get(cp, "mixed_width_frame0_m"),
        "mixed_width_xavg_m": get(cp, "mixed_width_m"),
        "penetration_upper_m": get(cp, "penetration_upper_m"),
        "penetration_lower_m": get(cp, "penetration_lower_m"),
        "diffusion_m2_s": D,
        "diffusion_err_m2_s": D_err,
        "diffusion_exponent": get(ld, "msd_exponent"),
        "diffusion_rms_m": get(ld, "rms_displacement_m"),
        "diffusion_reason": None if D is not None else d_reason,
        "transfer_events": None if mt is None else int(mt.transfer_events),
        "return_events": None if mt is None else int(mt.return_events),
        "transfer_per_s": get(mt, "transfer_per_s"),
        "transfer_per_s_err": get(mt, "transfer_per_s_err"),
        "transfer_per_m": get(mt, "transfer_per_m"),
        "transfer_per_m_err": get(mt, "transfer_per_m_err"),
        "transfer_rate": get(mt, "transfer_rate"),
        "transfer_rate_err": get(mt, "transfer_rate_err"),
        "transfer_persistence_s": get(mt, "persistence_s"),
        "transfer_membership_source": None if mt is None else str(mt.membership_source),
        "net_transfer_lower_to_upper": None if mt is None else int(mt.net_transfer_lower_to_upper),
        **cb,
        **{
            k: get(mt, k)
            for k in (
                "wear_lower_per_s",
                "wear_lower_per_s_err",
                "wear_lower_per_m",
                "wear_lower_per_m_err",
                "wear_upper_per_s",
                "wear_upper_per_s_err",
                "wear_upper_per_m",
                "wear_upper_per_m_err",
                "wear_lower_kg_per_m",
                "wear_lower_kg_per_m_err",
                "wear_upper_kg_per_m",
                "wear_upper_kg_per_m_err",
            )
        },
        **_turnover(bt, counting_rate),
        "step_length_m": l_step,
        "step_length_source": l_src,
        "time_s": finite_or_none(time_s),
        "analysis_start_s": float(times[sel][0]) if sel.size else None,
        "analysis_span_s": get(mt, "span_s"),
        "sliding_distance_m": get(mt, "sliding_distance_m"),
        "velocity_m_s": meta.velocity_m_s,
        "pressure_Pa": meta.pressure_Pa,
        "automaton_diameter_m": d,
        "dimension": meta.dimension,
        "conditions": conditions,
    }
    rates["layer_persistence"] = {
        "window_time_s": series(vp, "window_time_s"),
        "layer_depth_xavg_m": series(vp, "window_layer_depth_m"),
        "layer_offset_m": series(vp, "window_layer_offset_m"),
        "mixed_width_xavg_m": series(cp, "window_mixed_width_m"),
    }
    if eq is not None:
        rates["eq23"] = {k: v for k, v in eq.items() if k != "units"}
        rates["eq23"]["units"] = eq["units"]
    rates["units"] = {k: v for k, v in RATES_UNITS.items() if k in rates}
    rates["definitions"] = dict(DEFINITIONS)
    rates["warnings"] = warnings_
    rates["provenance"] = {
        "tribolmp": __version__,
        "MDAnalysis": MDAnalysis.__version__,
        "out_dir": out.name,
        "meta_seed": meta.raw.get("seed"),
        "frames_analysed": int(frames.size),
        "frames_total": int(u.trajectory.n_frames),
        "bin_width_m": bin_width_m if bin_width_m is not None else d,
        "transfer_window_frames": None if mt is None else int(mt.window),
        "transfer_persistence_frames": None if mt is None else int(mt.persistence_frames),
        "profile": "profile.npz" if (sp is not None and write) else None,
        "analyses": ["FrictionCoefficient", "VelocityProfile", "CompositionProfile", "BondTurnover",
                     "LateralDiffusion", "MassTransfer", "SurfaceProfile", "fit_eq23"],
    }
    if write:
        path = out / "rates.json"
        tmp = path.with_suffix(".json.tmp")
        tmp.write_text(json.dumps(jsonable(rates), indent=1, allow_nan=False))
        os.replace(tmp, path)
        rates["path"] = str(path)
        if sp is not None:
            rates["profile_path"] = str(profile_path)
    return rates
