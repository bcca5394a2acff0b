"""Which rough-contact solver to run.

The measured speed-against-error table behind ``method = "auto"``.

The table ``tribolmp/data/contact_speed_error.json`` is written by
``tests/data/generate_reference_data.py`` from the resolved rough-surface
references (``tests/data/contact_references.json``): for each method (``mdr``
ensemble, ``bem`` periodic cell), mesh (grid points per side of the height
map; MDR: the line of that many springs) and range of the *reduced pressure*
``p / (E* h'_rms)`` (``h'_rms`` the rms gradient of the surface, the one
combination on which a frictionless linear-elastic contact depends, see
docs/contact.md), the worst relative stiffness error over the surface classes
and the wall time per pressure.  MDR rows also carry the largest fraction of
fully closed MDR lines seen in their range: above
:data:`~.rough.CLOSED_FRACTION_LIMIT` MDR returns the punch limit ``E* L``,
so it is never picked there.
"""

from __future__ import annotations

import json
import math
from importlib import resources
from typing import Any

from .rough import CLOSED_FRACTION_LIMIT

__all__ = [
    "speed_error_table",
    "choose_method",
    "choose_method_for_scene",
    "reduced_pressures",
    "reduced_pressures_of_scene",
]


def speed_error_table() -> dict[str, Any] | None:
    """Return the shipped speed-against-error table, or None if absent/unreadable."""
    ref = resources.files("tribolmp") / "data" / "contact_speed_error.json"
    try:
        return json.loads(ref.read_text())
    except (OSError, ValueError):
        return None


def reduced_pressures(pressures, E_star: float, rms_gradient: float) -> list[float]:
    """``p / (E* h'_rms)`` (1) of each nominal pressure (Pa)."""
    return [float(p) / (float(E_star) * float(rms_gradient)) for p in pressures]


def reduced_pressures_of_scene(scene) -> list[float] | None:
    """Reduced pressures of a rough scene (None for an axisymmetric one).

    The rms gradient is the closed form of the scene's ``[roughness]`` PSD, or
    measured from its ``surface_file``.  A surface evolved by the topography
    stage is not known at planning time; its initial ``[roughness]`` is used.
    """
    if getattr(scene.geometry, "profile", None) != "rough" or scene.roughness is None:
        return None
    from ...errors import TribolmpError
    from .rough import rms_gradient, rms_gradient_of_psd

    r = scene.roughness
    try:
        if r.surface_file:
            from .solve import load_surface

            h, dx = load_surface(r.surface_file)
            grad = rms_gradient(h, dx if dx is not None else r.pixel_size)
        else:
            grad = rms_gradient_of_psd(
                r.rms_height, r.hurst, r.rolloff_wavelength, r.short_cutoff_wavelength
            )
    except (TribolmpError, OSError, ValueError):
        return None  # an unreadable map is reported by the contact stage itself, not by planning
    if not grad > 0:
        return (
            None  # a flat surface has no roughness scale: the choice then uses every pressure range
        )
    return reduced_pressures(scene.load.pressures, scene.effective_modulus, grad)


def _overlaps(row: dict, lo: float, hi: float) -> bool:
    rng = row.get("reduced_pressure_range")
    return rng is None or (rng[0] <= hi and rng[1] >= lo)


def _distance(row: dict, lo: float, hi: float) -> float:
    a, b = row["reduced_pressure_range"]
    return max(math.log(a / hi), math.log(lo / b), 0.0)


