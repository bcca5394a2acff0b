"""``tribolmp lubrication``.

Reduced lubrication forces, the Reynolds reference, film dynamics, polishing.

Only composes library calls from :mod:`tribolmp.models.lubrication`; no physics here.
"""

from __future__ import annotations

from . import seed_type

HELP = "reduced lubrication forces and the Reynolds reference"


def configure(parser) -> None:
    """Add the lubrication subcommands.

    ``squeeze``, ``sliding``, ``pairlaw``, ``approach``, ``summary`` and ``polish``.
    """
    sub = parser.add_subparsers(
        dest="action", metavar="ACTION", parser_class=type(parser), required=True
    )

    def sphere_args(p, velocity_help):
        p.add_argument("--radius", type=float, required=True, help="sphere radius R (m)")
        p.add_argument("--viscosity", type=float, required=True, help="viscosity eta (Pa s)")
        p.add_argument("--gap", type=float, required=True, help="minimum gap h (m)")
        p.add_argument("--velocity", type=float, required=True, help=velocity_help)
        p.add_argument("--json", action="store_true", help="machine-readable output")

    sq = sub.add_parser("squeeze", help="squeeze force on a sphere approaching a plane (N)")
    sphere_args(sq, "approach speed V = -dh/dt (m/s; V > 0 closes the gap)")
    sq.add_argument(
        "--model", default="damper", help="damper | cox-brenner | brenner | reynolds | power-law"
    )
    sq.add_argument(
        "--power-law-index", type=float, default=1.0, help="flow index n > 1/3 (1 = Newtonian)"
    )
    sq.add_argument(
        "--consistency", type=float, default=None, help="power-law consistency K (Pa s^n)"
    )
    sq.add_argument("--cells", type=int, default=400, help="Reynolds mesh cells")
    sq.add_argument(
        "--domain", type=float, default=1000.0, help="Reynolds outer radius / sqrt(2 R h)"
    )

    sl = sub.add_parser("sliding", help="drag on a sphere sliding parallel to a plane (N)")
    sphere_args(sl, "sliding speed U (m/s)")
    sl.add_argument("--model", default="gcb", help="gcb | couette (the seed's Eq. 12) | faxen")
    sl.add_argument(
        "--length", type=float, default=None, help="Couette integration radius L (m; default R)"
    )

    pl = sub.add_parser(
        "pairlaw", help="Eq. 13 pair law integrated over sphere and plane (ring quadrature)"
    )
    sphere_args(pl, "approach speed V (m/s)")
    pl.add_argument("--refine", type=float, default=0.25, help="element size / local gap (<= 0.5)")

    ap = sub.add_parser("approach", help="sphere under constant load through the film")
    ap.add_argument("--radius", type=float, required=True, help="R (m)")
    ap.add_argument("--viscosity", type=float, required=True, help="eta or K (Pa s^n)")
    ap.add_argument(
        "--normal-force",
        "--load",
        dest="load",
        type=float,
        required=True,
        help="constant load W (N); --load is the old spelling",
    )
    ap.add_argument("--gap", type=float, required=True, help="initial gap h0 (m)")
    ap.add_argument("--duration", type=float, required=True, help="time (s)")
    ap.add_argument("--steps", type=int, default=100, help="time steps")
    ap.add_argument("--model", default="damper", help="damper | cox-brenner | power-law")
    ap.add_argument("--power-law-index", type=float, default=1.0, help="n > 1/3")
    ap.add_argument("--scheme", default="log", help="log (stable, exact) | explicit (comparison)")
    ap.add_argument("--json", action="store_true", help="machine-readable output")

    su = sub.add_parser(
        "summary", help="lubrication summary of a scene (damper, force vs gap, Reynolds error)"
    )
    su.add_argument(
        "scene",
        nargs="?",
        default=None,
        help="scene TOML (default: the embedded scene with a [lubricant])",
    )
    su.add_argument("--json", action="store_true", help="machine-readable output")

    po = sub.add_parser("polish", help="lubricated polishing: roughness against time (CSV + plot)")
    po.add_argument(
        "scene",
        nargs="?",
        default=None,
        help="scene TOML with [polishing] (default: built-in values)",
    )
    po.add_argument("--out", required=True, help="output directory")
    po.add_argument("--steps", type=int, default=None, help="time steps (default 100)")
    po.add_argument("--grid-points", type=int, default=None, help="workpiece grid points per side")
    po.add_argument(
        "--seed", type=seed_type, default=None, help="random seed (default: [scene].seed)"
    )
    po.add_argument("--no-plot", action="store_true", help="skip the PNG")
    po.add_argument("--json", action="store_true", help="machine-readable summary")


