"""Run a scene through the multiscale chain: a thin script over :mod:`tribolmp.chain`.

Usage::

    python workflows/multiscale_chain.py [SCENE.toml] [--out DIR] [--force STAGE] [--plan]

Equivalent to ``tribolmp run``; kept as a script so that the chain can be
driven (or copied and adapted) without the CLI.  No physics here: it only
loads a scene, plans it and runs the library's stages.
"""

from __future__ import annotations

import argparse
import sys


def main(argv=None) -> int:
    """Parse arguments, run the chain, print where the report is; return an exit code."""
    from tribolmp.chain import STAGES, plan_scene, run_chain
    from tribolmp.errors import RunError, SetupError
    from tribolmp.scene import default_scene, load_scene

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "scene", nargs="?", help="TOML scene (default: the embedded steel-steel scene)"
    )
    parser.add_argument("--out", default="tribolmp-run", help="output folder")
    parser.add_argument(
        "--force", action="append", choices=STAGES, default=[], help="recompute this stage"
    )
    parser.add_argument("--plan", action="store_true", help="only print the plan")
    args = parser.parse_args(argv)
    try:
        scene = load_scene(args.scene) if args.scene else default_scene()
        if args.plan:
            for s in plan_scene(scene).stages:
                print(f"{s.name:18s} {'RUN ' if s.run else 'skip'}  {s.reason}")
            return 0
        run = run_chain(scene, args.out, force=args.force)
    except SetupError as exc:
        print(f"multiscale_chain: {exc}", file=sys.stderr)
        return 2
    except RunError as exc:
        print(f"multiscale_chain: {exc}", file=sys.stderr)
        return 3
    print(
        f"{len([e for e in run.entries.values() if e.ran])} "
        f"stage(s) ran; report: {run.out_dir / 'report.md'}"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
