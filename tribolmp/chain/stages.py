"""The six stages of the chain: thin adapters from scene + upstream hand-off files to model calls.

Each stage function takes a :class:`StageContext` and returns a
:class:`StageOutput` (numbers in SI with their units, plus the hand-off files
it wrote into ``ctx.workdir``).  No physics lives here: every number comes from
a model package, imported lazily inside the stage so that a scene imports only
the models it needs.  A model package that is not installed makes the stage
raise :class:`ModelUnavailable`, which the report records as
``ran: false, reason: "model not available: ..."`` instead of inventing numbers.
"""

from __future__ import annotations

import importlib
import json
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from types import ModuleType
from typing import Any

import numpy as np

from ..scene import Scene
from .cache import CachedStage, atomic_write_json
from .planner import StagePlan

__all__ = ["StageContext", "StageOutput", "ModelUnavailable", "STAGE_FUNCS", "require_model"]


class ModelUnavailable(Exception):
    """The model package a stage needs is not installed (or lacks the contract API)."""


@dataclass
class StageContext:
    """Everything a stage may use: the scene, its plan, a working folder, upstream results, an RNG."""

    scene: Scene
    plan: StagePlan
    workdir: Path
    upstream: dict[str, CachedStage]
    rng: np.random.Generator
    seed: list[int]
    progress: Callable[..., None] = lambda frac, what="": None


@dataclass
class StageOutput:
    """What a stage hands on: SI numbers with units and files (names relative to the workdir)."""

    values: dict[str, Any]
    units: dict[str, str] = field(default_factory=dict)
    files: dict[str, str] = field(default_factory=dict)
    method: str = ""
    message: str = ""
    nit: int = 0
    provenance: dict[str, Any] = field(default_factory=dict)


def require_model(module: str, *names: str) -> ModuleType:
    """Import ``module`` and check it exposes ``names``; raise :class:`ModelUnavailable` otherwise."""
    try:
        mod = importlib.import_module(module)
    except ImportError as exc:
        raise ModelUnavailable(f"{module} ({' '.join(str(exc).split())})") from None
    missing = [n for n in names if not hasattr(mod, n)]
    if missing:
        raise ModelUnavailable(f"{module} lacks {', '.join(missing)}")
    return mod


def _scalars(d: dict[str, Any]) -> dict[str, Any]:
    """JSON-friendly copy of the scalar (and short list) entries of a result."""
    out = {}
    for k, v in d.items():
        if isinstance(v, (np.floating, np.integer)):
            v = v.item()
        if isinstance(v, (bool, int, float, str)) or v is None:
            out[k] = v
        elif isinstance(v, np.ndarray) and v.size <= 64:
            out[k] = v.tolist()
        elif isinstance(v, (list, tuple)) and len(v) <= 64 and all(isinstance(x, (int, float, np.floating)) for x in v):
            out[k] = [float(x) for x in v]
    return out


def _rates_from_upstream(ctx: StageContext) -> tuple[dict[str, Any] | None, str]:
    """The rates dict and where it came from: nanoscale's rates.json, the scene's [rates], or none."""
    if "nanoscale" in ctx.upstream:
        path = ctx.upstream["nanoscale"].file("rates")
        return json.loads(path.read_text()), str(path)
    if ctx.scene.rates is not None:
        rates = ctx.scene.to_dict()["rates"]
        # The hand-off is a file even when the scene gives the rates, so every stage reads rates the same way.
        rates["units"] = {
            "mu": "1", "diffusion_m2_s": "m^2/s", "transfer_rate": "1/m", "wear_rate": "1/s",
            "layer_depth_m": "m", "step_length_m": "m", "step_time_s": "s",
        }
        atomic_write_json(ctx.workdir / "rates.json", rates)
        return rates, "[rates]"
    return None, ""


def _friction_coefficient(ctx: StageContext) -> tuple[float, str]:
    """mu from nanoscale / [rates] when present, else [load].friction_coefficient."""
    rates, src = _rates_from_upstream(ctx)
    if rates is not None and rates.get("mu") is not None:
        return float(rates["mu"]), src
    return ctx.scene.load.friction_coefficient, "[load].friction_coefficient"


STAGE_FUNCS: dict[str, Callable[[StageContext], StageOutput]] = {}


def _stage(name: str):
    def deco(func):
        STAGE_FUNCS[name] = func
        return func

    return deco


# ---------------------------------------------------------------- nanoscale


@_stage("nanoscale")
def nanoscale(ctx: StageContext) -> StageOutput:
    """LAMMPS MCA friction run -> ``rates.json`` (plus friction.csv, trajectory, meta.json)."""
    from ..rng import lammps_seed

    mca = require_model("tribolmp.lammps.mca", "run_mca", "params_from_scene")
    params = mca.params_from_scene(ctx.scene)
    out = ctx.workdir / "mca"
    # An interrupted run left restart files in the (kept) partial folder: continue from them.
    resume = out.is_dir() and any(out.iterdir())
    res = mca.run_mca(params, out, seed=lammps_seed(ctx.rng), resume=resume, np=ctx.scene.nanoscale.ranks)
    rates_path = out / "rates.json"
    if not rates_path.exists():
        raise RuntimeError(f"run_mca finished without writing {rates_path.name}")
    rates = json.loads(rates_path.read_text())
    meta = json.loads((out / "meta.json").read_text()) if (out / "meta.json").exists() else {}
    values = {k: v for k, v in _scalars(rates).items()}
    values["meta"] = _scalars(meta)
    files = {"rates": "mca/rates.json"}
    for key, name in (("friction", "friction.csv"), ("traj", "traj.lammpstrj"), ("meta", "meta.json"), ("log", "run.log")):
        if (out / name).exists():
            files[key] = f"mca/{name}"
    units = dict(rates.get("units", {}))
    return StageOutput(
        values=values,
        units=units,
        files=files,
        method=str(res.get("method", "mca")),
        message=str(res.get("message", "")),
        nit=int(res.get("nit", 0) or 0),
        provenance={"lammps_seed_from": ctx.seed, "resumed": resume, "params": _scalars(dict(getattr(params, "__dict__", {})))},
    )


