"""Named registry of the small committed test data files (like MDAnalysisTests.datafiles).

Each entry is a folder under ``tests/data`` holding an MCA output directory
(``meta.json``, ``traj.lammpstrj``, ``friction.csv``) and ``expected.json``,
the exact answers the analyses must reproduce.  The files are produced by
``tests/data/generate_reference_data.py`` from the generators of
:mod:`tribolmp.analysis.synthetic` (the reference solutions live in the
package); :data:`RECIPES` records how, so a test can regenerate them and
check that the committed copy is current.
"""

from __future__ import annotations

import json
from pathlib import Path

DATA_DIR = Path(__file__).resolve().parent

#: name -> (generator in tribolmp.analysis.synthetic, seed, keyword arguments)
RECIPES: dict[str, dict] = {
    "tiny_transfer": {
        "generators": [
            (
                "make_transfer",
                dict(
                    n_per_row=8,
                    n_frames=20,
                    velocity=10.0,
                    t_transfer=6,
                    t_detach=8,
                    t_reattach=13,
                    n_flicker=0,
                    bond_events=((3, 3, 2), (9, 4, 0), (15, 0, 5)),
                ),
            ),
            (
                "make_friction",
                dict(
                    n=400,
                    dt=5e-12,
                    mu=0.25,
                    phi=0.5,
                    sigma_eps=0.02,
                    transient=0.3,
                    tau=1e-10,
                    normal=2e-9,
                    velocity=10.0,
                ),
            ),
        ],
        "seed": 20261122,
    },
}


def path(name: str) -> Path:
    """Folder of the dataset ``name`` (an MCA output directory)."""
    if name not in RECIPES:
        raise KeyError(f"unknown test dataset {name!r}; known: {sorted(RECIPES)}")
    return DATA_DIR / name


def expected(name: str) -> dict:
    """Return the exact answers stored with dataset ``name``."""
    return json.loads((path(name) / "expected.json").read_text())


def generate(name: str, out_dir: Path) -> dict:
    """Write dataset ``name`` into ``out_dir`` and return its expected answers."""
    import numpy as np

    from tribolmp.analysis import synthetic

    recipe = RECIPES[name]
    rng = np.random.default_rng(recipe["seed"])
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    answers: dict = {}
    for func, kwargs in recipe["generators"]:
        answers[func] = getattr(synthetic, func)(out_dir, rng, **kwargs)
    (out_dir / "expected.json").write_text(json.dumps(answers, indent=1, sort_keys=True) + "\n")
    return answers
