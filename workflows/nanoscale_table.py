"""Build the nanoscale table the chain interpolates from the MCA campaign CSV.

Usage::

    python workflows/nanoscale_table.py [--campaign docs/data/mca_campaign.csv] [--law mca]
        [--out tribolmp/data/nanoscale_table.json] [--dim 2] [--check]

Groups one law's runs by (pressure, velocity), combines seeds
(:func:`tribolmp.analysis.nanoscale_table.build_table`) and writes the JSON
shipped as ``tribolmp/data/nanoscale_table.json``.  ``--check`` writes nothing
and exits 1 when the shipped file differs from what the CSV gives.  No physics
here: only the library call and the file.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

#: Provenance line of the shipped table (the campaign of issue 14, docs/mca_study.md).
DESCRIPTION = ("reduced MCA study (issue 14), law mca, smoke box 47.5 nm x 2 x 15 nm "
               "(rotated upper body), 2D, 20 ns per run, contact viscosity 0.175 Pa s "
               "(calibrated to a 10 nm layer) at dt_factor 0.05; docs/mca_study.md")


def main(argv=None) -> int:
    """Parse arguments, build the table, write or check it; return an exit code."""
    from tribolmp.analysis.nanoscale_table import build_table, write_table

    root = Path(__file__).resolve().parent.parent
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--campaign", default=str(root / "docs/data/mca_campaign.csv"),
                    help="campaign CSV")
    ap.add_argument("--law", default="mca", help="bond law whose runs make the table")
    ap.add_argument("--dim", type=int, default=2, choices=(2, 3), help="dimension of the runs used")
    ap.add_argument("--description", default=DESCRIPTION, help="provenance line")
    ap.add_argument("--out", default=str(root / "tribolmp/data/nanoscale_table.json"),
                    help="output JSON")
    ap.add_argument("--check", action="store_true", help="compare with --out instead of writing it")
    args = ap.parse_args(argv)
    table = build_table(args.campaign, law=args.law, description=args.description,
                        source_name="docs/data/mca_campaign.csv", dim=args.dim)
    out = Path(args.out)
    if args.check:
        same = out.is_file() and json.loads(out.read_text()) == table
        print(f"{out}: {'up to date' if same else 'differs from ' + args.campaign}")
        return 0 if same else 1
    write_table(table, out)
    print(f"wrote {out} ({len(table['rows'])} rows, law {args.law})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
