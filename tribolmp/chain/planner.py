"""The planner: which stages a scene needs, at which fidelity, and why.

The planner only reads the scene (its ``[outputs].requested`` list and which
optional sections exist) and, for ``[contact].method = "auto"``, the measured
speed-against-error table shipped in ``tribolmp/data/contact_speed_error.json``.
It imports no model code, so planning a scene is instant and a dry scene never
touches the lubrication package.

Rules (each becomes the ``reason`` string of the report):

* ``nanoscale`` runs LAMMPS only with a ``[nanoscale]`` section and only when
  its rates are needed (requested ``friction``/``mca_snapshot``/``rates``, or a
  downstream stage consumes them).  A scene with ``[rates]`` never starts LAMMPS.
* ``topography`` evolves Eq. 23 only with a ``[topography]`` section; without
  it the contact uses the surface the scene gives (``[roughness]``).
* ``contact`` runs when stiffness is requested or consumed downstream; with
  ``method = "auto"`` it picks MDR or BEM and the mesh from measured data.
* ``lubrication`` runs whenever the scene has a ``[lubricant]``.
* ``macroscale`` runs for ``stick_slip`` (with a ``[lubricant]``, the squeeze film shares its
  normal load); ``tribospectroscopy`` for ``tribospectroscopy``.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from typing import Any

from ..environment import data_path
from ..errors import SceneError
from ..scene import Scene

__all__ = ["STAGES", "StagePlan", "Plan", "plan_scene", "choose_contact_method", "speed_error_table"]

#: Stage names in execution order (a contract: report.json's "stages" uses them).
STAGES = ("nanoscale", "topography", "contact", "lubrication", "macroscale", "tribospectroscopy")

#: Python package each stage's model lives in (imported lazily by the stage).
MODEL_MODULES = {
    "nanoscale": "tribolmp.lammps.mca",
    "topography": "tribolmp.models.topography",
    "contact": "tribolmp.models.contact",
    "lubrication": "tribolmp.models.lubrication",
    "macroscale": "tribolmp.models.macro",
    "tribospectroscopy": "tribolmp.models.tribospectroscopy",
}


#: Source folders (relative to the tribolmp package) whose code each stage's results depend on;
#: their content is hashed into the stage's cache key, so a model change invalidates its results.
MODEL_SOURCES = {
    "nanoscale": ("lammps", "analysis", "data/lammps_inputs"),
    "topography": ("models/topography",),
    "contact": ("models/contact",),
    "lubrication": ("models/lubrication",),
    "macroscale": ("models/macro", "models/contact"),
    "tribospectroscopy": ("models/tribospectroscopy", "models/macro", "models/contact"),
}


#: Extra source folders a stage reads only with a planner option (so other scenes' keys do not change).
OPTIONAL_SOURCES = {("macroscale", "squeeze_film"): ("models/lubrication",)}


def code_hash(stage: str, options: dict[str, Any] | None = None) -> str:
    """SHA-256 of the source files (``*.py``, ``*.in``) a stage's model reads; imports nothing.

    ``options`` (the stage plan's) adds the :data:`OPTIONAL_SOURCES` of the options that are set.
    """
    import hashlib
    from pathlib import Path

    root = Path(__file__).resolve().parents[1]
    digest = hashlib.sha256()
    paths = [root / "chain" / "stages.py", root / "models" / "base.py"]
    folders = MODEL_SOURCES[stage] + tuple(
        f for (st, opt), extra in OPTIONAL_SOURCES.items() if st == stage and (options or {}).get(opt) for f in extra
    )
    for folder in folders:
        base = root / folder
        if base.is_dir():
            paths += sorted(p for p in base.rglob("*") if p.suffix in (".py", ".in") and p.is_file())
    for p in paths:
        digest.update(str(p.relative_to(root)).encode())
        digest.update(p.read_bytes())
    return digest.hexdigest()


@dataclass(frozen=True)
class StagePlan:
    """The planner's decision for one stage.

    Attributes
    ----------
    name : str
        Stage name (one of :data:`STAGES`).
    run : bool
        Whether the stage is computed.
    reason : str
        Why it runs (or why it is skipped), one line.
    needs : tuple of str
        Upstream stages whose results it consumes (hashed into its cache key).
    sections : tuple of str
        Scene sections it reads (hashed into its cache key).
    options : dict
        Planner choices (method, mesh, surface or rates source...).
    """

    name: str
    run: bool
    reason: str
    needs: tuple[str, ...] = ()
    sections: tuple[str, ...] = ()
    options: dict[str, Any] = field(default_factory=dict)

    def to_json_dict(self) -> dict[str, Any]:
        """Plain dict for report.json."""
        return {
            "name": self.name,
            "run": self.run,
            "reason": self.reason,
            "needs": list(self.needs),
            "sections": list(self.sections),
            "options": dict(self.options),
        }


@dataclass(frozen=True)
class Plan:
    """All stage decisions for a scene, in execution order."""

    scene: Scene
    stages: tuple[StagePlan, ...]

    def __getitem__(self, name: str) -> StagePlan:
        for s in self.stages:
            if s.name == name:
                return s
        raise KeyError(name)

    @property
    def running(self) -> list[str]:
        """Names of the stages that will be computed."""
        return [s.name for s in self.stages if s.run]

    def to_json_dict(self) -> list[dict[str, Any]]:
        """List of per-stage decisions."""
        return [s.to_json_dict() for s in self.stages]


# ------------------------------------------------------------ contact choice


def speed_error_table() -> dict[str, Any] | None:
    """The shipped measured speed-vs-error table of the contact solvers, or None if absent."""
    try:
        return json.loads(data_path("contact_speed_error.json").read_text())
    except (OSError, ValueError):
        return None


def choose_contact_method(tolerance: float, table: dict[str, Any] | None, *, reduced_pressures: list[float] | None = None) -> dict[str, Any]:
    """Pick the cheapest measured (method, mesh) whose error is within ``tolerance``.

    The choice itself is physics (which solver is valid where) and lives in
    :func:`tribolmp.models.contact.choice.choose_method`; see there for the
    table format.  ``reduced_pressures`` (``p / (E* h'_rms)``) selects the
    table rows of the pressure range the scene asks for.
    """
    from ..models.contact.choice import choose_method

    return choose_method(tolerance, table, reduced_pressures=reduced_pressures)


# ------------------------------------------------------------------ planner


def _requested(scene: Scene) -> set[str]:
    return set(scene.outputs.requested)


def plan_scene(scene: Scene, *, table: dict[str, Any] | None = None) -> Plan:
    """Decide which stages run for ``scene`` and why.

    Parameters
    ----------
    scene : Scene
        A validated scene.
    table : dict, optional
        Contact speed-error table (default: the shipped one).

    Returns
    -------
    Plan

    Raises
    ------
    SceneError
        A requested output needs a section the scene does not have.
    """
    req = _requested(scene)
    src = scene.source
    if "mca_snapshot" in req and scene.nanoscale is None:
        raise SceneError("[nanoscale]", "a [nanoscale] section when outputs request 'mca_snapshot'", "nothing", src)
    # 'topography' and 'tribospectroscopy' are in the default [outputs] list, so a scene without
    # their section is not contradictory: the stage is skipped and the report says why.
    # Downstream demand first, so that upstream stages know who consumes them.
    want_macro = "stick_slip" in req
    want_tribo = "tribospectroscopy" in req and scene.tribospectroscopy is not None
    want_lub = scene.lubricant is not None
    # The rigid body rides on the contact.  (Tribospectroscopy's contacts are the probe's two tips,
    # modelled by the tribospectroscopy package itself from [geometry]; they need only mu.)
    want_contact = "stiffness" in req or want_macro
    surface_from_topo = want_contact and scene.geometry.profile == "rough" and scene.topography is not None
    want_topo = "topography" in req or surface_from_topo
    if want_contact and scene.geometry.profile == "rough" and scene.topography is None and scene.roughness is None:
        raise SceneError("[roughness]", "a [roughness] or [topography] section for geometry.profile = 'rough'", "nothing", src)
    rates_consumers = [n for n, w in (("topography", want_topo), ("macroscale", want_macro), ("tribospectroscopy", want_tribo)) if w]
    want_rates = bool(req & {"friction", "mca_snapshot", "rates"}) or bool(rates_consumers)

    stages: list[StagePlan] = []

    # -- nanoscale
    if scene.rates is not None:
        stages.append(StagePlan("nanoscale", False, "rates given in [rates]: LAMMPS not started", options={"rates_source": "scene"}))
        rates_need: tuple[str, ...] = ()
        rates_sections: tuple[str, ...] = ("rates",)
    elif scene.nanoscale is not None and want_rates:
        why = [f"outputs request {sorted(req & {'friction', 'mca_snapshot', 'rates'})}"] if req & {"friction", "mca_snapshot", "rates"} else []
        if rates_consumers:
            why.append(f"rates feed {', '.join(rates_consumers)}")
        stages.append(
            StagePlan(
                "nanoscale",
                True,
                "MCA on LAMMPS: " + "; ".join(why),
                sections=("nanoscale", "material", "counter_material"),
                options={"rates_source": "nanoscale", "preset": scene.nanoscale.preset, "ranks": scene.nanoscale.ranks},
            )
        )
        rates_need, rates_sections = ("nanoscale",), ()
    elif scene.nanoscale is not None:
        stages.append(StagePlan("nanoscale", False, "no requested output needs nanoscale rates", options={"rates_source": "none"}))
        rates_need, rates_sections = (), ()
    else:
        stages.append(
            StagePlan("nanoscale", False, "no [nanoscale] or [rates] section: friction coefficient from [load]", options={"rates_source": "load"})
        )
        rates_need, rates_sections = (), ("load",)

    # -- topography
    if scene.topography is None:
        given = (
            f"the height map {scene.roughness.surface_file}" if scene.roughness is not None and scene.roughness.surface_file
            else "a random surface from [roughness]" if scene.roughness is not None else f"the [geometry] profile '{scene.geometry.profile}'"
        )
        stages.append(StagePlan("topography", False, f"no [topography] section: contact uses {given}"))
    elif want_topo:
        rsrc = "measured by nanoscale" if rates_need else "given in [rates]" if scene.rates is not None else "[topography] values (no rates in the scene)"
        why = "outputs request 'topography'" if "topography" in req else "the evolved surface feeds contact"
        stages.append(
            StagePlan(
                "topography",
                True,
                f"Eq. 23 with rates {rsrc}; {why}",
                needs=rates_need,
                sections=("topography", "kinematics") + tuple(s for s in rates_sections if s != "load"),
                options={"rates_source": "nanoscale" if rates_need else ("scene" if scene.rates is not None else "topography")},
            )
        )
    else:
        stages.append(StagePlan("topography", False, "no requested output needs the evolved surface"))

    # -- contact
    topo_runs = stages[-1].run
    if want_contact:
        c = scene.contact
        if scene.geometry.profile != "rough":
            surface = f"axisymmetric {scene.geometry.profile}"
            needs: tuple[str, ...] = ()
            secs = ("geometry", "material", "counter_material", "load", "contact")
        elif topo_runs:
            surface, needs = "evolved surface from topography", ("topography",)
            secs = ("geometry", "material", "counter_material", "load", "contact", "roughness")
        else:
            surface = "given height map" if scene.roughness.surface_file else "random surface from [roughness]"
            needs, secs = (), ("geometry", "material", "counter_material", "load", "contact", "roughness")
        if c.method == "auto":
            from ..models.contact.choice import reduced_pressures_of_scene

            choice = choose_contact_method(c.tolerance, speed_error_table() if table is None else table,
                                           reduced_pressures=reduced_pressures_of_scene(scene))
            method, mesh, why = choice["method"], choice["mesh"], "auto: " + choice["why"]
        else:
            choice = {}
            method, mesh, why = c.method, None, f"method '{c.method}' set in [contact]"
        purpose = "outputs request 'stiffness'" if "stiffness" in req else "stiffness feeds macroscale"
        stages.append(
            StagePlan(
                "contact",
                True,
                f"{method.upper()} on the {surface}; {why}; {purpose}",
                needs=needs,
                sections=secs,
                options={"method": method, "mesh": mesh, "surface": surface, **{f"expected_{k}": choice.get(f"expected_{k}") for k in ("error", "time_s") if choice}},
            )
        )
    else:
        stages.append(StagePlan("contact", False, "no requested output needs contact stiffness"))

    # -- lubrication
    if want_lub:
        what = "polishing" if scene.polishing is not None else "squeeze and shear forces"
        stages.append(
            StagePlan(
                "lubrication",
                True,
                f"scene has [lubricant]: {what}",
                sections=("lubricant", "polishing", "geometry", "load", "kinematics", "material", "counter_material"),
                options={"polishing": scene.polishing is not None},
            )
        )
    else:
        stages.append(StagePlan("lubrication", False, "dry scene: no [lubricant] section"))

    # -- macroscale
    if want_macro:
        needs = tuple(n for n in ("contact",) if any(s.name == n and s.run for s in stages)) + rates_need
        how = "MDR contact springs of the axisymmetric profile" if scene.geometry.profile != "rough" else "the rough contact's tangential stiffness"
        sections = ("kinematics", "load", "geometry", "material", "counter_material", "contact") + rates_sections
        options: dict[str, Any] = {"contact_law": "mdr" if scene.geometry.profile != "rough" else "stiffness"}
        film = ""
        if want_lub:
            # The body first approaches through the squeeze film; the rupture gap comes from
            # [roughness] (or the film thickness).  Only lubricated scenes hash these, so a dry
            # scene's key is what it was before the film fed the rigid body.
            sections += ("lubricant", "roughness")
            options["squeeze_film"] = True
            film = "; normal load shared with the [lubricant] squeeze film"
        stages.append(
            StagePlan(
                "macroscale",
                True,
                f"outputs request 'stick_slip': rigid body on {how}, mu from {'nanoscale' if rates_need else '[rates]' if scene.rates is not None else '[load]'}{film}",
                needs=needs,
                sections=sections,
                options=options,
            )
        )
    else:
        stages.append(StagePlan("macroscale", False, "'stick_slip' not requested"))

    # -- tribospectroscopy
    if want_tribo:
        ts = scene.tribospectroscopy
        stages.append(
            StagePlan(
                "tribospectroscopy",
                True,
                f"outputs request 'tribospectroscopy': F^2(a), {ts.model} model, {ts.convention} amplitudes, "
                f"mu from {'nanoscale' if rates_need else '[rates]' if scene.rates is not None else '[load]'}",
                needs=rates_need,
                sections=("tribospectroscopy", "load", "geometry", "material", "counter_material", "contact") + rates_sections,
                options={"model": ts.model},
            )
        )
    elif "tribospectroscopy" in req:
        stages.append(StagePlan("tribospectroscopy", False, "'tribospectroscopy' requested but the scene has no [tribospectroscopy] section"))
    else:
        stages.append(StagePlan("tribospectroscopy", False, "'tribospectroscopy' not requested"))

    return Plan(scene, tuple(stages))
