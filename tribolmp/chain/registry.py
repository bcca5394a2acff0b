"""The ordered registry of chain stages: the one list planner, runner, report, cache and CLI read.

Adding a stage is a new file under ``tribolmp/chain/stages/`` plus one entry
here, at the position where it runs (after the stages whose hand-offs it
consumes).  Stage files never import this module, so adding a stage changes
no other stage's code closure, cache key or seed.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator

from .stage import Stage
from .stages import contact, lubrication, macroscale, nanoscale, topography, tribospectroscopy

__all__ = ["Registry", "REGISTRY", "STAGES"]


class Registry:
    """An ordered, validated tuple of stages.

    Parameters
    ----------
    stages : iterable of Stage
        In execution order.  Names must be unique, and every hand-off a stage
        declares in ``consumes`` must be produced by an earlier stage.
    """

    def __init__(self, stages: Iterable[Stage]):
        self.stages: tuple[Stage, ...] = tuple(stages)
        names = [s.name for s in self.stages]
        if len(set(names)) != len(names) or not all(names):
            raise ValueError(f"stage names must be unique and non-empty: {names}")
        produced: set[str] = set()
        for s in self.stages:
            missing = [h for h in s.consumes if h not in produced]
            if missing:
                raise ValueError(
                    f"stage {s.name!r} consumes {missing}, which no earlier stage produces"
                )
            produced.update(s.produced)

    @property
    def names(self) -> tuple[str, ...]:
        """Stage names in execution order (report.json's ``stages`` order, ``--force`` choices)."""
        return tuple(s.name for s in self.stages)

    def __iter__(self) -> Iterator[Stage]:
        return iter(self.stages)

    def __len__(self) -> int:
        return len(self.stages)

    def __getitem__(self, name: str) -> Stage:
        for s in self.stages:
            if s.name == name:
                return s
        raise KeyError(f"no stage {name!r}; stages are {list(self.names)}")

    def inserted(
        self, stage: Stage, *, after: str | None = None, before: str | None = None
    ) -> Registry:
        """Return a copy with ``stage`` added after (or before) the named stage (default: last)."""
        order = list(self.stages)
        if after is not None:
            order.insert(self.names.index(after) + 1, stage)
        elif before is not None:
            order.insert(self.names.index(before), stage)
        else:
            order.append(stage)
        return Registry(order)

    def replaced(self, name: str, stage: Stage) -> Registry:
        """Return a copy with the stage ``name`` replaced by ``stage``."""
        return Registry(stage if s.name == name else s for s in self.stages)


#: The chain: nanoscale -> topography -> contact -> lubrication -> macroscale -> tribospectroscopy.
REGISTRY = Registry(
    (
        nanoscale.STAGE,
        topography.STAGE,
        contact.STAGE,
        lubrication.STAGE,
        macroscale.STAGE,
        tribospectroscopy.STAGE,
    )
)

#: Stage names in execution order (a contract: report.json's "stages" uses them).
STAGES = REGISTRY.names