def _params(args, **extra):
    from ..models.lubrication import reduced

    kw = dict(radius=args.radius, viscosity=args.viscosity, gap=args.gap)
    kw.update(extra)
    return reduced.Params(**kw)


def _print(args, payload: dict, text: str) -> None:
    if args.json:
        from . import emit_json

        emit_json(payload)
    else:
        print(text)


def _squeeze(args) -> int:
    from ..models.lubrication import reduced

    p = _params(
        args,
        velocity=args.velocity,
        power_law_index=args.power_law_index,
        consistency=args.consistency,
        reynolds_cells=args.cells,
        reynolds_domain=args.domain,
    )
    warn = _gap_warnings(args.gap)
    res = reduced.squeeze_force(p, args.model)
    payload = {k: v for k, v in res.items() if k not in ("units",)}
    if warn:
        payload["warnings"] = warn
    payload["units"] = res.units
    _print(
        args,
        payload,
        f"squeeze force ({args.model}): {res.force:.6g} N  [{res.time_s * 1e3:.3g} ms]",
    )
    return 0


def _sliding(args) -> int:
    from ..models.lubrication import reduced

    p = _params(args, velocity=0.0, sliding_velocity=args.velocity, length=args.length)
    warn = _gap_warnings(args.gap)
    res = reduced.sliding_force(p, args.model)
    _print(
        args,
        {**dict(res), **({"warnings": warn} if warn else {})},
        f"sliding drag ({args.model}): {res.force:.6g} N",
    )
    return 0


def _pairlaw(args) -> int:
    from ..models.lubrication import pairlaw

    warn = _gap_warnings(args.gap)
    res = pairlaw.sphere_plane_pair_force(
        args.radius, args.viscosity, args.gap, args.velocity, refine=args.refine
    )
    _print(
        args,
        {**dict(res), **({"warnings": warn} if warn else {})},
        f"pair-law force: {res.force:.6g} N (exact "
        f"{res.exact:.6g} N, rel. error {res.rel_error:.2e})",
    )
    return 0


def _approach(args) -> int:
    from ..models.lubrication import dynamics

    p = dynamics.FilmParams(
        radius=args.radius,
        viscosity=args.viscosity,
        normal_force=args.load,
        gap0=args.gap,
        duration=args.duration,
        steps=args.steps,
        model=args.model,
        power_law_index=args.power_law_index,
    )
    warn = _gap_warnings(args.gap)
    res = dynamics.approach(p, scheme=args.scheme)
    _print(
        args,
        {**dict(res), **({"warnings": warn} if warn else {})},
        f"h(t_end) = {res.h[-1]:.6g} m (exact {res.h_exact[-1]:.6g} "
        f"m); min gap {res.min_gap:.3g} m; {res.message}",
    )
    if res.status < 0:
        # The data are printed (a user comparing schemes wants them), but a failed scheme is
        # a failed run: exit 3, never 0.
        from ..errors import BlowUpError

        raise BlowUpError(f"scheme '{args.scheme}' failed: {res.message}")
    return 0


def _gap_warnings(gap: float) -> list[str]:
    """Refuse a gap below a molecular size; print (and return) the doubtful-continuum warning."""
    import sys

    from ..models.lubrication.validity import check_film_gap

    warn = check_film_gap(gap, "--gap")
    for line in warn:
        print(f"warning: {line}", file=sys.stderr)
    return warn


