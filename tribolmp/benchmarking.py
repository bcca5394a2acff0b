"""Small helpers shared by the ``benchmarks/`` scripts: CSV output and console tables.

Benchmarks print a table (resolution, wall time, error against a reference)
and write the same rows as CSV; both go through these two functions so that
every table in ``benchmarks/results/`` has the same layout.
"""

from __future__ import annotations

import csv
from collections.abc import Sequence
from pathlib import Path

__all__ = ["write_csv", "print_table"]


def write_csv(path: str | Path, rows: Sequence[dict]) -> Path:
    """Write ``rows`` (dicts) as CSV; columns are the union of keys in first-seen order.

    Parameters
    ----------
    path : str or Path
        Output file; parent folders are created.
    rows : sequence of dict
        One dict per table row.

    Returns
    -------
    Path
        The file written.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    keys: list[str] = []
    for r in rows:
        keys += [k for k in r if k not in keys]
    with path.open("w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=keys)
        w.writeheader()
        w.writerows(rows)
    return path


def print_table(title: str, rows: Sequence[dict], width: int = 16) -> None:
    """Print ``rows`` as a fixed-width table under a ``== title`` heading."""
    print(f"\n== {title}")
    if not rows:
        return
    keys = list(rows[0])
    print(" ".join(f"{k[:width]:>{width}s}" for k in keys))
    for r in rows:
        cells = []
        for k in keys:
            v = r.get(k, "")
            is_num = isinstance(v, float) or (
                hasattr(v, "dtype") and getattr(v.dtype, "kind", "") == "f"
            )
            cells.append(f"{float(v):>{width}.5g}" if is_num else f"{str(v):>{width}s}")
        print(" ".join(cells))
