"""MCA friction study: sweep sliding velocity x normal pressure (x seeds) on LAMMPS.

Usage::

    python workflows/mca_friction_sweep.py [--quick] [--preset default] [--velocities 1,5,20]
        [--pressures 0.5e6,50e6,150e6,382e6] [--seeds 1] [--law mca] [--duration S]
        [--box-length M] [--body-height M] [--dim 2] [--np 1] [--out mca_sweep] [--resume]
        [--campaign docs/data/mca_campaign.csv] [--table tribolmp/data/nanoscale_table.json]

For every (V, P, seed) it runs :func:`tribolmp.lammps.mca.run_mca` (which writes
``rates.json`` and ``profile.npz`` through
:func:`tribolmp.analysis.rates.compute_rates`), draws mu(t), the height
profiles and a Fig. 9-like snapshot coloured by body, and collects a table
into ``summary.csv`` and ``summary.md`` in ``--out``.  With ``--campaign`` each
finished run is also appended (one row per run, replacing an older row of the
same run) to that CSV, the study's committed table; ``--table`` then writes the
nanoscale table the chain interpolates (mu and the Eq. 23 coefficients against
P and V, seeds combined, with provenance).  ``--quick`` uses the ``smoke``
preset.  A run that fails is recorded with its error and the sweep goes on.
No physics here: only library calls and bookkeeping.
"""

from __future__ import annotations

import argparse
import csv
import json
import sys
import time
from pathlib import Path

#: Table columns: (header, rates.json / result key, scale, format).
COLUMNS = (
    ("V (m/s)", "velocity_m_s", 1.0, "{:g}"),
    ("P (MPa)", "pressure_Pa", 1e-6, "{:g}"),
    ("seed", "seed", None, "{}"),
    ("mu", "mu", 1.0, "{:.3f}"),
    ("mu_err", "mu_err", 1.0, "{:.3f}"),
    ("steady", "mu_steady", None, "{}"),
    ("layer (nm)", "layer_depth_m", 1e9, "{:.2f}"),
    ("layer err (nm)", "layer_depth_err_m", 1e9, "{:.2f}"),
    ("localized", "localized", None, "{}"),
    ("mixed (nm)", "mixed_width_m", 1e9, "{:.2f}"),
    ("D (m^2/s)", "diffusion_m2_s", 1.0, "{:.3g}"),
    ("MSD exponent", "diffusion_exponent", 1.0, "{:.2f}"),
    ("transfer (1/ns)", "transfer_per_s", 1e-9, "{:.3g}"),
    ("cross links formed", "cross_body_links_formed", None, "{}"),
    ("mu_per_s", "mu_per_s", 1.0, "{:.3g}"),
    ("d0 (m^2/s)", "d0_m2_s", 1.0, "{:.3g}"),
    ("t (ns)", "time_s", 1e9, "{:.3g}"),
    ("atoms", "natoms", None, "{}"),
    ("wall (s)", "wall_time_s", 1.0, "{:.0f}"),
    ("status", "status_text", None, "{}"),
)

#: Columns of the committed campaign table (docs/data/mca_campaign.csv), SI.
CAMPAIGN_COLUMNS = (
    "run",
    "pressure_Pa",
    "sliding_velocity_m_s",
    "seed",
    "dim",
    "law",
    "contact_viscosity_Pa_s",
    "dt_factor",
    "box_length_m",
    "body_height_m",
    "natoms",
    "time_s",
    "mu",
    "mu_err",
    "mu_steady",
    "layer_depth_m",
    "layer_depth_err_m",
    "localized",
    "localized_within_m",
    "mixed_width_m",
    "mixed_width_err_m",
    "cross_body_links_formed",
    "cross_body_links_per_ns",
    "cross_body_links_per_ns_err",
    "transfer_per_ns",
    "transfer_per_ns_err",
    "diffusion_m2_s",
    "diffusion_exponent",
    "mu_per_s",
    "mu_per_s_err",
    "d0_m2_s",
    "d0_m2_s_err",
    "dz",
    "dz_err",
    "dx_l2",
    "dx_l2_err",
    "valid_mu_per_s",
    "valid_d0_m2_s",
    "valid_dz",
    "valid_dx_l2",
    "modes_used",
    "wall_time_s",
    "status",
)