def choose_method(
    tolerance: float,
    table: dict[str, Any] | None = None,
    *,
    reduced_pressures: list[float] | None = None,
    closed_fraction: float | None = None,
) -> dict[str, Any]:
    """Cheapest measured (method, mesh) that meets ``tolerance``.

    Its stiffness error over the asked pressures is within ``tolerance``.

    Parameters
    ----------
    tolerance : float
        Acceptable relative error of the contact stiffness (1).
    table : dict, optional
        ``{"rows": [{"method", "mesh", "rel_error", "time_s",
        "reduced_pressure_range": [lo, hi], "closed_fraction_max"}, ...]}``
        (default: the shipped table).  Rows without a range apply to every
        pressure.
    reduced_pressures : list of float, optional
        ``p / (E* h'_rms)`` of the scene's pressures: each (method, mesh) is
        judged by its worst error over the rows whose range overlaps
        ``[min, max]`` of these (the nearest row when none does, said in ``why``).
    closed_fraction : float, optional
        Measured fraction of closed MDR lines (e.g. from a previous MDR run);
        above :data:`~.rough.CLOSED_FRACTION_LIMIT` MDR is not picked.

    Returns
    -------
    dict
        ``method``, ``mesh``, ``expected_error``, ``expected_time_s`` (per
        pressure), ``reduced_pressure_range`` (the asked one or None) and a
        one-line ``why``.
    """
    if table is None:
        table = speed_error_table()
    rows = [
        r
        for r in (table or {}).get("rows", [])
        if r.get("rel_error") is not None and r.get("time_s") is not None
    ]
    asked = None
    if reduced_pressures:
        asked = (min(reduced_pressures), max(reduced_pressures))
    if not rows:
        return {
            "method": "mdr",
            "mesh": None,
            "expected_error": None,
            "expected_time_s": None,
            "reduced_pressure_range": asked,
            "why": "no measured speed-error table shipped; MDR "
                   "with [contact].springs (error not quantified)",
        }
    groups: dict[tuple[str, Any], list[dict]] = {}
    for r in rows:
        groups.setdefault((r["method"], r["mesh"]), []).append(r)
    cands, notes = [], []
    for (method, mesh), rs in groups.items():
        use = rs
        extrapolated = False
        if asked is not None:
            use = [r for r in rs if _overlaps(r, *asked)]
            if not use:
                ranged = [r for r in rs if r.get("reduced_pressure_range")]
                d = min(_distance(r, *asked) for r in ranged)
                use = [r for r in ranged if _distance(r, *asked) == d]
                extrapolated = True
        closed = max((r.get("closed_fraction_max") or 0.0) for r in use)
        if method == "mdr" and closed_fraction is not None:
            closed = max(closed, closed_fraction)
        if method == "mdr" and closed > CLOSED_FRACTION_LIMIT:
            notes.append(
                f"MDR excluded: {closed:.0%} of its lines "
                "close in this pressure range (punch limit)"
            )
            continue
        cands.append({"method": method, "mesh": mesh, "rel_error": max(r["rel_error"] for r in use),
                      "time_s": max(r["time_s"] for r in use), "extrapolated": extrapolated})
    if not cands:
        return {
            "method": "bem",
            "mesh": None,
            "expected_error": None,
            "expected_time_s": None,
            "reduced_pressure_range": asked,
            "why": "; ".join(sorted(set(notes)))
            + "; no other measured solver: BEM at the scene's grid",
        }
    ok = [c for c in cands if c["rel_error"] <= tolerance]
    where = "" if asked is None else f" at p/(E* h'rms) {asked[0]:.3g}-{asked[1]:.3g}"
    if ok:
        best = min(ok, key=lambda c: (c["time_s"], c["rel_error"]))
        why = (
            "cheapest measured solver within tolerance "
            f"{tolerance:g}{where}: {best['method']} mesh {best['mesh']} "
            f"(measured error {best['rel_error']:.3g}, {best['time_s']:.3g} s)"
        )
    else:
        best = min(cands, key=lambda c: (c["rel_error"], c["time_s"]))
        why = (
            f"no measured solver reaches tolerance {tolerance:g}{where}; "
            f"most accurate is {best['method']} mesh "
            f"{best['mesh']} (measured error {best['rel_error']:.3g})"
        )
    if best["extrapolated"]:
        why += " (outside the measured pressure range: nearest measured range used)"
    elif asked is not None:
        spans = [r["reduced_pressure_range"] for r in rows if r.get("reduced_pressure_range")]
        if spans and (asked[0] < min(a for a, _ in spans) or asked[1] > max(b for _, b in spans)):
            why += (
                " (the measured range is p/(E* h'rms) "
                f"{min(a for a, _ in spans):.3g}-{max(b for _, b in spans):.3g};"
                " pressures outside it use the nearest range)"
            )
    if notes:
        why += "; " + "; ".join(sorted(set(notes)))
    return {"method": best["method"], "mesh": best["mesh"], "expected_error": best["rel_error"],
            "expected_time_s": best["time_s"], "reduced_pressure_range": asked, "why": why}


def choose_method_for_scene(scene, table: dict[str, Any] | None = None) -> dict[str, Any]:
    """Return the ``auto`` choice for a scene.

    The measured rough-surface table, or MDR for an axisymmetric profile.

    The table measures rough contacts only.  For a sphere, cone, flat punch or power-law profile
    the MDR is exact (Popov & Hess; Hertz force error 4e-7 at 1999 springs, docs/contact.md), so
    it is the choice at ``[contact].springs``.
    """
    tol = float(scene.contact.tolerance)
    if getattr(scene.geometry, "profile", None) != "rough":
        return {
            "method": "mdr",
            "mesh": None,
            "expected_error": None,
            "expected_time_s": None,
            "reduced_pressure_range": None,
            "why": f"MDR is exact for the axisymmetric {scene.geometry.profile} "
                   "profile (rough-surface table not applicable)",
        }
    return choose_method(tol, table, reduced_pressures=reduced_pressures_of_scene(scene))
