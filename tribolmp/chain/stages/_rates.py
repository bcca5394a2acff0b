"""The ``rates`` hand-off as its consumers read it: one :class:`~tribolmp.records.Rates` record."""

from __future__ import annotations

import json
from dataclasses import replace

from ...jsonio import atomic_write_json
from ...records import Rates
from ..stage import Decision, StageContext

__all__ = ["upstream_rates", "nanoscale_rates", "mu_binding"]


def upstream_rates(ctx: StageContext) -> tuple[Rates | None, str]:
    """Return the rates record a stage uses and where it came from.

    The nanoscale stage's ``rates.json`` when the planner supplied that hand-off,
    else the scene's ``[rates]`` (written to ``rates.json`` in the stage's folder
    too, so every stage reads rates the same way), else ``(None, "")``.
    """
    up = ctx.handoff("rates")
    if up is not None:
        src = f"nanoscale stage {up.key} (rates.json)"
        return Rates.from_mapping(json.loads(up.file("rates").read_text()), source=src), src
    if ctx.scene.rates is not None:
        rec = ctx.scene.rates.to_record("[rates]")
        atomic_write_json(
            ctx.workdir / "rates.json", {k: v for k, v in rec.to_dict().items() if v is not None}
        )
        return rec, "[rates]"
    return None, ""


def nanoscale_rates(ctx: StageContext) -> Rates | None:
    """Return the nanoscale stage's rates record when the planner supplied it, else None.

    Rates given in the scene are not read here.
    """
    return upstream_rates(ctx)[0] if ctx.handoff("rates") is not None else None


def mu_binding(scene, decision: Decision, supplied) -> Decision:
    """Bind a mu consumer.

    Say where mu comes from and hash ``[rates]`` or ``[load]`` when that is the source.

    The precedence is :func:`tribolmp.models.friction.friction_coefficient`'s:
    the nanoscale hand-off, else ``[rates]``, else ``[load]``.
    """
    if "rates" in supplied:
        src, extra = "nanoscale", ()
    elif scene.rates is not None:
        src, extra = "[rates]", ("rates",)
    else:
        src, extra = "[load]", ("load",)
    sections = decision.sections + tuple(s for s in extra if s not in decision.sections)
    return replace(
        decision, reason=decision.reason.replace("{mu}", f"mu from {src}"), sections=sections
    )
