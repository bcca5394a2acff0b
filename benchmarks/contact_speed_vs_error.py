"""Contact mechanics: wall time against error for MDR and the 3D BEM.

Tables (printed, and written as CSV into ``benchmarks/results/``):

1. ``contact_speed_vs_error.csv`` -- MDR by number of springs and BEM by grid
   on Hertz, cone and JKR (error vs the analytic references of
   :mod:`tribolmp.models.contact.reference`); the BEM is non-adhesive, so JKR
   has MDR rows only.
2. ``contact_bem_vs_tamaas.csv`` -- our FFT/CG solver against tamaas 2.9
   (optional; pip-installed for the benchmark only) on the reference surfaces
   at 512^2, same load: wall time of one solve, and the stiffness (ours: the
   tangent solve; tamaas: finite difference of the mean gap).
3. ``contact_rough_speed_vs_error.csv`` (+ ``_summary.csv``, ``.png``) -- on
   the resolved rough references of ``tests/data/contact_references.json``
   (surfaces rebuilt from their recipes): the MDR ensemble by line length and
   number of realisations and the periodic BEM by grid, side by side, error of
   the stiffness against the finest periodic reference, wall time per pressure.

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
    """Time MDR (by springs) and BEM (by grid) against the analytic axisymmetric references.

    Hertz and cone for both; JKR for MDR only (the BEM is non-adhesive).  One row
    per case and resolution: wall time (best of repeats) and the error against
    :mod:`tribolmp.models.contact.reference`.
    """
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
            t, res = _best_time(
                lambda: solve(AxisymmetricParams(E_star=E, indentation=d, springs=n, **kw)), 3
            )
            rows.append(
                dict(
                    case=case,
                    method="mdr",
                    resolution=n,
                    time_s=t,
                    error=abs(res.force / F - 1),
                    quantity="force",
                )
            )
        for n in grids:
            # Load control at the reference force; error of the indentation (the BEM's output).
            t, res = _best_time(
                lambda: solve(
                    AxisymmetricParams(E_star=E, normal_force=F, grid_points=n, **kw), method="bem"
                ),
                1,
            )
            rows.append(
                dict(
                    case=case,
                    method="bem",
                    resolution=n,
                    time_s=t,
                    error=abs(res.indentation / d - 1),
                    quantity="indentation",
                )
            )
    po = ref.jkr_pull_off_force_control(R, w)
    po_d = ref.jkr_pull_off_displacement_control(R, w)
    for n in springs:
        t, res = _best_time(
            lambda: solve(
                AxisymmetricParams(
                    profile="sphere",
                    radius=R,
                    E_star=E,
                    indentation=d,
                    work_of_adhesion=w,
                    springs=n,
                )
            ),
            3,
        )
        err = max(
            abs(res.pull_off_force / po - 1),
            abs(res.pull_off_force_displacement_control / po_d - 1),
        )
        rows.append(
            dict(
                case="jkr",
                method="mdr",
                resolution=n,
                time_s=t,
                error=err,
                quantity="pull-off (both controls)",
            )
        )
    return rows


def _references():
    """Load the shipped rough-contact references and helpers.

    The references are tests/data/contact_references.json.
    """
    import json

    root = Path(__file__).resolve().parents[1]
    sys.path.insert(0, str(root))
    from tests.data import contact_references as cr

    return cr, json.loads((root / "tests" / "data" / "contact_references.json").read_text())


def _reference_k(cr, cls):
    """Best periodic stiffness and the resolved mask.

    The best stiffness is that of the finest grid of the resolution study (map 0).
    """
    res = cls["resolution"]
    nf = max(int(n) for n in res)
    return np.array(res[str(nf)]["periodic"]["stiffness"]), cr.resolved_mask(cls), nf


def _tamaas_solve(tm, h, dx, E, P, tol):
    """Tamaas PolonskyKeerRey at mean pressure P: (time s, pressure field, mean gap m)."""
    n = h.shape[0]
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [n * dx, n * dx], [n, n])
    model.E, model.nu = E, 0.0
    solver = tm.PolonskyKeerRey(model, h.copy(), tol)
    solver.max_iter = 100000
    t0 = time.perf_counter()
    solver.solve(P)
    t = time.perf_counter() - t0
    p = np.array(model.traction).reshape(h.shape)
    u = np.array(model.displacement).reshape(h.shape)
    c = float(np.mean((h - u)[p > 0]))
    return t, p, float(np.mean(u - h)) + c


def _load_baseline(path: str):
    """Load another version of ``bem.py`` (e.g. ``git show REV:tribolmp/models/contact/bem.py``).

    It is imported as a sibling of the package's module so that its relative imports resolve;
    the package's own ``bem`` is untouched.
    """
    import importlib.util

    import tribolmp.models.contact as pkg

    spec = importlib.util.spec_from_file_location(f"{pkg.__name__}._baseline_bem", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def tamaas_table(quick: bool, baseline: str | None = None) -> list[dict]:
    """Our periodic BEM against tamaas on the reference surfaces: stiffness and wall time.

    Both solvers run alternately (best of ``repeats`` each, the machine is shared), at the
    same surface and load.  Stiffness: ours from the tangent solve (what ``solve_bem``
    returns), tamaas's by the finite difference of its mean gap between p and p (1 + 1e-3);
    "time for stiffness" is ours (one solve incl. the tangent solve) against tamaas's two solves.
    ``baseline``: path of another ``bem.py``, timed in the same loop (before/after columns).
    """
    from tribolmp.models.contact.bem import solve_bem

    try:
        import tamaas as tm  # benchmark-only optional dependency
    except Exception as exc:  # noqa: BLE001
        print(f"tamaas not available ({exc}); skipping the tamaas table", file=sys.stderr)
        return []
    tm.set_log_level(tm.LogLevel.error)
    cr, refs = _references()
    n = 256 if quick else 512
    base = _load_baseline(baseline) if baseline else None
    names = [k for k in ("H0.8-rolloff", "H0.5-selfaffine", "wavy+H0.8") if k in refs["classes"]][
        : 1 if quick else 3
    ]
    repeats = 1 if quick else 2
    rows = []
    # finite-difference step in pressure for tamaas's stiffness (O(eps) ~ 1e-3 relative error)
    eps = 1e-3
    for name in names:
        cls = refs["classes"][name]
        h, dx = cr.reference_surface(cls["recipe"], cls["recipe"]["seeds"][0], n)
        P = np.array(cls["pressures"])
        ok = cr.resolved_mask(cls)
        for j in [j for j in (0, 3) if ok[j]]:
            p = float(P[j])
            L2 = (n * dx) ** 2
            t_tm, t_tm2, t_ours, t_base = [], [], [], []
            for _ in range(repeats):
                t1, p_tm, g1 = _tamaas_solve(tm, h, dx, cr.E_STAR, p, 1e-12)
                t2, _, g2 = _tamaas_solve(tm, h, dx, cr.E_STAR, p * (1 + eps), 1e-12)
                t0 = time.perf_counter()
                ours = solve_bem(h, dx, cr.E_STAR, p, periodic=True, tol=1e-10)
                t_ours.append(time.perf_counter() - t0)
                if base is not None:
                    t0 = time.perf_counter()
                    old = base.solve_bem(h, dx, cr.E_STAR, p, periodic=True, tol=1e-10)
                    t_base.append(time.perf_counter() - t0)
                t_tm.append(t1)
                t_tm2.append(t1 + t2)
            k_tm = eps * p * L2 / (g1 - g2)
            ours2 = solve_bem(
                h,
                dx,
                cr.E_STAR,
                p * (1 + eps),
                periodic=True,
                tol=1e-10,
                stiffness=False,
                p0=ours.p,
            )
            k_ours_fd = eps * p * L2 / (ours.mean_gap - ours2.mean_gap)
            rows.append(
                dict(
                    surface=name,
                    grid=n,
                    reduced_pressure=cls["reduced_pressures"][j],
                    area_fraction=ours.area_fraction,
                    ours_time_s=min(t_ours),
                    ours_nit=ours.nit,
                    ours_nit_stiffness=ours.nit_stiffness,
                    tamaas_time_s=min(t_tm),
                    tamaas_time_for_stiffness_s=min(t_tm2),
                    time_ratio_solve_incl_tangent=min(t_ours) / min(t_tm),
                    time_ratio_for_stiffness=min(t_ours) / min(t_tm2),
                    ours_stiffness=ours.stiffness,
                    ours_fd_stiffness=k_ours_fd,
                    tamaas_fd_stiffness=k_tm,
                    stiffness_rel_diff=ours.stiffness / k_tm - 1,
                    fd_stiffness_rel_diff=k_ours_fd / k_tm - 1,
                    max_pressure_diff=float(np.max(np.abs(ours.p - p_tm)) / np.max(p_tm)),
                )
            )
            if base is not None:
                rows[-1].update(
                    baseline_time_s=min(t_base),
                    baseline_nit_stiffness=old.nit_stiffness,
                    baseline_time_ratio_for_stiffness=min(t_base) / min(t_tm2),
                    baseline_stiffness_rel_diff=old.stiffness / k_tm - 1,
                )
            print(
                f"  tamaas {name} p/(E*h')={cls['reduced_pressures'][j]:g}: "
                f"ours {min(t_ours):.2f} s vs tamaas {min(t_tm):.2f} s "
                f"(x2 for its stiffness), k diff {rows[-1]['stiffness_rel_diff']:+.2e}",
                flush=True,
            )
    return rows


def rough_table(quick: bool) -> list[dict]:
    """MDR and periodic BEM against the resolved references, one run.

    Resolutions: the MDR line length x realisations, the BEM grid.
    """
    from tribolmp.models.contact.bem import solve_bem
    from tribolmp.models.contact.rough import mdr_profiles_from_heightmap, stiffness_vs_load

    cr, refs = _references()
    names = list(refs["classes"])[:2] if quick else list(refs["classes"])
    grids = (
        (128, 256) if quick else (128, 256, 512)
    )  # > 2 K_S + 1 = 65 points: the band-limited surface unaliased
    reals = (4, 16, 64) if quick else (4, 16, 64, 256)
    rows = []
    for name in names:
        cls = refs["classes"][name]
        k_ref, ok, nf = _reference_k(cr, cls)
        P = np.array(cls["pressures"])[ok]
        pb = np.array(cls["reduced_pressures"])[ok]
        kr = k_ref[ok]
        seed = cls["recipe"]["seeds"][0]
        for n in (128, 256, 512):
            h, dx = cr.reference_surface(cls["recipe"], seed, n)
            for R in reals:
                def run():
                    x, g = mdr_profiles_from_heightmap(h, dx, R, np.random.default_rng(seed + R))
                    return stiffness_vs_load(x, g, cr.E_STAR, P, nominal_area=(n * dx) ** 2)
                t, res = _best_time(run, 3)
                err = np.abs(res.stiffness / kr - 1)
                for j in range(P.size):
                    rows.append(
                        dict(
                            surface=name,
                            method="mdr",
                            mesh=n,
                            realizations=R,
                            reduced_pressure=pb[j],
                            rel_error=err[j],
                            closed_fraction=res.closed_fraction[j],
                            time_s=t / P.size,
                            reference_grid=nf,
                        )
                    )
        for n in grids:
            h, dx = cr.reference_surface(cls["recipe"], seed, n)
            p0 = None
            for j, p in enumerate(P):
                t0 = time.perf_counter()
                r = solve_bem(h, dx, cr.E_STAR, float(p), periodic=True, tol=1e-10, p0=p0)
                t = time.perf_counter() - t0
                p0 = r.p
                rows.append(
                    dict(
                        surface=name,
                        method="bem",
                        mesh=n,
                        realizations=0,
                        reduced_pressure=pb[j],
                        rel_error=abs(r.stiffness / kr[j] - 1),
                        closed_fraction=float("nan"),
                        time_s=t,
                        reference_grid=nf,
                    )
                )
        print(f"  rough {name}: done", flush=True)
    return rows


def _plot_rough(rows: list[dict], path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.5, 4.8))
    keys = sorted({(r["method"], r["mesh"], r["realizations"]) for r in rows})
    for method, mesh, R in keys:
        sel = [r for r in rows if (r["method"], r["mesh"], r["realizations"]) == (method, mesh, R)]
        t = np.median([r["time_s"] for r in sel])
        e = max(float(np.median([r["rel_error"] for r in sel])), 1e-6)
        hi = max(float(np.max([r["rel_error"] for r in sel])), e)
        ax.errorbar([t], [e], yerr=[[0.0], [hi - e]], fmt="o" if method == "mdr" else "s",
                    color="C0" if method == "mdr" else "C3", capsize=2)
        ax.annotate(f"{mesh}" + (f"x{R}" if method == "mdr" else "²"), (t, e), fontsize=7)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall time per pressure (s)")
    ax.set_ylabel("|k/k_periodic - 1|: median (marker), worst (bar)")
    ax.set_title("rough contact: MDR (blue, line x realisations) vs BEM (red, grid)", fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def _plot(rows: list[dict], path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6, 4.5))
    for case in ("hertz", "cone", "jkr"):
        for method, marker in (("mdr", "o-"), ("bem", "s--")):
            sel = [r for r in rows if r["case"] == case and r["method"] == method]
            if sel:
                ax.loglog(
                    [r["time_s"] for r in sel],
                    [max(r["error"], 1e-16) for r in sel],
                    marker,
                    label=f"{method} {case}",
                )
    ax.set_xlabel("wall time (s)")
    ax.set_ylabel("relative error")
    ax.legend(fontsize=8)
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def _rough_summary(rows: list[dict]) -> list[dict]:
    out = []
    for key in sorted({(r["method"], r["mesh"], r["realizations"]) for r in rows}):
        sel = [r for r in rows if (r["method"], r["mesh"], r["realizations"]) == key]
        closed = [r["closed_fraction"] for r in sel if r["method"] == "mdr"]
        out.append(dict(method=key[0], mesh=key[1], realizations=key[2], cases=len(sel),
                        median_rel_error=float(np.median([r["rel_error"] for r in sel])),
                        max_rel_error=float(np.max([r["rel_error"] for r in sel])),
                        max_closed_fraction=float(np.max(closed)) if closed else float("nan"),
                        median_time_s=float(np.median([r["time_s"] for r in sel]))))
    return out


def main(argv=None) -> int:
    """Run the benchmark; ``--quick`` for a small version."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="small sizes (seconds instead of minutes)")
    ap.add_argument(
        "--out", default=str(Path(__file__).resolve().parent / "results"), help="output folder"
    )
    ap.add_argument(
        "--skip", default="", help="comma list of tables to skip: axisymmetric,tamaas,rough"
    )
    ap.add_argument(
        "--baseline-bem",
        default=None,
        metavar="FILE",
        help="another bem.py (e.g. `git show REV:tribolmp/models/contact/bem.py > FILE`), timed "
        "side by side with the current one in the tamaas table",
    )
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
        rows = tamaas_table(args.quick, args.baseline_bem)
        print_table("BEM against tamaas (periodic rough surface)", rows)
        write_csv(out / f"contact_bem_vs_tamaas{suffix}.csv", rows)
    if "rough" not in skip:
        rows = rough_table(args.quick)
        summary = _rough_summary(rows)
        print_table(
            "Rough surfaces (resolved references): worst "
            "error and time per (method, mesh, realisations)",
            summary,
        )
        write_csv(out / f"contact_rough_speed_vs_error{suffix}.csv", rows)
        write_csv(out / f"contact_rough_speed_vs_error_summary{suffix}.csv", summary)
        _plot_rough(rows, out / f"contact_rough_speed_vs_error{suffix}.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
