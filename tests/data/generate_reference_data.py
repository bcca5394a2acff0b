"""Regenerate the committed test data: ``python tests/data/generate_reference_data.py [NAME ...]``.

Names:

* each dataset of :data:`tests.data.RECIPES` (written into ``tests/data/<name>/``
  from :mod:`tribolmp.analysis.synthetic` with its fixed seed);
* ``contact`` -- the resolved rough-contact references of
  :mod:`tests.data.contact_references` (all classes; ``contact:CLASS`` for one,
  merged into the existing file) -> ``tests/data/contact_references.json``
  (``contact-coarse`` adds missing coarse-grid runs of maps 1+ to an existing file;
  ``contact-light:CLASS`` runs a class with 256^2 maps, for a crowded machine),
  then the summary ``contact-summary`` (no new solves): the MDR ratio table
  (``tests/data/contact_ratio_table.md``) and the planner's speed-error table
  ``tribolmp/data/contact_speed_error.json``; ``contact-fingerprint`` stores (no solves) the
  fingerprint of every map's base-grid height map (:func:`map_fingerprint`) next to its
  curves, which the tests check.  Run it with ``nice -n 10``: one class
  at 512^2 took 11-12 min of wall time on the shared 2-core machine (load 5-7), most of it the
  rigid-punch BEM (zero-padded 1024^2 FFTs).

Default: all.  Run it after a deliberate change of a generator or a solver, and commit the result.
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

import os  # noqa: E402

from tests.data import DATA_DIR, RECIPES, generate  # noqa: E402

# TRIBOLMP_CONTACT_JSON: write the contact classes elsewhere (parallel runs, merged by
# "contact-merge:A,B")
CONTACT_JSON = Path(os.environ.get("TRIBOLMP_CONTACT_JSON", DATA_DIR / "contact_references.json"))


#: seed of the fixed +-1 masks of :func:`map_fingerprint` (part of the fingerprint's definition)
FINGERPRINT_SEED = 20261202


def map_fingerprint(h) -> list[float]:
    """Numerical fingerprint of a height map: 9 numbers that change with any pixel of it.

    ``[mean, std, min, max, rms slope (one-pixel differences, per pixel), and the
    means of h times four fixed random +-1 masks (seed FINGERPRINT_SEED)]``, all
    in units of the map's heights (m).  Unlike a byte hash of the floats it is
    insensitive to round-off (FFT libraries, platforms): it is compared with a
    relative tolerance, while one pixel changed by its rms moves the mask means
    by ~ 1/n^2 of the rms (4e-6 on 512^2), far above round-off (1e-15).
    """
    import numpy as np

    h = np.asarray(h, dtype=float)
    masks = np.random.default_rng(FINGERPRINT_SEED).integers(0, 2, (4,) + h.shape) * 2 - 1
    slope = np.sqrt(np.mean(np.diff(h, axis=0) ** 2) + np.mean(np.diff(h, axis=1) ** 2))
    return [
        float(h.mean()),
        float(h.std()),
        float(h.min()),
        float(h.max()),
        float(slope),
        *(float(np.mean(h * mk)) for mk in masks),
    ]


def _fingerprint_class(cls: dict) -> None:
    """Store ``map_fingerprint`` (base grid) in every map of a class (no solves)."""
    from tests.data import contact_references as cr

    nb = cr.n_base(cls)
    for m in cls["maps"]:
        h, _ = cr.reference_surface(cls["recipe"], m["seed"], nb)
        m["map_fingerprint"] = dict(n=nb, values=map_fingerprint(h))


def _contact_fingerprints() -> None:
    refs = json.loads(CONTACT_JSON.read_text())
    for cls in refs["classes"].values():
        _fingerprint_class(cls)
    CONTACT_JSON.write_text(json.dumps(refs, indent=None, separators=(",", ":")) + "\n")


def _contact(classes: list[str], base: int | None = None) -> None:
    from tests.data import contact_references as cr

    refs = json.loads(CONTACT_JSON.read_text()) if CONTACT_JSON.exists() else {}
    refs.setdefault("classes", {})
    refs["setup"] = dict(
        side_m=cr.SIDE,
        E_star_Pa=cr.E_STAR,
        k_s=cr.K_S,
        n_base=cr.N_BASE,
        n_study=list(cr.N_STUDY),
        n_mdr=list(cr.N_MDR),
        mdr_realizations=cr.MDR_REALIZATIONS,
        bem_tol=cr.BEM_TOL,
        reduced_pressures=list(cr.REDUCED_PRESSURES),
        note=(
            "stiffness N/m of the L x L cell (periodic) or L x L rigid punch; mean_gap m; "
            "time_s per pressure"
        ),
    )
    for name in classes:
        t0 = time.perf_counter()
        print(f"contact class {name} ...", flush=True)
        refs["classes"][name] = cr.run_class(
            name, log=lambda s: print(s, flush=True), base=base or cr.N_BASE
        )
        _fingerprint_class(refs["classes"][name])  # the maps these curves were computed from
        refs["created_utc"] = time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())
        CONTACT_JSON.write_text(
            json.dumps(refs, indent=None, separators=(",", ":")) + "\n"
        )  # saved after every class
        print(f"contact class {name}: {time.perf_counter() - t0:.0f} s wall", flush=True)


def _contact_coarse() -> None:
    """Add the coarse-grid periodic runs of maps 1, 2 to classes generated without them."""
    from tests.data import contact_references as cr

    refs = json.loads(CONTACT_JSON.read_text())
    for name, cls in refs["classes"].items():
        cr.extend_coarse(cls)
        print(f"contact class {name}: coarse grids of maps 1+ done", flush=True)
    CONTACT_JSON.write_text(json.dumps(refs, indent=None, separators=(",", ":")) + "\n")


def _contact_summary() -> None:
    from tests.data import contact_references as cr

    refs = json.loads(CONTACT_JSON.read_text())
    md, table = cr.summarise(refs)
    (DATA_DIR / "contact_ratio_table.md").write_text(md)
    out = Path(__file__).resolve().parents[2] / "tribolmp" / "data" / "contact_speed_error.json"
    out.write_text(json.dumps(table, indent=2) + "\n")
    print(md)


def main(argv=None) -> int:
    """Regenerate the named datasets (default: all)."""
    from tests.data import contact_references as cr

    names = list(argv if argv is not None else sys.argv[1:]) or sorted(RECIPES) + ["contact"]
    for name in names:
        if name == "contact":
            _contact(list(cr.CLASSES))
            _contact_coarse()
            _contact_summary()
        elif name.startswith("contact-light:"):
            _contact([name.split(":", 1)[1]], base=256)
        elif name.startswith("contact:"):
            _contact([name.split(":", 1)[1]])
        elif name.startswith("contact-merge:"):
            refs = json.loads(CONTACT_JSON.read_text())
            for part in name.split(":", 1)[1].split(","):
                refs["classes"].update(json.loads(Path(part).read_text())["classes"])
            CONTACT_JSON.write_text(json.dumps(refs, indent=None, separators=(",", ":")) + "\n")
        elif name == "contact-fingerprint":
            _contact_fingerprints()
        elif name == "contact-coarse":
            _contact_coarse()
        elif name == "contact-summary":
            _contact_summary()
        else:
            answers = generate(name, DATA_DIR / name)
            size = sum(p.stat().st_size for p in (DATA_DIR / name).iterdir())
            print(f"{name}: {size / 1024:.0f} KiB, expected {sorted(answers)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