def localized(rates: dict, within_m: float) -> bool | None:
    """Whether slip and mixing stay near the initial interface in the analysed second half.

    True when, in every persistence window of the second half, the sheared layer lies within
    ``within_m`` of the initial interface (|layer centre offset| + half its x-averaged depth) and
    the x-averaged mixed width is below ``2 within_m``.
    """
    lp = rates.get("layer_persistence") or {}
    off = list(lp.get("layer_offset_m") or [])
    dep = list(lp.get("layer_depth_xavg_m") or lp.get("layer_depth_m") or [])
    mix = list(lp.get("mixed_width_xavg_m") or [])
    if not off:
        return None
    n = len(off)
    half = range(n // 2, n)
    for i in half:
        o = off[i]
        d = dep[i] if i < len(dep) else None
        m = mix[i] if i < len(mix) else None
        if (
            o is None
            or d is None
            or abs(o) + 0.5 * d > within_m
            or (m is not None and m > 2 * within_m)
        ):
            return False
    return True


def _viscosity_as_run(rates: dict, meta: dict) -> float | None:
    """Return the mca law's contact viscosity of a run (Pa s), a deck override included."""
    if (rates.get("conditions") or {}).get("law") != "mca":
        return None
    eta = (meta.get("overrides") or {}).get("eta")
    if eta is not None:
        from tribolmp.units import from_lammps

        return from_lammps(float(eta), "viscosity")
    return ((meta.get("mapping") or {}).get("law") or {}).get("contact_viscosity")


def campaign_row(row: dict, rates: dict, meta: dict, params) -> dict:
    """One committed row of the campaign table from a run's rates.json and meta.json.

    SI units, counts per ns.
    """
    d = float(meta.get("automaton_diameter_m") or 2.5e-9)
    within = 3 * d
    out = {
        "run": row["run"],
        "pressure_Pa": row["pressure_Pa"],
        "sliding_velocity_m_s": row["velocity_m_s"],
        "seed": row["seed"],
        "dim": (rates.get("conditions") or {}).get("dim"),
        "law": (rates.get("conditions") or {}).get("law"),
        # the law's viscosity as run (a deck override included); bpm laws have none
        "contact_viscosity_Pa_s": _viscosity_as_run(rates, meta),
        "dt_factor": getattr(params, "dt_factor", None),
        "box_length_m": getattr(params, "box_length", None),
        "body_height_m": getattr(params, "body_height", None),
        "natoms": meta.get("n_atoms"),
        "time_s": rates.get("time_s"),
        "mu": rates.get("mu"),
        "mu_err": rates.get("mu_err"),
        "mu_steady": rates.get("mu_steady"),
        "layer_depth_m": rates.get("layer_depth_m"),
        "layer_depth_err_m": rates.get("layer_depth_err_m"),
        "localized": localized(rates, within),
        "localized_within_m": within,
        "mixed_width_m": rates.get("mixed_width_m"),
        "mixed_width_err_m": rates.get("mixed_width_err_m"),
        "cross_body_links_formed": rates.get("cross_body_links_formed"),
        "diffusion_m2_s": rates.get("diffusion_m2_s"),
        "diffusion_exponent": rates.get("diffusion_exponent"),
        "modes_used": len(rates.get("modes_used") or []),
        "wall_time_s": meta.get("wall_time_s"),
        "status": row.get("status_text"),
    }
    for src, dst in (
        ("cross_body_links_formed_per_s", "cross_body_links_per_ns"),
        ("transfer_per_s", "transfer_per_ns"),
    ):
        for suffix in ("", "_err"):
            v = rates.get(src + suffix)
            out[dst + suffix] = None if v is None else v * 1e-9
    for c in ("mu_per_s", "d0_m2_s", "dz", "dx_l2"):
        out[c], out[f"{c}_err"] = rates.get(c), rates.get(f"{c}_err")
        out[f"valid_{c}"] = (rates.get("valid") or {}).get(c)
    return out


def append_campaign(path: Path, new: dict) -> None:
    """Add (or replace, by run name) one row of the campaign CSV, atomically."""
    rows = []
    if path.exists():
        with path.open() as fh:
            rows = [r for r in csv.DictReader(fh) if r.get("run") != new["run"]]
    rows.append({k: ("" if new.get(k) is None else new.get(k)) for k in CAMPAIGN_COLUMNS})
    tmp = path.with_suffix(".csv.tmp")
    with tmp.open("w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(CAMPAIGN_COLUMNS))
        w.writeheader()
        w.writerows(rows)
    tmp.replace(path)


def nanoscale_table(campaign: Path, out: Path, *, description: str, law: str | None = None,
                    dim: int = 2) -> dict:
    """Write the table the chain interpolates (one law, one dimension).

    Built by :func:`tribolmp.analysis.nanoscale_table.build_table`.
    """
    from tribolmp.analysis.nanoscale_table import build_table, write_table

    table = build_table(campaign, law=law or "mca", description=description, dim=dim)
    write_table(table, out)
    return table


def campaign_figures(campaign: Path, out_dir: Path, prefix: str = "mca_study") -> list[Path]:
    """Draw mu(P) per V with error bars and the layer depth (P, V) from the campaign CSV.

    Return the PNGs.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    with campaign.open() as fh:
        rows = [r for r in csv.DictReader(fh) if r.get("mu") not in ("", None)]
    out_dir.mkdir(parents=True, exist_ok=True)
    paths = []
    for key, err, label, scale, name in (
        ("mu", "mu_err", "mu", 1.0, "mu"),
        ("layer_depth_m", "layer_depth_err_m", "layer depth (nm)", 1e9, "layer"),
    ):
        fig, ax = plt.subplots(figsize=(5, 3.4))
        laws = sorted({r.get("law") or "?" for r in rows})
        markers = dict(zip(laws, "os^D"))
        for law in laws:
            for v in sorted({float(r["sliding_velocity_m_s"]) for r in rows}):
                sel = sorted(
                    (
                        r
                        for r in rows
                        if float(r["sliding_velocity_m_s"]) == v
                        and r[key] not in ("", None)
                        and (r.get("law") or "?") == law
                    ),
                    key=lambda r: float(r["pressure_Pa"]),
                )
                if not sel:
                    continue
                ax.errorbar(
                    [float(r["pressure_Pa"]) * 1e-6 for r in sel],
                    [float(r[key]) * scale for r in sel],
                    yerr=[float(r[err] or 0) * scale for r in sel],
                    fmt=markers[law],
                    capsize=3,
                    label=f"{law}, V = {v:g} m/s",
                    mfc="none" if law != laws[-1] else None,
                )
        ax.set_xscale("symlog", linthresh=1.0)
        if name == "mu":
            # at 0.5 MPa only a few automata touch and mu can reach several units
            ax.set_yscale("log")
        ax.set_xlabel("P (MPa)")
        ax.set_ylabel(label)
        ax.set_title(f"{label} (one marker per run; seeds at 150 and 382 MPa)", fontsize=8)
        ax.legend(fontsize=6)
        fig.tight_layout()
        path = out_dir / f"{prefix}_{name}.png"
        fig.savefig(path, dpi=90)
        plt.close(fig)
        paths.append(path)
    return paths


def roughness_figure(run_dirs: list[Path], path: Path) -> dict[str, dict]:
    """Plot the rms of the lower body's column-mass profile (profile.npz) against time for each run.

    Returns, per run, the rms at frame 0, after 1 ns, and at the end (m): the "roughness destroyed
    within ns" diagnostic.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    from tribolmp.analysis.eq23 import read_profile

    fig, ax = plt.subplots(figsize=(5.5, 3.4))
    out = {}
    for run in run_dirs:
        f = run / "profile.npz"
        if not f.exists():
            continue
        prof = read_profile(f)
        h = prof["h"] - prof["h"].mean(axis=1, keepdims=True)
        rms = h.std(axis=1)
        t = prof["t"]
        label = f"{run.parent.name}/{run.name}"
        ax.plot(t * 1e9, rms * 1e9, lw=0.8, label=label)
        i1 = int(np.searchsorted(t, t[0] + 1e-9))
        out[label] = {
            "rms0_m": float(rms[0]),
            "rms_1ns_m": float(rms[min(i1, rms.size - 1)]),
            "rms_end_m": float(rms[-1]),
            "rms_last_quarter_m": float(rms[3 * rms.size // 4 :].mean()),
        }
    ax.set_xlabel("t (ns)")
    ax.set_ylabel("rms of h(x) (nm)")
    ax.set_title("lower body's column-mass profile: roughness against time", fontsize=8)
    ax.legend(fontsize=5, ncol=2)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)
    return out


def eq23_figure(run_dirs: list[Path], path: Path) -> None:
    """Plot gamma(k) and S gamma against k^2 per mode with the Eq. 23 fits.

    From each run's rates.json.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    fig, axes = plt.subplots(1, 2, figsize=(9, 3.4))
    for run in run_dirs:
        rj = run / "rates.json"
        if not rj.exists():
            continue
        eq = json.loads(rj.read_text()).get("eq23")
        if not eq:
            continue
        m = eq["modes"]
        k2 = np.asarray(m["k_per_m"]) ** 2
        used = np.asarray(m["used"], dtype=bool)
        for ax, (y, e, c0, c1) in zip(
            axes,
            (
                ("gamma_per_s", "gamma_err_per_s", "mu_per_s", "d0_m2_s"),
                ("s_gamma_m3_s", "s_gamma_err_m3_s", "dz", "dx_l2"),
            ),
        ):
            yy = np.array([np.nan if v is None else v for v in m[y]], dtype=float)
            ee = np.array([np.nan if v is None else v for v in m[e]], dtype=float)
            line = ax.errorbar(k2[used], yy[used], yerr=ee[used], fmt="o", ms=3, capsize=2,
                               label=f"{run.parent.name}/{run.name}")
            ax.plot(k2[~used], yy[~used], "x", color=line[0].get_color(), ms=4)
            a, b = eq["raw"].get(c0), eq["raw"].get(c1)
            if a is not None and b is not None and used.any():
                kk = np.linspace(0, k2[used].max(), 50)
                ax.plot(kk, a + b * kk, "-", lw=0.8, color=line[0].get_color())
    axes[0].set_ylabel("gamma (1/s)")
    axes[1].set_ylabel("S gamma (m^3/s)")
    for ax in axes:
        ax.set_xlabel("k^2 (1/m^2)")
        ax.legend(fontsize=6)
    axes[0].set_title("relaxation rate per mode (o used, x not); line: mu + D0 k^2", fontsize=8)
    axes[1].set_title("S gamma per mode; line: Dz + Dx l^2 k^2 (raw fit)", fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def _cell(row: dict, key: str, scale, fmt: str) -> str:
    v = row.get(key)
    if v is None:
        return "-"
    if scale is not None:
        try:
            return fmt.format(float(v) * scale)
        except (TypeError, ValueError):
            return str(v)
    return fmt.format(v)


def write_tables(rows: list[dict], out: Path) -> tuple[Path, Path]:
    """Write ``summary.csv`` (raw SI values) and ``summary.md`` (scaled, rounded)."""
    keys = [k for _, k, _, _ in COLUMNS]
    csv_path = out / "summary.csv"
    with csv_path.open("w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(keys)
        for row in rows:
            w.writerow(["" if row.get(k) is None else row.get(k) for k in keys])
    md_path = out / "summary.md"
    lines = ["| " + " | ".join(h for h, *_ in COLUMNS) + " |", "|" + "---|" * len(COLUMNS)]
    for row in rows:
        lines.append("| " + " | ".join(_cell(row, k, s, f) for _, k, s, f in COLUMNS) + " |")
    md_path.write_text("\n".join(lines) + "\n")
    return csv_path, md_path


def main(argv=None) -> int:
    """Run the sweep; returns 0 if every run finished, 3 if some failed, 2 on bad input."""
    from tribolmp.analysis.plots import plot_friction, plot_profiles, plot_snapshot
    from tribolmp.analysis.profiles import CompositionProfile, VelocityProfile
    from tribolmp.analysis.rates import compute_rates
    from tribolmp.cli import float_list
    from tribolmp.errors import RunError, SetupError
    from tribolmp.lammps.mca import preset_params, run_mca

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="smoke preset (small, ~1 ns per run)")
    ap.add_argument(
        "--preset",
        default=None,
        choices=("smoke", "default", "paper"),
        help="size/time preset (default: default)",
    )
    ap.add_argument(
        "--velocities", type=float_list, default=[1.0, 5.0, 20.0], help="sliding velocities (m/s)"
    )
    ap.add_argument(
        "--pressures", type=float_list, default=[50e6, 150e6, 382e6], help="normal pressures (Pa)"
    )
    ap.add_argument("--duration", type=float, default=None, help="simulated time per run (s)")
    ap.add_argument("--box-length", type=float, default=None, help="periodic length (m)")
    ap.add_argument("--body-height", type=float, default=None, help="height of each body (m)")
    ap.add_argument(
        "--sink-depth",
        type=float,
        default=None,
        help="heat-sink thickness near base and slider (m)",
    )
    ap.add_argument(
        "--roughness-rms", type=float, default=None, help="rms height of each initial surface (m)"
    )
    ap.add_argument("--dump-interval", type=float, default=None, help="trajectory interval (s)")
    ap.add_argument("--contact-viscosity", type=float, default=None,
                    help="viscosity between touching, unlinked automata (Pa s; mca law)")
    ap.add_argument("--dt-factor", type=float, default=None, help="timestep / sqrt(m/k)")
    ap.add_argument("--dim", type=int, default=2, choices=(2, 3))
    ap.add_argument("--np", type=int, default=1, help="MPI ranks per run")
    ap.add_argument(
        "--seed", type=int, default=1, help="seed of the rough surfaces (same for every run)"
    )
    ap.add_argument(
        "--seeds",
        type=lambda t: [int(x) for x in t.split(",") if x.strip()],
        default=None,
        help="comma-separated seeds: every (V, P) once per seed (default: --seed)",
    )
    ap.add_argument(
        "--law",
        default=None,
        help="bond law (tribolmp.lammps.laws registry; default: the preset's)",
    )
    ap.add_argument(
        "--campaign", default=None, help="append each finished run to this CSV (the study's table)"
    )
    ap.add_argument(
        "--table", default=None, help="write the nanoscale table (JSON) from --campaign at the end"
    )
    ap.add_argument(
        "--description", default="", help="one line stored in the nanoscale table's provenance"
    )
    ap.add_argument(
        "--figures",
        default=None,
        help="folder for the campaign figures (mu(P), layer(P)) at the end",
    )
    ap.add_argument(
        "--run-prefix",
        default="",
        help="prefix of the run names (e.g. 'mca_': one campaign CSV holds several laws' rows)",
    )
    ap.add_argument("--out", default="mca_sweep", help="output folder")
    ap.add_argument(
        "--resume", action="store_true", help="skip finished runs, resume interrupted ones"
    )
    ap.add_argument(
        "--reanalyse",
        action="store_true",
        help="no LAMMPS: recompute rates.json and figures of the finished runs in --out",
    )
    args = ap.parse_args(argv)
    preset = args.preset or ("smoke" if args.quick else "default")
    overrides = {
        k: v
        for k, v in (
            ("duration", args.duration),
            ("box_length", args.box_length),
            ("body_height", args.body_height),
            ("sink_depth", args.sink_depth),
            ("bond_style", args.law),
            ("roughness_rms", args.roughness_rms),
            ("dump_interval", args.dump_interval),
            ("contact_viscosity", args.contact_viscosity),
            ("dt_factor", args.dt_factor),
        )
        if v is not None
    }
    seeds = args.seeds or [args.seed]
    campaign = Path(args.campaign) if args.campaign else None
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    rows: list[dict] = []
    failed = 0
    t_all = time.perf_counter()
    points = [(v, p, sd) for v in args.velocities for p in args.pressures for sd in seeds]
    default_law = preset_params(preset, dim=args.dim).bond_style
    for v, p, sd in points:
        name = (
            args.run_prefix
            + f"v{v:g}_p{p / 1e6:g}MPa"
            + (f"_s{sd}" if len(seeds) > 1 or args.seeds else "")
        )
        run_dir = out / name
        row: dict = {"velocity_m_s": v, "pressure_Pa": p, "run": name, "seed": sd}
        try:
            params = preset_params(
                preset, dim=args.dim, sliding_velocity=v, pressure=p, **overrides
            )
            rates_path = run_dir / "rates.json"
            if (args.resume and rates_path.exists()) or args.reanalyse:
                if not (run_dir / "traj.lammpstrj").exists():
                    raise RunError(f"{run_dir}: no finished run to reanalyse")
                rates = (
                    compute_rates(run_dir) if args.reanalyse else json.loads(rates_path.read_text())
                )
                meta = json.loads((run_dir / "meta.json").read_text())
                row.update(natoms=meta.get("n_atoms"), wall_time_s=meta.get("wall_time_s"),
                           atom_steps_per_s=meta.get("atom_steps_per_s"))
            else:
                res = run_mca(params, run_dir, seed=sd, resume=args.resume, np=args.np)
                rates = res.get("rates") or {}
                row.update(
                    natoms=res.natoms,
                    wall_time_s=res.wall_time_s,
                    atom_steps_per_s=res.atom_steps_per_s,
                )
            row.update(
                {
                    k: rates.get(k)
                    for k in rates
                    if k not in ("units", "provenance", "layer_persistence")
                }
            )
            warn = rates.get("warnings") or []
            row["status_text"] = (
                "ok" if not warn else f"{len(warn)} warning(s), first: {warn[0][:70]}"
            )
            plot_friction(run_dir, run_dir / "mu_t.png", title=name)
            plot_snapshot(run_dir, run_dir / "snapshot.png", title=f"{name}: last frame")
            vp = VelocityProfile.from_output(run_dir).run(frames=_steady(rates, run_dir))
            cp = CompositionProfile.from_output(run_dir).run(frames=_steady(rates, run_dir))
            plot_profiles(vp.results, cp.results, run_dir / "profiles.png", title=name)
            row["localized"] = localized(rates, 3 * params.automaton_diameter)
            if campaign is not None:
                meta = json.loads((run_dir / "meta.json").read_text())
                append_campaign(campaign, campaign_row(row, rates, meta, params))
            row["finished"] = True
        except (SetupError, OSError) as exc:
            row["status_text"] = f"rejected: {exc}"
            failed += 1
        except RunError as exc:
            row["status_text"] = f"failed: {exc}"
            failed += 1
        if campaign is not None and not row.get("finished"):
            # a failed run is a row too (status says why), so the table shows what is missing
            append_campaign(
                campaign,
                {
                    "run": name,
                    "pressure_Pa": p,
                    "sliding_velocity_m_s": v,
                    "seed": sd,
                    "law": overrides.get("bond_style") or default_law,
                    "dim": args.dim,
                    "status": row["status_text"],
                },
            )
        rows.append(row)
        csv_path, md_path = write_tables(rows, out)
        print(
            f"{name}: mu={_cell(row, 'mu', 1.0, '{:.3f}')} "
            f"layer={_cell(row, 'layer_depth_m', 1e9, '{:.2f}')} nm "
            f"[{row['status_text'][:80]}]",
            flush=True,
        )
    print(f"wrote {csv_path} and {md_path} in {time.perf_counter() - t_all:.0f} s")
    if args.table and campaign is not None and campaign.exists():
        nanoscale_table(campaign, Path(args.table), description=args.description,
                        law=overrides.get("bond_style") or default_law, dim=args.dim)
        print(f"wrote {args.table}")
    if args.figures and campaign is not None and campaign.exists():
        for path in campaign_figures(campaign, Path(args.figures)):
            print(f"wrote {path}")
    print(md_path.read_text())
    return 3 if failed else 0


def _steady(rates: dict, run_dir: Path):
    """Frames at or after the analysis start recorded in rates.json."""
    from tribolmp.analysis.outputs import open_trajectory, read_meta, resume_frames

    meta = read_meta(run_dir)
    frames, steps = resume_frames(open_trajectory(run_dir, meta))
    start = rates.get("analysis_start_s") or 0.0
    return frames[steps * meta.dt_s >= start - 0.5 * meta.dt_s]


if __name__ == "__main__":
    sys.exit(main())
