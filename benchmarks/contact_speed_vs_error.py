"""Contact mechanics: wall time against error for MDR and the 3D BEM.

Tables (printed, and written as CSV into ``benchmarks/results/``):

1. ``contact_speed_vs_error.csv`` -- MDR by number of springs and BEM by grid
   on Hertz, cone and JKR (error vs the analytic references of
   :mod:`tribolmp.models.contact.reference`); the BEM is non-adhesive, so JKR
   has MDR rows only.
2. ``contact_bem_vs_tamaas.csv`` -- our FFT/CG solver against tamaas 2.9
   (optional; pip-installed for the benchmark only) on the same periodic rough
   surface, with the same load, timed side by side.
3. ``contact_rough_mdr_vs_bem.csv`` -- MDR ensemble stiffness against the BEM
   (non-periodic rough punch and periodic cell) over three decades of
   pressure, with the wall time of each.

A log-log plot of time against error goes next to the CSVs.

Usage: ``python benchmarks/contact_speed_vs_error.py [--quick] [--out DIR]``.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

from tribolmp.benchmarking import print_table, write_csv


def _best_time(fun, repeat):
    best, out = float("inf"), None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fun()
        best = min(best, time.perf_counter() - t0)
    return best, out


def axisymmetric_table(quick: bool) -> list[dict]:
    from tribolmp.models.contact import AxisymmetricParams, solve
    from tribolmp.models.contact import reference as ref

    E, R, d, w = 1e11, 1e-3, 1e-6, 0.5
    rows = []
    springs = (21, 51, 201, 501, 1999) if quick else (21, 51, 101, 201, 501, 1001, 1999, 4001)
    grids = (32, 64) if quick else (32, 64, 128, 256)
    cases = {
        "hertz": (dict(profile="sphere", radius=R), float(ref.hertz_force(d, R, E))),
        "cone": (dict(profile="cone", half_angle_deg=70.0), float(ref.cone_force(d, 70.0, E))),
    }
    for case, (kw, F) in cases.items():
        for n in springs:
            t, res = _best_time(lambda: solve(AxisymmetricParams(modulus=E, indentation=d, springs=n, **kw)), 3)
            rows.append(dict(case=case, method="mdr", resolution=n, time_s=t, error=abs(res.force / F - 1), quantity="force"))
        for n in grids:
            # Load control at the reference force; error of the indentation (the BEM's output).
            t, res = _best_time(lambda: solve(AxisymmetricParams(modulus=E, normal_force=F, grid=n, **kw), method="bem"), 1)
            rows.append(dict(case=case, method="bem", resolution=n, time_s=t, error=abs(res.indentation / d - 1), quantity="indentation"))
    po = ref.jkr_pull_off_force_control(R, w)
    po_d = ref.jkr_pull_off_displacement_control(R, w)
    for n in springs:
        t, res = _best_time(lambda: solve(AxisymmetricParams(profile="sphere", radius=R, modulus=E, indentation=d, work_of_adhesion=w, springs=n)), 3)
        err = max(abs(res.pull_off_force / po - 1), abs(res.pull_off_force_displacement_control / po_d - 1))
        rows.append(dict(case="jkr", method="mdr", resolution=n, time_s=t, error=err, quantity="pull-off (both controls)"))
    return rows


def tamaas_table(quick: bool) -> list[dict]:
    from tribolmp.models.contact.bem import solve_bem
    from tribolmp.models.contact.rough import generate_surface, self_affine_psd

    n = 128 if quick else 512
    L, E = 1.0, 1.0
    dx = L / n
    rng = np.random.default_rng(7)
    h = generate_surface(n, dx, self_affine_psd(1e-2, 0.8, L / 4, L / 64), rng)
    P = 0.005  # ~1.5 % contact area
    rows = []
    try:
        import tamaas as tm  # benchmark-only optional dependency
    except Exception as exc:  # noqa: BLE001
        print(f"tamaas not available ({exc}); skipping the tamaas column", file=sys.stderr)
        tm = None
    for rep in range(2):
        t0 = time.perf_counter()
        ours = solve_bem(h, dx, E, P, periodic=True, stiffness=False, tol=1e-10)
        t_ours = time.perf_counter() - t0
        row = dict(grid=n, repeat=rep, ours_time_s=t_ours, ours_nit=ours.nit, ours_area_fraction=ours.area_fraction)
        if tm is not None:
            model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [L, L], [n, n])
            model.E, model.nu = E, 0.0
            solver = tm.PolonskyKeerRey(model, h.copy(), 1e-12)
            t0 = time.perf_counter()
            solver.solve(P)
            t_tm = time.perf_counter() - t0
            p_tm = np.array(model.traction).reshape(h.shape)
            row.update(
                tamaas_time_s=t_tm,
                tamaas_area_fraction=float(np.mean(p_tm > 0)),
                ratio=t_ours / t_tm,
                max_pressure_diff=float(np.max(np.abs(ours.p - p_tm)) / np.max(p_tm)),
            )
        rows.append(row)
    return rows


def rough_table(quick: bool) -> list[dict]:
    from tribolmp.models.contact import solve_rough
    from tribolmp.models.contact.rough import generate_surface, self_affine_psd

    n = 64 if quick else 256
    dx = 2e-6
    E = 1.13e11
    rng = np.random.default_rng(20060327)
    s_rng, e_rng = rng.spawn(2)
    h = generate_surface(n, dx, self_affine_psd(1e-6, 0.8, n * dx / 4, 8e-6 if not quick else 8e-6), s_rng)
    pressures = [1e5, 1e6, 1e7, 1e8] if not quick else [1e6, 1e7, 1e8]
    t_mdr, mdr = _best_time(lambda: solve_rough(h, dx, E, pressures, method="mdr", realizations=16, rng=np.random.default_rng(1)), 7)
    rows = []
    bems = {per: solve_rough(h, dx, E, pressures, method="bem", periodic=per) for per in (False, True)}
    for j, p in enumerate(pressures):
        bn, bp = bems[False].rows[j], bems[True].rows[j]
        rows.append(
            dict(
                grid=n,
                pressure=p,
                mdr_stiffness=mdr.stiffness[j],
                mdr_q10=mdr.stiffness_q10[j],
                mdr_q90=mdr.stiffness_q90[j],
                mdr_time_s=t_mdr / len(pressures),
                bem_punch_stiffness=bn["stiffness"],
                bem_punch_area_fraction=bn["area_fraction"],
                bem_punch_time_s=bn["time_s"],
                ratio_mdr_punch=mdr.stiffness[j] / bn["stiffness"],
                bem_periodic_stiffness=bp["stiffness"],
                bem_periodic_time_s=bp["time_s"],
                ratio_mdr_periodic=mdr.stiffness[j] / bp["stiffness"],
                speedup_vs_punch=bn["time_s"] / (t_mdr / len(pressures)),
            )
        )
    return rows


def _plot(rows: list[dict], path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6, 4.5))
    for case in ("hertz", "cone", "jkr"):
        for method, marker in (("mdr", "o-"), ("bem", "s--")):
            sel = [r for r in rows if r["case"] == case and r["method"] == method]
            if sel:
                ax.loglog([r["time_s"] for r in sel], [max(r["error"], 1e-16) for r in sel], marker, label=f"{method} {case}")
    ax.set_xlabel("wall time (s)")
    ax.set_ylabel("relative error")
    ax.legend(fontsize=8)
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main(argv=None) -> int:
    """Run the benchmark; ``--quick`` for a small version."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="small sizes (seconds instead of minutes)")
    ap.add_argument("--out", default=str(Path(__file__).resolve().parent / "results"), help="output folder")
    ap.add_argument("--skip", default="", help="comma list of tables to skip: axisymmetric,tamaas,rough")
    args = ap.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    skip = set(filter(None, args.skip.split(",")))
    suffix = "_quick" if args.quick else ""
    if "axisymmetric" not in skip:
        rows = axisymmetric_table(args.quick)
        print_table("MDR (springs) and BEM (grid) against analytic references", rows)
        write_csv(out / f"contact_speed_vs_error{suffix}.csv", rows)
        _plot(rows, out / f"contact_speed_vs_error{suffix}.png")
    if "tamaas" not in skip:
        rows = tamaas_table(args.quick)
        print_table("BEM against tamaas (periodic rough surface)", rows)
        write_csv(out / f"contact_bem_vs_tamaas{suffix}.csv", rows)
    if "rough" not in skip:
        rows = rough_table(args.quick)
        print_table("Rough surface: MDR ensemble (16) against BEM stiffness", rows)
        write_csv(out / f"contact_rough_mdr_vs_bem{suffix}.csv", rows)
    return 0


if __name__ == "__main__":
    sys.exit(main())
