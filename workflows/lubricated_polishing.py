"""Lubricated polishing workflow: roughness against time for a scene (thin wrapper, no physics).

Usage::

    python workflows/lubricated_polishing.py [SCENE.toml] --out DIR [--steps N] [--grid-points N]
    [--seed S]

Equivalent to ``tribolmp lubrication polish``; see docs/lubrication.md.
"""

from __future__ import annotations

import sys


def main(argv=None) -> int:
    """Run ``tribolmp lubrication polish`` with ``argv`` and return its exit code."""
    from tribolmp.cli import main as cli_main

    return cli_main(["lubrication", "polish", *(sys.argv[1:] if argv is None else argv)])


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(main())
