"""``rates.json``: the nanoscale rates that parameterise the continuum models.

:func:`compute_rates` runs every analysis of :mod:`tribolmp.analysis` on an
MCA output directory and writes ``rates.json`` (SI units, listed in its
``units`` map).  The fields the topography model (Eq. 23) consumes are

``diffusion_m2_s``
    Lateral diffusion coefficient D of surface automata in their body's frame.
``step_length_m``
    The elementary step length l.  The seed (Sec. 7) ties the microscopic
    length of the stochastic mass transport to the quasi-liquid layer, so
    l = the layer depth from the velocity profile when a layer at least one
    automaton thick was resolved, else the automaton diameter (the smallest
    step the model can represent).  ``step_length_source`` says which.
``step_time_s``
    tau = l^2 / D, so that D = l^2 / tau as in the seed's D ~ l^2/tau.
``transfer_rate`` (1/m), ``wear_rate``, ``detachment_rate``, ``reattachment_rate`` (1/s)
    From :class:`~tribolmp.analysis.transfer.MassTransfer`.

Values that could not be measured are ``null`` with a reason in ``warnings``;
the file is strict JSON (no NaN).
"""

from __future__ import annotations

import datetime as _dt
import json
import os
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import DataFileError
from ..jsonio import finite_or_none
from ..records import Rates
from .outputs import read_friction_csv, read_meta

__all__ = ["compute_rates", "RATES_UNITS", "steady_frames"]

#: Unit of every numeric field of rates.json: the shared record's fields (tribolmp.records.Rates)
#: plus the analysis's own diagnostics.
RATES_UNITS = {
    **Rates.units(),
    "layer_offset_m": "m",
    "mixed_width_m": "m",
    "penetration_upper_m": "m",
    "penetration_lower_m": "m",
    "diffusion_err_m2_s": "m^2/s",
    "net_transfer_rate": "1/m",
    "links_broken_per_s": "1/s",
    "links_formed_per_s": "1/s",
    "link_break_rate": "1/s",
    "atom_steps_per_s": "1/s",
    "time_s": "s",
    "steady_start_s": "s",
    "mu_window_start_s": "s",
    "mu_n_independent": "1",
    "analysis_start_s": "s",
    "velocity_m_s": "m/s",
}


def steady_frames(times_s: np.ndarray, start_s: float, min_frames: int = 8) -> tuple[np.ndarray, str]:
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
        f"only {idx.size} dump frames after the friction steady start {start_s:.3g} s; analysed the last {k}"
    )


