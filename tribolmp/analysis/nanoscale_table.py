"""The nanoscale table the chain interpolates, built from the MCA campaign CSV (contract C6).

``docs/data/mca_campaign.csv`` has one row per MCA run (``workflows/mca_friction_sweep.py
--campaign``).  :func:`build_table` groups the runs of one law by (pressure, velocity), combines
the seeds and returns the table ``tribolmp/data/nanoscale_table.json`` ships::

    {"rows": [{"pressure_Pa", "sliding_velocity_m_s", "mu", "mu_err", "n_runs", "seeds",
               "steady", "runs", "mu_per_s", "mu_per_s_err", "mu_per_s_valid", ... ,
               optional "mu_static", "mu_kinetic" (+ _err) when the CSV has those columns}],
     "units": {...}, "provenance": {...}}

Combination per (P, V): the mean over seeds; its error the larger of the combined standard
errors ``sqrt(sum err^2)/n`` and the seed scatter ``std/sqrt(n)`` (n > 1).  An Eq. 23
coefficient is given only if the analysis marked it valid in every seed, else null with
``<c>_valid: false``.  A table never mixes laws nor dimensions (a 3D run at a 2D condition is
another experiment, not another seed).  The output depends on the CSV only (its
SHA-256 is recorded, no creation time), so rebuilding it is a byte-for-byte check.

Run ``python workflows/nanoscale_table.py`` to rebuild the shipped file.
"""

from __future__ import annotations

import csv
import hashlib
import json
import math
from pathlib import Path
from typing import Any

__all__ = ["COEFFICIENTS", "FRICTION_EXTRA", "build_table", "write_table"]

#: Eq. 23 coefficients of the 1D profile (contract C1) carried per row.
COEFFICIENTS = ("mu_per_s", "d0_m2_s", "dz", "dx_l2")
#: Static and kinetic friction coefficients, carried when the campaign measured them.
FRICTION_EXTRA = ("mu_static", "mu_kinetic")

_UNITS = {"pressure_Pa": "Pa", "sliding_velocity_m_s": "m/s", "mu": "1", "mu_err": "1",
          "mu_static": "1", "mu_kinetic": "1", "mu_per_s": "1/s", "d0_m2_s": "m^2/s",
          "dz": "m^3/s", "dx_l2": "m^5/s"}


def _combine(vals: list[float], errs: list[float]) -> tuple[float, float]:
    """Return the mean over seeds and its standard error (see the module docstring)."""
    n = len(vals)
    mean = sum(vals) / n
    se = math.sqrt(sum(e * e for e in errs)) / n
    if n > 1:
        sd = math.sqrt(sum((v - mean) ** 2 for v in vals) / (n - 1))
        se = max(se, sd / math.sqrt(n))
    return mean, se


def _number(text: str | None) -> float | None:
    return None if text in ("", None) else float(text)


def build_table(campaign: str | Path, *, law: str, description: str = "",
                source_name: str | None = None, dim: int = 2) -> dict[str, Any]:
    """Return the nanoscale table of one law's runs in the campaign CSV.

    Parameters
    ----------
    campaign : path
        The campaign CSV (columns of ``workflows/mca_friction_sweep.py``'s ``CAMPAIGN_COLUMNS``).
    law : str
        Bond law whose rows are used (e.g. ``"mca"``); a run without ``mu`` (failed) is skipped.
    description : str
        One line for the provenance (box, durations, where the study is documented).
    source_name : str, optional
        How the provenance names the CSV (default: the path as given).
    dim : {2, 3}
        Dimension of the runs used (the CSV's ``dim`` column); rows of the other are skipped.

    Returns
    -------
    dict
        ``rows`` sorted by (pressure, velocity), ``units``, ``provenance``.
    """
    path = Path(campaign)
    raw = path.read_bytes()
    rows = [r for r in csv.DictReader(raw.decode("utf-8").splitlines())
            if r.get("law") == law and r.get("dim") == str(dim)]
    groups: dict[tuple[float, float], list[dict]] = {}
    for r in rows:
        if _number(r.get("mu")) is None:
            continue
        groups.setdefault((float(r["pressure_Pa"]), float(r["sliding_velocity_m_s"])), []).append(r)
    if not groups:
        raise ValueError(f"{path}: no finished {dim}D run of law {law!r}")
    table_rows = []
    for (p, v), rs in sorted(groups.items()):
        mu, mu_err = _combine([float(r["mu"]) for r in rs],
                              [_number(r["mu_err"]) or 0.0 for r in rs])
        tr: dict[str, Any] = {
            "pressure_Pa": p, "sliding_velocity_m_s": v, "mu": mu, "mu_err": mu_err,
            "n_runs": len(rs), "seeds": sorted({int(r["seed"]) for r in rs}),
            "steady": all(r.get("mu_steady") == "True" for r in rs), "runs": [r["run"] for r in rs],
        }
        for c in COEFFICIENTS:
            ok = all(r.get(f"valid_{c}") == "True" and _number(r.get(c)) is not None for r in rs)
            if ok:
                tr[c], tr[f"{c}_err"] = _combine([float(r[c]) for r in rs],
                                                 [_number(r.get(f"{c}_err")) or 0.0 for r in rs])
            else:
                tr[c], tr[f"{c}_err"] = None, None
            tr[f"{c}_valid"] = ok
        for c in FRICTION_EXTRA:
            vals = [_number(r.get(c)) for r in rs]
            if all(x is not None for x in vals):
                errs = [_number(r.get(f"{c}_err")) or 0.0 for r in rs]
                tr[c], tr[f"{c}_err"] = _combine(vals, errs)
        table_rows.append(tr)
    # the MCA profiles' length bounds the wavelengths the Eq. 23 rows measured (the chain uses
    # them only for a part whose map resolves such a wavelength); the shortest box is stated
    lengths = [_number(r.get("box_length_m")) for rs in groups.values() for r in rs]
    lengths = [x for x in lengths if x is not None and x > 0]
    return {
        "rows": table_rows,
        "units": dict(_UNITS),
        "provenance": {
            "profile_length_m": min(lengths) if lengths else None,
            "source": source_name or str(campaign),
            "source_sha256": hashlib.sha256(raw).hexdigest(),
            "description": description,
            "laws": [law],
            "dims": sorted({r.get("dim") for rs in groups.values() for r in rs}),
            "builder": "tribolmp.analysis.nanoscale_table.build_table "
                       "(workflows/nanoscale_table.py)",
            "combination": "mean over seeds; error max(sqrt(sum err^2)/n, std/sqrt(n)); "
                           "Eq. 23 only if valid in all",
            "static_friction": "measured" if any("mu_static" in r for r in table_rows)
            else "not measured by the campaign (the chain states mu_s as an assumption)",
        },
    }


def write_table(table: dict[str, Any], out: str | Path) -> Path:
    """Write the table as indented JSON (the shipped layout) and return the path."""
    out = Path(out)
    out.write_text(json.dumps(table, indent=1) + "\n", encoding="utf-8")
    return out
