"""Figures of the 100 ns runs at the default size (docs/mca_study.md, "100 ns at the default size").

Usage::

    python workflows/mca_paper_figures.py RUN_DIR [RUN_DIR ...] [--out docs]

Each RUN_DIR is a finished ``tribolmp mca run --preset paper`` folder (its
``meta.json`` gives the pressure and the viscosity of the panel title).  Writes
``mca_paper_snapshots.png`` (the last frame of every run, coloured by body,
like the seed's Fig. 9) and ``mca_paper_mu.png`` (μ(t) with the steady window
and mean ± error of every run), one panel per run, into ``--out``.
Composition only: the drawing is :mod:`tribolmp.analysis.plots`.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path


def _label(run_dir: Path) -> str:
    meta = json.loads((run_dir / "meta.json").read_text())
    p = meta["params"]
    # the viscosity as mapped (runs written before it was a parameter record it there only)
    eta = ((meta.get("mapping") or {}).get("law") or {}).get("contact_viscosity")
    eta_s = f", eta {eta:g} Pa s" if eta is not None else ""
    return (
        f"{p['pressure'] / 1e6:g} MPa, {p['sliding_velocity']:g} m/s{eta_s}, "
        f"{meta.get('time_s', 0) / 1e-9:.0f} ns"
    )


def figures(run_dirs: list[Path], out: Path) -> tuple[Path, Path]:
    """Write the two multi-panel PNGs for ``run_dirs`` into ``out``; return their paths."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from tribolmp.analysis.plots import plot_friction, plot_snapshot

    n = len(run_dirs)
    out.mkdir(parents=True, exist_ok=True)
    snaps, mus = out / "mca_paper_snapshots.png", out / "mca_paper_mu.png"
    fig, axes = plt.subplots(n, 1, figsize=(9, 3.4 * n), squeeze=False)
    for ax, d in zip(axes[:, 0], run_dirs):
        plot_snapshot(d, ax=ax, title=f"{_label(d)}: last frame")
    fig.tight_layout()
    fig.savefig(snaps, dpi=110)
    plt.close(fig)
    fig, axes = plt.subplots(n, 1, figsize=(7, 2.8 * n), squeeze=False, sharex=True)
    for ax, d in zip(axes[:, 0], run_dirs):
        plot_friction(d, ax=ax, title=_label(d))
    fig.tight_layout()
    fig.savefig(mus, dpi=110)
    plt.close(fig)
    return snaps, mus


def main(argv: list[str] | None = None) -> int:
    """Command line: check the run folders (exit 2 with one line), write the PNGs."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("runs", nargs="+", type=Path, help="finished --preset paper run folders")
    ap.add_argument("--out", type=Path, default=Path("docs"), help="folder of the PNGs")
    args = ap.parse_args(argv)
    for d in args.runs:
        if not (d / "meta.json").is_file() or not (d / "friction.csv").is_file():
            print(f"mca_paper_figures: {d}: expected a finished MCA run folder "
                  "(meta.json, friction.csv)", file=sys.stderr)
            return 2
    for p in figures(args.runs, args.out):
        print(p)
    return 0


if __name__ == "__main__":
    sys.exit(main())