def compute_rates(out_dir, *, start_s: float | None = None, bin_width_m: float | None = None,
                  window: int | None = None, write: bool = True) -> dict:
    """Analyse an MCA output directory and write ``out_dir/rates.json``.

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
        Classification window of :class:`MassTransfer` (frames).
    write : bool
        Write ``rates.json`` (default) or only return the dict.

    Returns
    -------
    dict
        The content of ``rates.json``: ``mu``, ``mu_err``, ``layer_depth_m``,
        ``diffusion_m2_s``, ``transfer_rate``, ``wear_rate``,
        ``detachment_rate``, ``reattachment_rate``, ``step_length_m``,
        ``step_time_s``, ``atom_steps_per_s`` and ``time_s`` (when known),
        diagnostics, ``units``, ``warnings`` and ``provenance``.
    """
    import MDAnalysis

    from .. import __version__
    from .diffusion import LateralDiffusion
    from .friction import FrictionCoefficient
    from .outputs import open_trajectory, resume_frames
    from .profiles import CompositionProfile, VelocityProfile
    from .transfer import BondTurnover, MassTransfer

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

    def attempt(name, make):
        # one failing analysis (e.g. too few frames) must not lose the others
        if frames.size < 4:
            warnings_.append(f"{name}: skipped, only {frames.size} dump frames (need >= 4)")
            return None
        try:
            return make().run(frames=frames).results
        except DataFileError as exc:
            warnings_.append(f"{name}: {exc}")
            return None

    vp = attempt("velocity profile", lambda: VelocityProfile(u, meta, bin_width_m=bin_width_m))
    cp = attempt("composition profile", lambda: CompositionProfile(u, meta, bin_width_m=bin_width_m))
    bt = attempt("bond turnover", lambda: BondTurnover(u, meta))
    ld = attempt("diffusion", lambda: LateralDiffusion(u, meta))
    mt = attempt("transfer", lambda: MassTransfer(u, meta, window=window))

    d = meta.automaton_diameter_m
    layer = None if vp is None else finite_or_none(vp.layer_depth_m)
    resolved = vp is not None and bool(vp.layer_resolved) and layer is not None
    if resolved and layer >= d:
        l_step, l_src = layer, "layer_depth_m"
    else:
        l_step, l_src = d, "automaton_diameter_m"
        warnings_.append(
            "step_length_m: no sheared layer of two bins or more resolved (slip on a single plane); "
            "using the automaton diameter"
        )
    D = finite_or_none(ld.diffusion_m2_s) if ld is not None else None
    if D is not None and D <= 0:
        warnings_.append(f"diffusion: fitted D = {D:.3g} m^2/s is not positive (no lateral mixing resolved)")
        D = None
    tau = l_step**2 / D if D else None
    if tau is None:
        warnings_.append("step_time_s: undefined without a positive diffusion coefficient")

    def get(res, key):
        return None if res is None else finite_or_none(res[key])

    def series(res, key):
        return None if res is None else [finite_or_none(v) for v in res[key]]

    time_s = meta.time_s if meta.time_s is not None else float(fr["time_s"][-1])
    rates: dict[str, Any] = {
        "mu": get(fc, "mu"),
        "mu_err": get(fc, "mu_err"),
        "mu_steady": bool(fc.steady) if fc is not None else False,
        "steady_start_s": get(fc, "steady_start_s"),
        "mu_estimator": None if fc is None else str(fc.estimator),
        "mu_window_start_s": get(fc, "window_start_s"),
        "mu_n_independent": get(fc, "n_independent"),
        "layer_depth_m": layer,
        "layer_offset_m": get(vp, "layer_offset_m"),
        "layer_resolved": resolved,
        "mixed_width_m": get(cp, "mixed_width_m"),
        "penetration_upper_m": get(cp, "penetration_upper_m"),
        "penetration_lower_m": get(cp, "penetration_lower_m"),
        "diffusion_m2_s": D,
        "diffusion_err_m2_s": get(ld, "diffusion_err_m2_s"),
        "transfer_rate": get(mt, "transfer_rate"),
        "net_transfer_rate": get(mt, "net_transfer_rate"),
        "wear_rate": get(mt, "wear_rate"),
        "detachment_rate": get(mt, "detachment_rate"),
        "reattachment_rate": get(mt, "reattachment_rate"),
        "links_broken_per_s": get(bt, "broken_per_s"),
        "links_formed_per_s": get(bt, "formed_per_s"),
        "link_break_rate": get(bt, "break_rate_per_link"),
        "step_length_m": l_step,
        "step_length_source": l_src,
        "step_time_s": tau,
        "time_s": finite_or_none(time_s),
        "analysis_start_s": float(times[sel][0]) if sel.size else None,
        "velocity_m_s": meta.velocity_m_s,
        "pressure_Pa": meta.pressure_Pa,
        "automaton_diameter_m": d,
        "dimension": meta.dimension,
    }
    if meta.atom_steps_per_s is not None:
        rates["atom_steps_per_s"] = meta.atom_steps_per_s
    rates["layer_persistence"] = {
        "window_time_s": series(vp, "window_time_s"),
        "layer_depth_m": series(vp, "window_layer_depth_m"),
        "layer_offset_m": series(vp, "window_layer_offset_m"),
        "mixed_width_m": series(cp, "window_mixed_width_m"),
    }
    rates["units"] = {k: v for k, v in RATES_UNITS.items() if k in rates}
    rates["warnings"] = warnings_
    rates["provenance"] = {
        "tribolmp": __version__,
        "MDAnalysis": MDAnalysis.__version__,
        "created_utc": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
        "out_dir": str(out.resolve()),
        "frames_analysed": int(frames.size),
        "frames_total": int(u.trajectory.n_frames),
        "bin_width_m": bin_width_m if bin_width_m is not None else d,
        "transfer_window_frames": None if mt is None else int(mt.window),
        "definitions": {
            "mu": ("sum F_t / sum F_n over the window starting at mu_window_start_s: the MSER-5 steady start "
                   "when mu_steady (mu_estimator 'steady_mean'), else the second half of the run "
                   "('second_half_mean', NOT steady; steady_start_s null); mu_err: blocking standard error, "
                   "widened to half the difference of the window's two halves when not steady"),
            "layer_depth_m": "10-90 % width of the isotonic fit of v_x(h)/V_slider",
            "diffusion_m2_s": "MSD = 2 n D t of surface automata minus their body group's mean, n lateral dims",
            "transfer_rate": "automata joining the other body's motion per surface automaton per metre slid",
            "wear_rate": "transfer_rate * V (1/s)",
            "detachment_rate": "automata leaving the body they moved with, per surface automaton per second",
            "reattachment_rate": "automata joining a body, per layer automaton per second",
            "step_length_m": "layer depth if resolved (>= 2 bins and >= d), else the automaton diameter",
            "step_time_s": "step_length_m**2 / diffusion_m2_s",
        },
    }
    if write:
        path = out / "rates.json"
        tmp = path.with_suffix(".json.tmp")
        tmp.write_text(json.dumps(rates, indent=1, allow_nan=False))
        os.replace(tmp, path)
        rates["path"] = str(path)
    return rates