# --------------------------------------------------------------- topography


@_stage("topography")
def topography(ctx: StageContext) -> StageOutput:
    """Eq. 23 with the upstream rates -> final height map (``surface.npy`` + sidecar JSON) and its PSD."""
    topo = require_model("tribolmp.models.topography", "params_from_scene", "evolve", "save_height_map")
    rates, rates_src = _rates_from_upstream(ctx)
    params = topo.params_from_scene(ctx.scene, rates=rates)
    res = topo.evolve(params, rng=ctx.rng, scheme=ctx.scene.topography.scheme)
    topo.save_height_map(ctx.workdir / "surface.npy", res.h, params.dx)
    np.savez(ctx.workdir / "psd.npz", k=res.k, psd=res.psd, psd_theory=res.psd_theory)
    files = {"surface": "surface.npy", "psd": "psd.npz"}
    if (ctx.workdir / "surface.json").exists():
        files["surface_meta"] = "surface.json"
    if (ctx.workdir / "rates.json").exists():
        files["rates"] = "rates.json"
    values = _scalars(res)
    values.pop("status", None)
    values["rates_source"] = rates_src or "[topography]"
    values["params"] = _scalars(dict(vars(params)))
    return StageOutput(
        values=values,
        units={k: v for k, v in res.units.items() if k in values},
        files=files,
        method=res.method,
        message=res.message,
        nit=int(res.nit),
    )


# -------------------------------------------------------------- lubrication


@_stage("lubrication")
def lubrication(ctx: StageContext) -> StageOutput:
    """Reduced squeeze and sliding forces at the scene's film (and across gaps), plus polishing if asked."""
    red = require_model("tribolmp.models.lubrication.reduced", "params_from_scene", "squeeze_force", "sliding_force", "with_gap")
    p = red.params_from_scene(ctx.scene)
    newtonian = p.power_law_index == 1.0
    # The reduced damper against the accurate reference of the same library (Brenner's exact
    # series for Newtonian fluids, the power-law closed form otherwise).
    ref_model = "brenner" if newtonian else "power-law"
    gaps = np.geomspace(p.gap / 10.0, min(10.0 * p.gap, p.radius), 21)
    curves: dict[str, Any] = {"x": gaps, "x_label": "gap h (m)"}
    curves["squeeze damper"] = np.array([red.squeeze_force(red.with_gap(p, h), "damper").force for h in gaps])
    curves[f"squeeze {ref_model}"] = np.array([red.squeeze_force(red.with_gap(p, h), ref_model).force for h in gaps])
    values: dict[str, Any] = {
        "gap_m": p.gap,
        "radius_m": p.radius,
        "approach_velocity_m_s": p.velocity,
        "sliding_velocity_m_s": p.sliding_velocity,
        "squeeze_force_damper_N": red.squeeze_force(p, "damper").force,
        f"squeeze_force_{ref_model}_N": red.squeeze_force(p, ref_model).force,
    }
    values["damper_rel_error"] = values["squeeze_force_damper_N"] / values[f"squeeze_force_{ref_model}_N"] - 1.0
    units = {k: ("m" if k.endswith("_m") else "m/s" if k.endswith("_m_s") else "N" if k.endswith("_N") else "1") for k in values}
    if newtonian and p.sliding_velocity != 0:
        values["sliding_force_gcb_N"] = red.sliding_force(p, "gcb").force
        units["sliding_force_gcb_N"] = "N"
        curves["sliding gcb"] = np.array([red.sliding_force(red.with_gap(p, h), "gcb").force for h in gaps])
    np.savez(ctx.workdir / "curves.npz", **curves)
    files = {"curves": "curves.npz"}
    method = f"damper vs {ref_model}"
    if ctx.scene.polishing is not None:
        pol = require_model("tribolmp.models.lubrication.polishing", "params_from_scene", "solve")
        pp = pol.params_from_scene(ctx.scene)
        res = pol.solve(pp, rng=ctx.rng)
        pvals = _scalars(res)
        values["polishing"] = pvals
        for k, v in pvals.items():
            if isinstance(v, (int, float)) and not isinstance(v, bool) and k not in ("status", "nit"):
                values[f"polishing_{k}"] = v
                if k in res.units:
                    units[f"polishing_{k}"] = res.units[k]
        method += f"; polishing {res.method}"
    return StageOutput(values=values, units=units, files=files, method=method, message=f"lubrication at h = {p.gap:g} m")
