"""``tribolmp run [SCENE.toml] [--out DIR] [--force [STAGE]]``: the multiscale chain.

Without a scene it runs the embedded default (the seed's steel-steel couple,
scaled to run here).  Progress goes to stderr; ``report.md``, ``report.json``,
``figures/`` and ``cache/`` go to ``--out``.
"""

from __future__ import annotations

HELP = "run a scene through the multiscale chain (default: the embedded scene)"

STAGE_CHOICES = ("nanoscale", "topography", "contact", "lubrication", "macroscale", "tribospectroscopy", "all")


def configure(parser) -> None:
    """Add arguments."""
    parser.add_argument("scene", nargs="?", default=None, help="TOML scene file (default: the embedded steel-steel scene)")
    parser.add_argument("--out", default="tribolmp-run", help="output folder (default: ./tribolmp-run)")
    parser.add_argument(
        "--force",
        nargs="?",
        const="all",
        action="append",
        choices=STAGE_CHOICES,
        metavar="STAGE",
        help="recompute STAGE (repeatable) or, without a name, every stage, ignoring the cache",
    )
    parser.add_argument("--cache-dir", default=None, help="share a stage cache between runs (default: OUT/cache)")
    parser.add_argument("--plan", action="store_true", help="print the plan (what would run and why) and exit")
    parser.add_argument("--no-figures", action="store_true", help="skip the PNG figures")
    parser.add_argument("--quiet", action="store_true", help="no progress output")
    parser.add_argument("--json", action="store_true", help="print report.json's stages list as JSON on stdout")


def _terminate_as_interrupt(signum, frame):  # pragma: no cover - exercised by a subprocess test
    raise KeyboardInterrupt


def run(args) -> int:
    """Plan and run the scene; print a summary; return 0 (failures raise one-line errors)."""
    import signal
    from pathlib import Path

    from ..chain import plan_scene
    from ..chain.runner import run_chain
    from ..scene import default_scene, load_scene
    from . import emit_json

    scene = load_scene(args.scene) if args.scene else default_scene()
    if args.plan:
        plan = plan_scene(scene)
        if args.json:
            emit_json({"scene": scene.source, "plan": plan.to_json_dict()})
        else:
            for s in plan.stages:
                print(f"{s.name:18s} {'RUN ' if s.run else 'skip'}  {s.reason}")
        return 0
    force = set(args.force or ())
    force_arg = True if "all" in force else force
    # A kill (SIGTERM) unwinds like Ctrl-C, so the report records the interrupted stage;
    # committed stages are safe either way (atomic renames).
    signal.signal(signal.SIGTERM, _terminate_as_interrupt)
    out = Path(args.out)
    chain = run_chain(
        scene,
        out,
        force=force_arg,
        cache_dir=args.cache_dir,
        quiet=args.quiet,
        figures=False if args.no_figures else None,
    )
    if args.json:
        import json

        emit_json(json.loads((out / "report.json").read_text())["stages"])
    else:
        ran = [e.name for e in chain.entries.values() if e.ran]
        print(f"{scene.scene.name}: {len(ran)} stage(s) ran ({', '.join(ran)}) in {chain.wall_time_s:.1f} s")
        for e in chain.entries.values():
            if not e.ran:
                print(f"  skipped {e.name}: {e.reason}")
        print(f"report: {out / 'report.md'}  data: {out / 'report.json'}")
    return 0