def _load(scene_path, *, need_lubricant: bool):
    from ..errors import SceneError
    from ..scene import builtin_scene, load_scene

    if scene_path is None:
        scene = builtin_scene("lubrication")
    else:
        scene = load_scene(scene_path)
    if need_lubricant and scene.lubricant is None:
        raise SceneError("[lubricant]", "a [lubricant] section", "nothing", scene.source)
    return scene


def _summary(args) -> int:
    from ..models.lubrication import lubrication_summary

    res = lubrication_summary(_load(args.scene, need_lubricant=True))
    stokes = res.get("error_damper_vs_stokes", [float("nan")] * len(res.gap))
    lines = [
        f"alpha = 6 pi eta R^2 = {res.alpha:.6g} N s (V = {res.velocity:.3g} m/s)",
        "h/R        damper (N)    Reynolds (N)  Reynolds "
        "grid error  damper error vs Stokes (Brenner)",
    ]
    for e, fd, fr, er, es in zip(
        res.gap_over_radius,
        res.force_damper,
        res.force_reynolds,
        res.error_damper_vs_reynolds,
        stokes,
    ):
        lines.append(f"{e:<10.3g} {fd:<13.6g} {fr:<13.6g} {er:+.2e}            "
                     + (f"{es:+.2e}" if es == es else "n/a (power law: no exact reference)"))
    _print(args, dict(res), "\n".join(lines))
    return 0


def _polish(args) -> int:
    import csv
    import json
    from pathlib import Path

    import numpy as np

    from ..models.lubrication import polishing

    scene = _load(args.scene, need_lubricant=False)
    overrides = {}
    if args.steps is not None:
        overrides["steps"] = args.steps
    if args.grid_points is not None:
        overrides["grid_points"] = args.grid_points
    params = polishing.params_from_scene(scene, **overrides)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    seed = scene.scene.seed if args.seed is None else args.seed
    res = polishing.polish(params, rng=np.random.default_rng(seed))
    with open(out / "roughness.csv", "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["time_s", "sq_m", "sa_m", "removed_volume_m3", "mean_depth_removed_m"])
        for row in zip(res.t, res.sq, res.sa, res.removed_volume, res.removed_volume / params.area):
            w.writerow([f"{v:.9g}" for v in row])
    np.save(out / "topography_final.npy", res.h)
    np.savez_compressed(
        out / "topography_snapshots.npz",
        t=res.snapshot_t,
        h=np.array(res.snapshots),
        pixel_size_m=params.pixel_size,
    )
    summary = {
        k: res[k]
        for k in (
            "removal_rate",
            "preston_rate",
            "mass_balance_error",
            "contact_fraction",
            "load_error",
            "n_particles",
            "time_s",
            "message",
        )
    }
    summary.update(
        sq_initial_m=float(res.sq[0]),
        sq_final_m=float(res.sq[-1]),
        pixel_size_m=params.pixel_size,
        seed=seed,
        # "velocity": the old name of sliding_velocity, kept for readers of this JSON
        params={**params.__dict__, "velocity": params.sliding_velocity},
    )
    (out / "polish_summary.json").write_text(json.dumps(summary, indent=2, default=float))
    (out / "topography_final.json").write_text(
        json.dumps({"pixel_size_m": params.pixel_size, "units": "m"})
    )
    if not args.no_plot:
        from ..models.lubrication.plots import plot_polishing

        plot_polishing(res, out / "roughness.png")
    _print(
        args,
        {**summary, "out": str(out)},
        f"Sq {res.sq[0]:.4g} m -> {res.sq[-1]:.4g} m in "
        f"{params.duration:g} s; removal rate {res.removal_rate:.4g} m/s "
        f"(Preston k p v = {res.preston_rate:.4g} m/s); wrote {out}/roughness.csv",
    )
    return 0


def run(args) -> int:
    """Dispatch to the chosen action."""
    return {
        "squeeze": _squeeze,
        "sliding": _sliding,
        "pairlaw": _pairlaw,
        "approach": _approach,
        "summary": _summary,
        "polish": _polish,
    }[args.action](args)
