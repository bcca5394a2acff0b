"""Synthetic MCA output directories whose analysis results are known exactly.

Each ``make_*`` function writes an output directory in the format of
:func:`tribolmp.lammps.mca.run_mca` (``meta.json``, ``traj.lammpstrj``,
``friction.csv``) from an explicit random generator, and returns the answer
the corresponding analysis must find.  They are the reference solutions of the
analysis tests (``tests/analysis``) and of ``tests/data``.

All arguments are SI; the files hold LAMMPS ``units nano`` numbers, as the
decks write them (nm, nm/ns).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
from scipy.special import ndtr, ndtri

from .outputs import DUMP_COLUMNS, MOL_BASE, MOL_LOWER, MOL_SLIDER, MOL_UPPER

__all__ = [
    "write_dump",
    "write_meta",
    "write_friction_csv",
    "erf_width",
    "make_shear_mixing",
    "make_walkers",
    "make_transfer",
    "make_friction",
    "make_oscillating_friction",
    "ar1_mean_stderr",
]

_FMT = "%d %d %d %.6f %.6f %.6f %.5f %.5f %.5f %.4f %d"


def write_dump(path, frames) -> Path:
    """Write frames as a LAMMPS ``dump custom`` file with the MCA columns.

    Parameters
    ----------
    path : str or Path
        Output file.
    frames : iterable of dict
        Keys ``step`` (int), ``box`` ((3, 2) bounds, nm), ``mol`` (N,),
        ``pos`` ((N, 3), nm), ``vel`` ((N, 3), nm/ns), ``radius`` (N,) nm,
        ``nbond`` (N,); optional ``type`` (N,), ``id`` (N,) (default 1..N) and
        ``extra`` (dict column name -> (N,) integers, appended after the MCA
        columns, e.g. the mca law's per-automaton links to the other body).
    """
    path = Path(path)
    with path.open("w") as fh:
        for fr in frames:
            pos = np.asarray(fr["pos"], dtype=float)
            n = pos.shape[0]
            ids = np.asarray(fr.get("id", np.arange(1, n + 1)))
            mol = np.asarray(fr["mol"])
            typ = np.asarray(
                fr.get("type", np.where(mol == MOL_BASE, 2, np.where(mol == MOL_SLIDER, 3, 1)))
            )
            box = np.asarray(fr["box"], dtype=float)
            fh.write(f"ITEM: TIMESTEP\n{int(fr['step'])}\nITEM: NUMBER OF ATOMS\n{n}\n")
            fh.write("ITEM: BOX BOUNDS pp ff pp\n")
            for lo, hi in box:
                fh.write(f"{lo:.6f} {hi:.6f}\n")
            extra = fr.get("extra") or {}
            fh.write("ITEM: ATOMS " + " ".join(DUMP_COLUMNS + tuple(extra)) + "\n")
            table = np.column_stack(
                [
                    ids,
                    mol,
                    typ,
                    pos,
                    np.asarray(fr["vel"], dtype=float),
                    np.broadcast_to(fr["radius"], (n,)),
                    np.broadcast_to(fr["nbond"], (n,)),
                ]
                + [np.broadcast_to(v, (n,)) for v in extra.values()]
            )
            np.savetxt(fh, table, fmt=_FMT + " %d" * len(extra))
    return path


def write_meta(out_dir, *, dt_s, dump_interval_steps, velocity_m_s, diameter_m, box_m, dim=2,
               pressure_Pa=150e6, density_kg_m3=7800.0, **extra) -> Path:
    """Write ``meta.json`` with the fields the analyses read (SI)."""
    meta = {
        "units": {"dt_s": "s", "dump_interval_s": "s", "velocity_m_s": "m/s", "pressure_Pa": "Pa",
                  "automaton_diameter_m": "m", "box_m": "m", "density_kg_m3": "kg/m^3"},
        "dt_s": dt_s,
        "dump_interval_steps": int(dump_interval_steps),
        "dump_interval_s": dt_s * int(dump_interval_steps),
        "velocity_m_s": velocity_m_s,
        "pressure_Pa": pressure_Pa,
        "automaton_diameter_m": diameter_m,
        "box_m": [list(map(float, b)) for b in box_m],
        "dimension": dim,
        "normal_axis": "y",
        "density_kg_m3": density_kg_m3,
        "molecules": {"1": "base", "2": "lower body", "3": "upper body", "4": "rigid slider"},
        "synthetic": True,
        **extra,
    }
    path = Path(out_dir) / "meta.json"
    path.write_text(json.dumps(meta, indent=1))
    return path


def write_friction_csv(path, time_s, friction_N, normal_N, top_x_m) -> Path:
    """Write ``friction.csv`` (SI columns ``time_s,friction_N,normal_N,top_x_m``)."""
    path = Path(path)
    table = np.column_stack([time_s, friction_N, normal_N, top_x_m])
    np.savetxt(
        path,
        table,
        delimiter=",",
        header="time_s,friction_N,normal_N,top_x_m",
        comments="",
        fmt="%.10g",
    )
    return path


def erf_width(sigma: float, lo: float = 0.1, hi: float = 0.9) -> float:
    """Distance between the ``lo`` and ``hi`` levels of an error-function step of std ``sigma``."""
    return float(sigma * (ndtri(hi) - ndtri(lo)))


def _box(L, H, dim, depth=None):
    depth = L if depth is None else depth
    return (
        np.array([[0.0, L], [0.0, H], [0.0, depth if dim == 3 else 0.0]])
        if dim == 3
        else np.array([[0.0, L], [0.0, H], [-0.5, 0.5]])
    )


def make_shear_mixing(
    out_dir,
    rng,
    *,
    n_atoms=3000,
    n_frames=8,
    velocity=10.0,
    diameter=2.5e-9,
    height=40e-9,
    length=40e-9,
    interface=20e-9,
    sigma_v=3e-9,
    offset_v=1e-9,
    sigma_c=2e-9,
    noise=0.05,
    wave_amplitude=0.0,
    roughness_amplitude=0.0,
) -> dict:
    """Shear and mixing with error-function profiles of known width.

    Frame 0 is unmixed: lower body below ``interface``, upper above.  In the
    later frames, heights are uniform, v_x = V Phi((y - y0 - offset_v)/sigma_v)
    plus Gaussian noise (``noise * V``), and an automaton is upper-body with
    probability Phi((y - y0)/sigma_c).  The bottom and top 2.5 nm are base
    and slider.  Lengths in m.

    ``wave_amplitude`` > 0 makes the slip and mixing planes wavy in the
    later frames, ``y0 + A sin(2 pi x / L)`` (a wavy slip line: an x-averaged
    profile turns it into an apparent layer ~2A wide, a per-column profile
    does not).  ``roughness_amplitude`` > 0 makes the frame-0 interface wavy
    in the same way (the initial roughness, present before any mixing).

    Returns
    -------
    dict
        ``layer_depth_m``, ``layer_offset_m``, ``mixed_width_m``,
        ``penetration_m`` (at 5 %), ``interface_height_m``, ``velocity_m_s``.
    """
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    nm = 1e-9
    H, L, y0 = height / nm, length / nm, interface / nm
    edge = 2.5
    frames = []
    dt, every = 1e-13, 1000
    for k in range(n_frames):
        y = rng.uniform(0.0, H, n_atoms)
        x = rng.uniform(0.0, L, n_atoms)
        if k == 0:
            yc = y0 + roughness_amplitude / nm * np.sin(2 * np.pi * x / L)
            upper = y >= yc
            vx = np.where(upper, velocity, 0.0)
        else:
            yc = y0 + wave_amplitude / nm * np.sin(2 * np.pi * x / L)
            upper = rng.random(n_atoms) < ndtr((y - yc) / (sigma_c / nm))
            vx = velocity * ndtr((y - yc - offset_v / nm) / (sigma_v / nm))
            vx = vx + noise * velocity * rng.standard_normal(n_atoms)
        mol = np.where(upper, MOL_UPPER, MOL_LOWER)
        mol[y < edge] = MOL_BASE
        mol[y > H - edge] = MOL_SLIDER
        vx[mol == MOL_BASE] = 0.0
        vx[mol == MOL_SLIDER] = velocity
        pos = np.column_stack([x, y, np.zeros(n_atoms)])
        vel = np.column_stack([vx, np.zeros(n_atoms), np.zeros(n_atoms)])
        frames.append(
            dict(step=k * every, box=_box(L, H, 2), mol=mol, pos=pos, vel=vel, radius=1.25, nbond=6)
        )
    write_dump(out / "traj.lammpstrj", frames)
    write_meta(out, dt_s=dt, dump_interval_steps=every, velocity_m_s=velocity, diameter_m=diameter,
               box_m=_box(L, H, 2) * nm)
    return {
        "layer_depth_m": erf_width(sigma_v),
        "layer_offset_m": offset_v,
        "mixed_width_m": erf_width(sigma_c),
        "penetration_m": float(-sigma_c * ndtri(0.05)),
        "interface_height_m": interface,
        "velocity_m_s": velocity,
    }


def make_walkers(out_dir, rng, *, diffusion=2e-9, n_walkers=200, n_frames=60, velocity=20.0, dim=2,
                 length=30e-9, diameter=2.5e-9, interval=1e-10, shear_velocity_sd=0.0) -> dict:
    """Surface automata doing Brownian motion of known D on top of their body's motion.

    Each body has ``n_walkers`` surface automata (within one diameter of the
    interface) that random-walk laterally with coefficient ``diffusion``
    (m^2/s) in every lateral dimension; the upper body and its surface
    automata also slide at ``velocity`` along x, so they cross the periodic
    boundary many times.  Bulk rows, base and slider move rigidly with their
    body.  Heights do not change.

    ``shear_velocity_sd`` (m/s) > 0 gives every walker, in addition, a
    constant velocity along x drawn from N(0, sd): the shear dispersion of
    automata carried at different speeds by a sheared layer.  Their MSD then
    grows as t^2 once ``sd^2 t^2`` exceeds ``2 D t`` (not diffusion).

    Returns
    -------
    dict
        ``diffusion_m2_s``, ``lateral_dims``, ``n_surface``, ``velocity_m_s``.
    """
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    nm, d = 1e-9, diameter / 1e-9
    L = length / nm
    y0 = 5 * d
    H = 10 * d
    lat = [0] if dim == 2 else [0, 2]
    # rows: base, two lower bulk rows (> 2 d from the interface), the lower and upper surface rows
    # (d/2 from it), two upper bulk rows, slider
    rows = [
        (0.5 * d, MOL_BASE, 0),
        (1.8 * d, MOL_LOWER, 0),
        (2.8 * d, MOL_LOWER, 0),
        (y0 - 0.5 * d, MOL_LOWER, 1),
        (y0 + 0.5 * d, MOL_UPPER, 1),
        (7.2 * d, MOL_UPPER, 0),
        (8.2 * d, MOL_UPPER, 0),
        (9.5 * d, MOL_SLIDER, 0),
    ]
    heights, mols, walk = [], [], []
    for h, m, w in rows:
        n = n_walkers if w else max(4, int(L / d))
        heights.append(np.full(n, h))
        mols.append(np.full(n, m))
        walk.append(np.full(n, bool(w)))
    h, mol, walk = map(np.concatenate, (heights, mols, walk))
    n = h.size
    x0 = rng.uniform(0, L, (n, 3))
    moving = np.isin(mol, (MOL_UPPER, MOL_SLIDER))
    D = diffusion / nm**2 * 1e-9  # nm^2/ns
    dt_ns = interval / 1e-9
    disp = np.zeros((n, 3))
    drift = np.zeros(n)
    if shear_velocity_sd > 0:
        drift[walk] = rng.normal(0.0, shear_velocity_sd, int(walk.sum()))  # m/s = nm/ns
    frames = []
    every = 2000
    box = _box(L, H, dim)
    for k in range(n_frames):
        if k:
            steps = rng.standard_normal((n, 3)) * math.sqrt(2 * D * dt_ns)
            steps[~walk] = 0.0
            steps[:, 1] = 0.0
            if dim == 2:
                steps[:, 2] = 0.0
            disp += steps
        pos = x0 + disp
        pos[:, 0] += drift * dt_ns * k
        pos[moving, 0] += velocity * dt_ns * k
        pos[:, 1] = h
        if dim == 2:
            pos[:, 2] = 0.0
        for a in lat:
            pos[:, a] = np.mod(pos[:, a], L)
        vel = np.zeros((n, 3))
        vel[moving, 0] = velocity
        frames.append(
            dict(step=k * every, box=box, mol=mol, pos=pos, vel=vel, radius=d / 2, nbond=6)
        )
    write_dump(out / "traj.lammpstrj", frames)
    write_meta(
        out,
        dt_s=interval / every,
        dump_interval_steps=every,
        velocity_m_s=velocity,
        diameter_m=diameter,
        box_m=box * nm,
        dim=dim,
    )
    return {"diffusion_m2_s": diffusion, "lateral_dims": len(lat), "n_surface": 2 * n_walkers,
            "velocity_m_s": velocity}


def make_transfer(
    out_dir,
    rng,
    *,
    n_per_row=20,
    n_frames=40,
    velocity=10.0,
    interval=1e-10,
    diameter=2.5e-9,
    n_transfer_up=3,
    n_transfer_down=2,
    n_layer=4,
    t_transfer=10,
    t_detach=15,
    t_reattach=25,
    n_flicker=3,
    t_flicker=30,
    flicker_frames=2,
    bond_events=((5, 3, 2), (12, 4, 0), (20, 0, 5)),
) -> dict:
    """Scripted transfer, detachment/reattachment and link changes with exact answers.

    Two surface rows (one per body, within one diameter of the interface) and
    two bulk rows per body, a base and a slider row.  From frame
    ``t_transfer`` on, ``n_transfer_up`` lower-surface automata move with the
    upper body (and sit just above the interface), ``n_transfer_down``
    upper-surface automata stop with the lower body (just below it).  From
    ``t_detach`` to ``t_reattach`` ``n_layer`` other lower-surface automata
    move at V/2 (the layer), then return to the lower body.  From
    ``t_flicker`` on, ``n_flicker`` further lower-surface automata move with
    the upper body for only ``flicker_frames`` intervals (shorter than the
    default persistence of 5 frames: not a transfer).  ``bond_events``
    lists ``(interval, broken, formed)``: in interval ``k -> k+1`` that many
    links break and form between disjoint automata, so ``c_nbond`` changes
    reveal them exactly.  Motion is noise-free, so a window of one frame
    classifies every automaton exactly.

    Returns
    -------
    dict
        Exact event counts, the sliding distance over the classified frames
        (window 1), the surface count, and the rates the analysis must give.
    """
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    nm, d = 1e-9, diameter / 1e-9
    L = n_per_row * d
    y0 = 5 * d
    rows = [
        (0.5 * d, MOL_BASE),
        (1.8 * d, MOL_LOWER),
        (2.8 * d, MOL_LOWER),
        (y0 - 0.5 * d, MOL_LOWER),
        (y0 + 0.5 * d, MOL_UPPER),
        (7.2 * d, MOL_UPPER),
        (8.2 * d, MOL_UPPER),
        (9.5 * d, MOL_SLIDER),
    ]
    h = np.concatenate([np.full(n_per_row, r[0]) for r in rows])
    mol = np.concatenate([np.full(n_per_row, r[1]) for r in rows])
    x0 = np.tile((np.arange(n_per_row) + 0.5) * d, len(rows))
    n = h.size
    lower_surface = np.nonzero((mol == MOL_LOWER) & (h == y0 - 0.5 * d))[0]
    upper_surface = np.nonzero((mol == MOL_UPPER) & (h == y0 + 0.5 * d))[0]
    pick = rng.permutation(lower_surface)
    up_ids = pick[:n_transfer_up]
    layer_ids = pick[n_transfer_up:n_transfer_up + n_layer]
    flicker_ids = pick[n_transfer_up + n_layer:n_transfer_up + n_layer + n_flicker]
    down_ids = rng.permutation(upper_surface)[:n_transfer_down]
    dt_ns = interval / 1e-9
    step_v = np.zeros((n_frames, n))  # velocity during interval k -> k+1
    step_v[:, np.isin(mol, (MOL_UPPER, MOL_SLIDER))] = velocity
    step_v[t_transfer:, up_ids] = velocity
    step_v[t_transfer:, down_ids] = 0.0
    step_v[t_detach:t_reattach, layer_ids] = velocity / 2
    step_v[t_flicker:t_flicker + flicker_frames, flicker_ids] = velocity
    xs = np.vstack([np.zeros(n), np.cumsum(step_v[:-1] * dt_ns, axis=0)]) + x0
    nbond = np.full(n, 4)
    nb_frames = []
    expected_broken = expected_formed = 0
    for k in range(n_frames):
        for (kk, nbr, nfo) in bond_events:
            if kk + 1 == k:  # changes between frame kk and kk+1
                chosen = rng.choice(
                    np.nonzero(np.isin(mol, (MOL_LOWER, MOL_UPPER)))[0],
                    2 * (nbr + nfo),
                    replace=False,
                )
                nbond = nbond.copy()
                nbond[chosen[: 2 * nbr]] -= 1
                nbond[chosen[2 * nbr:]] += 1
                expected_broken += nbr
                expected_formed += nfo
        nb_frames.append(nbond)
    frames = []
    every = 1000
    box = _box(L, 10 * d, 2)
    for k in range(n_frames):
        hk = h.copy()
        if k >= t_transfer + 1:  # they have moved with the other body for one interval
            hk[up_ids] = y0 + 0.5 * d + 0.01
            hk[down_ids] = y0 - 0.5 * d - 0.01
        pos = np.column_stack([np.mod(xs[k], L), hk, np.zeros(n)])
        vel = np.column_stack([step_v[k], np.zeros(n), np.zeros(n)])
        frames.append(
            dict(
                step=k * every, box=box, mol=mol, pos=pos, vel=vel, radius=d / 2, nbond=nb_frames[k]
            )
        )
    write_dump(out / "traj.lammpstrj", frames)
    write_meta(
        out,
        dt_s=interval / every,
        dump_interval_steps=every,
        velocity_m_s=velocity,
        diameter_m=diameter,
        box_m=box * nm,
    )
    # exact answers for window = 1: classified frames are 1..T-1, state k uses interval k-1 -> k
    w = 1
    span = (n_frames - 1 - w) * interval
    distance = velocity * span
    n_surface = 2 * n_per_row  # surface rows are within 2 d of the interface, bulk rows are not
    n_tr = n_transfer_up + n_transfer_down
    lower_out, lower_in = n_transfer_up + n_layer, n_transfer_down + n_layer
    upper_out, upper_in = n_transfer_down, n_transfer_up
    return {
        "broken_total": expected_broken,
        "formed_total": expected_formed,
        "transfer_events": n_tr,
        "detach_events": n_tr + n_layer,
        "return_events": n_layer,
        "flicker_events": int(flicker_ids.size) if t_flicker + flicker_frames < n_frames else 0,
        "crossed_lower_up": n_transfer_up,
        "crossed_upper_down": n_transfer_down,
        "n_surface": n_surface,
        "span_s": span,
        "sliding_distance_m": distance,
        "transfer_per_s": n_tr / span,
        "transfer_per_s_err": math.sqrt(n_tr) / span,
        "transfer_per_m": n_tr / distance,
        "transfer_rate": n_tr / (n_surface * distance),
        "net_transfer_lower_to_upper": n_transfer_up - n_transfer_down,
        "wear_lower": n_transfer_up - n_transfer_down,
        "wear_upper": n_transfer_down - n_transfer_up,
        "wear_lower_per_s": (n_transfer_up - n_transfer_down) / span,
        "wear_lower_per_s_err": math.sqrt(lower_out + lower_in) / span,
        "wear_upper_per_m": (n_transfer_down - n_transfer_up) / distance,
        "wear_upper_per_m_err": math.sqrt(upper_out + upper_in) / distance,
        "velocity_m_s": velocity,
    }


def make_oscillating_friction(
    out_dir,
    rng,
    *,
    n=200,
    dt=5e-12,
    mu=0.15,
    amplitude=0.45,
    period=0.45e-9,
    normal=2e-8,
    normal_amplitude=0.0,
    noise=0.01,
    phase=0.0,
    velocity=5.0,
) -> dict:
    """friction.csv with periodic forces.

    F_t = F_n0 (mu + a sin(w t + phase) + noise), F_n = F_n0 (1 + b sin(w t)).

    ``amplitude`` a of order mu with a ``period`` of about half the run mimics
    the stick-slip-like swing of a short MCA run (the 1 ns smoke run: mu(t)
    between -0.5 and 0.7 with a period of ~0.45 ns): no steady mean can be
    resolved.  With a = 0 and ``normal_amplitude`` b > 0 the friction force is
    constant while the normal force swings, so the mean of F_t/F_n exceeds the
    ratio of the mean forces by the factor 1/sqrt(1 - b^2) (Jensen).

    Returns
    -------
    dict
        ``mu``: the long-run ratio of mean forces <F_t>/<F_n> (exactly ``mu``,
        the sines average out over whole periods); ``mean_of_ratios``: the
        long-run mean of F_t/F_n for a = 0 (mu / sqrt(1 - b^2)); ``period_s``.
    """
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    t = (np.arange(n) + 1) * dt
    w = 2.0 * math.pi / period
    fn = normal * (1.0 + normal_amplitude * np.sin(w * t))
    ft = normal * (mu + amplitude * np.sin(w * t + phase) + noise * rng.standard_normal(n))
    write_friction_csv(out / "friction.csv", t, ft, fn, velocity * t)
    return {
        "mu": mu,
        "mean_of_ratios": mu / math.sqrt(1.0 - normal_amplitude**2),
        "period_s": period,
    }


def ar1_mean_stderr(phi: float, sigma_eps: float, n: int) -> float:
    """Exact standard error of the mean of ``n`` samples of a stationary AR(1) process."""
    var_x = sigma_eps**2 / (1 - phi**2)
    k = np.arange(1, n)
    s = 1 + 2 * np.sum((1 - k / n) * phi**k)
    return float(math.sqrt(var_x * s / n))


def make_friction(out_dir, rng, *, n=4000, dt=1e-11, mu=0.3, phi=0.9, sigma_eps=0.01, transient=0.2,
                  tau=2e-9, normal=7.5e-9, velocity=5.0, drift=0.0) -> dict:
    """friction.csv with mu(t) = mu + transient*exp(-t/tau) + AR(1) noise (+ optional drift).

    Returns
    -------
    dict
        ``mu``, ``mu_err`` (exact standard error of the steady mean over the
        samples after ``5 tau``), ``transient_end_s`` (``5 tau``).
    """
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    t = (np.arange(n) + 1) * dt
    eps = rng.normal(0.0, sigma_eps, n)
    x = np.empty(n)
    x[0] = eps[0] / math.sqrt(1 - phi**2)
    for i in range(1, n):
        x[i] = phi * x[i - 1] + eps[i]
    m = mu + transient * np.exp(-t / tau) + x + drift * t / t[-1]
    fn = np.full(n, normal)
    write_friction_csv(out / "friction.csv", t, m * fn, fn, velocity * t)
    n_steady = int(np.sum(t > 5 * tau))
    err = ar1_mean_stderr(phi, sigma_eps, n_steady) if n_steady > 1 else float("nan")
    return {"mu": mu, "mu_err": err, "transient_end_s": 5 * tau}
