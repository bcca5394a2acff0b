"""Regenerate the committed test data: ``python tests/data/generate_reference_data.py [NAME ...]``.

Writes each dataset of :data:`tests.data.RECIPES` into ``tests/data/<name>/``
from :mod:`tribolmp.analysis.synthetic` with its fixed seed.  Run it after a
deliberate change of a generator, and commit the result.
"""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from tests.data import DATA_DIR, RECIPES, generate  # noqa: E402


def main(argv=None) -> int:
    """Regenerate the named datasets (default: all)."""
    names = list(argv if argv is not None else sys.argv[1:]) or sorted(RECIPES)
    for name in names:
        answers = generate(name, DATA_DIR / name)
        size = sum(p.stat().st_size for p in (DATA_DIR / name).iterdir())
        print(f"{name}: {size / 1024:.0f} KiB, expected {sorted(answers)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
