"""``tribolmp sweep``: parameter campaigns on Dask.

Usage: ``tribolmp sweep SCENE.toml --vary section.field=v1,v2,... [--vary ...] [--seeds N]
[--workers N | --scheduler ADDRESS] [--out DIR] [--json]``.

Each point of the product of the ``--vary`` lists (times ``--seeds``) runs the chain as one Dask
task (a LocalCluster on 127.0.0.1 by default; ``--scheduler`` for any running cluster, e.g.
dask-jobqueue on SLURM/PBS: docs/sweep.md). Results go through one shared stage cache, so a killed
sweep resumes and shared stages are computed once.  ``--json`` prints ``{"points": [{"vary", "seed",
"status", "values", "message"}], "table", "workers", "wall_time_s"}``. Exit 0 when every point
finished, 3 when some failed (they are in the table), 2 on bad input.
"""

from __future__ import annotations

HELP = (
    "parameter campaign: run a scene over a product of values on Dask (LocalCluster or --scheduler)"
)


def _resources(text: str) -> dict[str, float]:
    import argparse

    out = {}
    for item in text.split(","):
        name, _, val = item.partition("=")
        try:
            out[name.strip()] = float(val)
        except ValueError:
            raise argparse.ArgumentTypeError(
                f"expected NAME=NUMBER[,NAME=NUMBER], got {text!r}"
            ) from None
        if not name.strip() or not out[name.strip()] > 0:
            raise argparse.ArgumentTypeError(f"expected NAME=NUMBER with NUMBER > 0, got {text!r}")
    return out


def configure(parser) -> None:
    """Add arguments."""
    parser.add_argument("scene", help="base scene (TOML)")
    parser.add_argument(
        "--vary",
        action="append",
        default=[],
        metavar="SECTION.FIELD=V1,V2,...",
        help="a scene field and its values (repeatable; the points are the product)",
    )
    parser.add_argument(
        "--seeds", type=int, default=1, help="seeds per point: [scene].seed + 0..N-1 (default 1)"
    )
    eng = parser.add_mutually_exclusive_group()
    eng.add_argument(
        "--workers",
        type=int,
        default=2,
        help="worker processes of the embedded LocalCluster (default 2)",
    )
    eng.add_argument(
        "--scheduler",
        default=None,
        metavar="ADDRESS",
        help="address of a running Dask scheduler, e.g. tcp://host:8786",
    )
    parser.add_argument(
        "--out", default="tribolmp-sweep", help="output folder (default ./tribolmp-sweep)"
    )
    parser.add_argument(
        "--cache-dir",
        default=None,
        help="stage cache shared by all points (default OUT/cache); share it between sweeps",
    )
    parser.add_argument(
        "--resources",
        type=_resources,
        default=None,
        metavar="NAME=N",
        help="Dask resources each point reserves, e.g. MPI=4 for [nanoscale].ranks = 4",
    )
    parser.add_argument(
        "--map",
        action="append",
        default=[],
        metavar="STAGE.KEY",
        help="draw this scalar as a map over the first two varied fields",
    )
    parser.add_argument("--no-figures", action="store_true", help="skip the PNG figures")
    parser.add_argument("--quiet", action="store_true", help="no progress output")
    parser.add_argument("--json", action="store_true", help="print the result as JSON")


def run(args) -> int:
    """Parse the axes, run the sweep, print the table path or the JSON."""
    from ..campaign import parse_vary, run_sweep
    from ..errors import ParameterError
    from . import emit_json

    if not args.vary:
        raise ParameterError("--vary", "at least one section.field=v1,v2,...", "none")
    axes = [parse_vary(v) for v in args.vary]
    res = run_sweep(
        args.scene,
        axes,
        seeds=args.seeds,
        out=args.out,
        workers=args.workers,
        scheduler=args.scheduler,
        cache_dir=args.cache_dir,
        resources=args.resources,
        figures=not args.no_figures,
        map_keys=args.map,
        quiet=args.quiet,
    )
    failed = [p for p in res.points if p["status"] != "ok"]
    if args.json:
        emit_json(res.to_json_dict())
    else:
        print(
            f"{len(res.points)} point(s), {len(failed)} failed, "
            f"on {res.workers} worker(s) in {res.wall_time_s:.1f} s"
            + (f" ({res.resumed} done earlier)" if res.resumed else "")
        )
        for p in failed:
            print(
                f"  failed {' '.join(f'{k}={v}' for k, v in p['vary'].items())} "
                f"seed={p['seed']}: {p['message']}"
            )
        print(f"table: {res.table_csv}  ({res.table_json})")
        for name, path in res.figures.items():
            print(f"{name}: {path}")
    return 3 if failed else 0
