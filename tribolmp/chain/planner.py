"""The planner: which stages a scene needs, at which fidelity, and why.

One generic pass over the registry (:mod:`tribolmp.chain.registry`), no
stage-specific code here:

1. **Demand, backwards.**  From the last stage to the first, each stage's
   ``plan(scene, demand)`` decides whether it runs, from the scene's
   ``[outputs].requested`` and the hand-offs the stages after it are waiting
   for.  A running stage satisfies the pending demand for the hand-offs it
   produces and adds its own ``consumes``/``wants``.
2. **Supply, forwards.**  From the first stage to the last, each running
   stage's hand-offs are bound to the nearest earlier running producer
   (``supplied``, ``needs``); ``bind(scene, decision, supplied)`` lets the
   stage name its sources.  A required hand-off (``consumes``) that no
   running stage supplies is a scene error.

The stages' ``plan``/``bind`` read only the scene (and, for the contact
solver choice, the measured speed-against-error table): planning imports no
model that the scene does not need, so a dry scene never touches the
lubrication package and nothing starts LAMMPS.  Each decision's ``reason`` is
the report's.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

from ..errors import SceneError
from ..scene import Scene
from .registry import REGISTRY, STAGES, Registry
from .stage import Decision, Demand, with_supplied
from .stages.contact import choose_contact_method, speed_error_table

__all__ = [
    "STAGES",
    "StagePlan",
    "Plan",
    "plan_scene",
    "choose_contact_method",
    "speed_error_table",
]

#: The planner's per-stage decision (historical name).
StagePlan = Decision


@dataclass(frozen=True)
class Plan:
    """All stage decisions for a scene, in execution order, with the registry they came from."""

    scene: Scene
    stages: tuple[Decision, ...]
    registry: Registry = REGISTRY

    def __getitem__(self, name: str) -> Decision:
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


def plan_scene(
    scene: Scene, *, table: dict[str, Any] | None = None, registry: Registry | None = None
) -> Plan:
    """Decide which stages run for ``scene`` and why.

    Parameters
    ----------
    scene : Scene
        A validated scene.
    table : dict, optional
        Contact speed-error table (default: the shipped one).
    registry : Registry, optional
        The stages (default: :data:`~tribolmp.chain.registry.REGISTRY`).

    Returns
    -------
    Plan

    Raises
    ------
    SceneError
        A requested output needs a section the scene does not have, or a
        stage requires a hand-off no running stage produces.
    """
    registry = REGISTRY if registry is None else registry
    demand = Demand(
        frozenset(scene.outputs.requested),
        overrides={"contact_table": table} if table is not None else {},
    )
    decided: dict[str, Decision] = {}
    for stage in reversed(registry.stages):
        d = stage.plan(scene, demand)
        if d.name != stage.name:  # pragma: no cover - a stage bug, not user input
            raise ValueError(f"stage {stage.name!r} returned the decision of {d.name!r}")
        undeclared = [h for h in (*d.consumes, *d.wants) if h not in stage.consumes]
        if undeclared:  # pragma: no cover - a stage bug
            raise ValueError(f"stage {stage.name!r} asks for undeclared hand-offs {undeclared}")
        if d.run:
            for h in stage.produced:
                demand.pending.pop(h, None)
            for h in (*d.consumes, *d.wants):
                demand.pending.setdefault(h, []).append(stage.name)
        decided[stage.name] = d

    producer: dict[str, str] = {}
    out: list[Decision] = []
    for stage in registry.stages:
        d = decided[stage.name]
        if d.run:
            supplied = {h: producer[h] for h in (*d.consumes, *d.wants) if h in producer}
            missing = [h for h in d.consumes if h not in supplied]
            if missing:
                raise SceneError(
                    f"stage {stage.name}",
                    f"a stage that produces {missing}",
                    "none runs for this scene",
                    scene.source,
                )
            d = with_supplied(stage.bind(scene, d, supplied), supplied)
            for h in stage.produced:
                producer[h] = stage.name
        else:
            d = replace(d, consumes=(), wants=())
        out.append(d)
    return Plan(scene, tuple(out), registry)
