"""MCA friction study: sweep sliding velocity x normal pressure on LAMMPS.

Usage::

    python workflows/mca_friction_sweep.py [--quick] [--preset default] [--velocities 1,5,20]
        [--pressures 50e6,150e6,382e6] [--duration S] [--box-length M] [--body-height M]
        [--dim 2] [--np 1] [--seed 1] [--out mca_sweep] [--resume]

For every (V, P) it runs :func:`tribolmp.lammps.mca.run_mca` (which writes
``rates.json`` through :func:`tribolmp.analysis.rates.compute_rates`), draws
mu(t), the height profiles and a Fig. 9-like snapshot coloured by body, and
collects a table of mu, layer depth, D and wear rate into ``summary.csv`` and
``summary.md`` in ``--out``.  ``--quick`` uses the ``smoke`` preset (about
10 s of LAMMPS per run on one core).  A run that fails is recorded in the
table with its error and the sweep goes on.  No physics here: only library
calls and bookkeeping.
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
    ("mu", "mu", 1.0, "{:.3f}"),
    ("mu_err", "mu_err", 1.0, "{:.3f}"),
    ("steady", "mu_steady", None, "{}"),
    ("layer (nm)", "layer_depth_m", 1e9, "{:.2f}"),
    ("layer resolved", "layer_resolved", None, "{}"),
    ("layer offset (nm)", "layer_offset_m", 1e9, "{:.2f}"),
    ("mixed (nm)", "mixed_width_m", 1e9, "{:.2f}"),
    ("D (m^2/s)", "diffusion_m2_s", 1.0, "{:.3g}"),
    ("wear (1/s)", "wear_rate", 1.0, "{:.3g}"),
    ("transfer (1/m)", "transfer_rate", 1.0, "{:.3g}"),
    ("links broken (1/s)", "links_broken_per_s", 1.0, "{:.3g}"),
    ("t (ns)", "time_s", 1e9, "{:.3g}"),
    ("atoms", "natoms", None, "{}"),
    ("Matom-steps/s", "atom_steps_per_s", 1e-6, "{:.3g}"),
    ("wall (s)", "wall_time_s", 1.0, "{:.0f}"),
    ("status", "status_text", None, "{}"),
)


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
    ap.add_argument("--preset", default=None, choices=("smoke", "default", "paper"), help="size/time preset (default: default)")
    ap.add_argument("--velocities", type=float_list, default=[1.0, 5.0, 20.0], help="sliding velocities (m/s)")
    ap.add_argument("--pressures", type=float_list, default=[50e6, 150e6, 382e6], help="normal pressures (Pa)")
    ap.add_argument("--duration", type=float, default=None, help="simulated time per run (s)")
    ap.add_argument("--box-length", type=float, default=None, help="periodic length (m)")
    ap.add_argument("--body-height", type=float, default=None, help="height of each body (m)")
    ap.add_argument("--sink-depth", type=float, default=None, help="heat-sink thickness near base and slider (m)")
    ap.add_argument("--dim", type=int, default=2, choices=(2, 3))
    ap.add_argument("--np", type=int, default=1, help="MPI ranks per run")
    ap.add_argument("--seed", type=int, default=1, help="seed of the rough surfaces (same for every run)")
    ap.add_argument("--out", default="mca_sweep", help="output folder")
    ap.add_argument("--resume", action="store_true", help="skip finished runs, resume interrupted ones")
    ap.add_argument("--reanalyse", action="store_true",
                    help="no LAMMPS: recompute rates.json and figures of the finished runs in --out")
    args = ap.parse_args(argv)
    preset = args.preset or ("smoke" if args.quick else "default")
    overrides = {k: v for k, v in (("duration", args.duration), ("box_length", args.box_length),
                                   ("body_height", args.body_height), ("sink_depth", args.sink_depth)) if v is not None}
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    rows: list[dict] = []
    failed = 0
    t_all = time.perf_counter()
    for v in args.velocities:
        for p in args.pressures:
            name = f"v{v:g}_p{p / 1e6:g}MPa"
            run_dir = out / name
            row: dict = {"velocity_m_s": v, "pressure_Pa": p, "run": name}
            try:
                params = preset_params(preset, dim=args.dim, sliding_velocity=v, pressure=p, **overrides)
                rates_path = run_dir / "rates.json"
                if (args.resume and rates_path.exists()) or args.reanalyse:
                    if not (run_dir / "traj.lammpstrj").exists():
                        raise RunError(f"{run_dir}: no finished run to reanalyse")
                    rates = compute_rates(run_dir) if args.reanalyse else json.loads(rates_path.read_text())
                    meta = json.loads((run_dir / "meta.json").read_text())
                    row.update(natoms=meta.get("n_atoms"), wall_time_s=meta.get("wall_time_s"),
                               atom_steps_per_s=meta.get("atom_steps_per_s"))
                else:
                    res = run_mca(params, run_dir, seed=args.seed, resume=args.resume, np=args.np)
                    rates = res.get("rates") or {}
                    row.update(natoms=res.natoms, wall_time_s=res.wall_time_s, atom_steps_per_s=res.atom_steps_per_s)
                row.update({k: rates.get(k) for k in rates if k not in ("units", "provenance", "layer_persistence")})
                warn = rates.get("warnings") or []
                row["status_text"] = "ok" if not warn else f"{len(warn)} warning(s), first: {warn[0][:70]}"
                plot_friction(run_dir, run_dir / "mu_t.png", title=name)
                plot_snapshot(run_dir, run_dir / "snapshot.png", title=f"{name}: last frame")
                vp = VelocityProfile.from_output(run_dir).run(frames=_steady(rates, run_dir))
                cp = CompositionProfile.from_output(run_dir).run(frames=_steady(rates, run_dir))
                plot_profiles(vp.results, cp.results, run_dir / "profiles.png", title=name)
            except (SetupError, OSError) as exc:
                row["status_text"] = f"rejected: {exc}"
                failed += 1
            except RunError as exc:
                row["status_text"] = f"failed: {exc}"
                failed += 1
            rows.append(row)
            csv_path, md_path = write_tables(rows, out)
            print(f"{name}: mu={_cell(row, 'mu', 1.0, '{:.3f}')} layer={_cell(row, 'layer_depth_m', 1e9, '{:.2f}')} nm "
                  f"[{row['status_text'][:80]}]", flush=True)
    print(f"wrote {csv_path} and {md_path} in {time.perf_counter() - t_all:.0f} s")
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
