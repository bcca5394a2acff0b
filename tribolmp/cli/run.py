"""``tribolmp run [SCENE.toml] [--out DIR] [--force [STAGE]]``: the multiscale chain.

Without a scene it runs the embedded default (the seed's steel-steel couple,
scaled to run here).  Progress goes to stderr; ``report.md``, ``report.json``,
``figures/`` and ``cache/`` go to ``--out``.
"""

from __future__ import annotations

import sys

HELP = "run a scene through the multiscale chain (default: the embedded scene)"



def configure(parser) -> None:
    """Add arguments (the ``--force`` choices are the registry's stage names)."""
    from ..chain.registry import STAGES

    parser.add_argument(
        "scene",
        nargs="?",
        default=None,
        help="TOML scene file (default: the embedded steel-steel scene)",
    )
    parser.add_argument(
        "--out", default="tribolmp-run", help="output folder (default: ./tribolmp-run)"
    )
    parser.add_argument(
        "--force",
        nargs="?",
        const="all",
        action="append",
        choices=(*STAGES, "all"),
        metavar="STAGE",
        help="recompute STAGE (repeatable) or, without a name, every stage, ignoring the cache",
    )
    parser.add_argument(
        "--cache-dir", default=None, help="share a stage cache between runs (default: OUT/cache)"
    )
    parser.add_argument(
        "--plan", action="store_true", help="print the plan (what would run and why) and exit"
    )
    parser.add_argument("--no-figures", action="store_true", help="skip the PNG figures")
    parser.add_argument("--quiet", action="store_true", help="no progress output")
    parser.add_argument(
        "--json", action="store_true", help="print report.json's stages list as JSON on stdout"
    )


def _terminate_as_interrupt(signum, frame):  # pragma: no cover - exercised by a subprocess test
    raise KeyboardInterrupt


def run(args) -> int:
    """Plan and run the scene; print a summary; return 0 (failures raise one-line errors)."""
    import signal

    from ..chain import plan_scene
    from ..chain.runner import run_chain
    from ..locking import prepare_dir
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
    # Checked on the raw text (Path("") is ".", which would silently write into the working
    # folder) and after the scene, so an invalid scene creates nothing.
    if args.cache_dir is not None:
        prepare_dir(args.cache_dir, "--cache-dir")
    out = prepare_dir(args.out, "--out")
    force = set(args.force or ())
    force_arg = True if "all" in force else force
    # A kill (SIGTERM) unwinds like Ctrl-C, so the report records the interrupted stage;
    # committed stages are safe either way (atomic renames).
    signal.signal(signal.SIGTERM, _terminate_as_interrupt)
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
        print(summary_text(chain))
        print(f"report: {out / 'report.md'}  data: {out / 'report.json'}")
    for line in stage_warnings(chain):
        print(f"warning: {line}", file=sys.stderr)
    return 0


def summary_text(chain) -> str:
    """Which stages were computed, which came from the cache, which were skipped (several lines)."""
    computed = [e.name for e in chain.entries.values() if e.status == "computed"]
    cached = [e.name for e in chain.entries.values() if e.status == "cached"]
    lines = [
        f"{chain.scene.scene.name}: {len(computed)} stage(s) "
        f"computed ({', '.join(computed) or 'none'}), "
        f"{len(cached)} from the cache ({', '.join(cached) or 'none'}) in {chain.wall_time_s:.1f} s"
    ]
    lines += [f"  skipped {e.name}: {e.reason}" for e in chain.entries.values() if not e.ran]
    return "\n".join(lines)


def stage_warnings(chain) -> list[str]:
    """Return the warnings a stage recorded.

    For example the nanoscale stage's 'not steady'; each is prefixed by the stage name.
    """
    out = []
    for e in chain.entries.values():
        if e.cached is None:
            continue
        values = e.cached.values
        warns = list(values.get("warnings") or e.cached.record.get("warnings") or [])
        if e.name == "nanoscale" and values.get("mu_steady") is False:
            warns.insert(
                0,
                "friction coefficient is NOT steady: mu is the mean of the second half of the run",
            )
        out += [f"{e.name}: {w}" for w in warns]
    return out
