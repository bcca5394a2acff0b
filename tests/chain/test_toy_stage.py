"""A new stage is one file plus one registry entry: planner, runner, report and cache need no edit.

The toy stage below consumes the contact stage's ``stiffness`` hand-off and
writes a small table with a figure.  It is added to a *copy* of the registry;
the existing stages' decisions, seeds and cache keys must not change, and a
rerun with the toy stage must reuse every existing stage from the cache.
"""

from __future__ import annotations

import json

import numpy as np

from tests.chain.test_runner import _scene, calls  # noqa: F401  (fixture: counting stage functions)
from tribolmp.chain import planner as planner_mod
from tribolmp.chain import runner as runner_mod
from tribolmp.chain.planner import plan_scene
from tribolmp.chain.stage import (
    Decision,
    Demand,
    Figure,
    Handoff,
    Stage,
    StageContext,
    StageOutput,
    stage_seed,
)


def _draw(ax, result, run) -> None:
    d = np.load(result.file("toy_table"))
    ax.plot(d["x"], d["y"], "o-")


class Toy(Stage):
    """Toy stage: reads the stiffness hand-off, writes a table of twice the number of its bytes."""

    name = "toy"
    produces = (Handoff("toy_table", units={"x": "1", "y": "1"}, doc="toy.npz"),)
    consumes = ("stiffness",)
    sections = ("load",)
    figures = (Figure("toy", "toy_table", _draw, "toy figure", "A toy figure"),)

    def plan(self, scene, demand: Demand) -> Decision:
        return self.go(
            "toy: summarises the contact stiffness", sections=self.sections, consumes=("stiffness",)
        )

    def run(self, ctx: StageContext) -> StageOutput:
        n = len(ctx.handoff_file("stiffness").read_bytes())
        np.savez(ctx.workdir / "toy.npz", x=np.arange(3.0), y=2.0 * n * np.arange(3.0))
        return StageOutput(
            values={"bytes": n, "draw": float(ctx.rng.random())},
            units={"bytes": "1"},
            files={"toy_table": "toy.npz"},
        )


def _rows(out):
    return json.loads((out / "report.json").read_text())


def test_planner_binds_the_toy_stage_and_leaves_the_others_alone():
    scene = _scene()
    base = plan_scene(scene, registry=planner_mod.REGISTRY)
    toyed = plan_scene(scene, registry=planner_mod.REGISTRY.inserted(Toy(), after="macroscale"))
    assert [d.name for d in toyed.stages] == [
        *base.registry.names[:5],
        "toy",
        base.registry.names[5],
    ]
    toy = toyed["toy"]
    assert toy.run and toy.needs == ("contact",) and toy.supplied == {"stiffness": "contact"}
    for d in base.stages:
        assert toyed[d.name].to_json_dict() == d.to_json_dict(), d.name
    # Seeds come from names, not positions: the toy before tribospectroscopy shifts nothing.
    assert stage_seed(1, "tribospectroscopy") != stage_seed(1, "toy")


def test_toy_stage_runs_reports_and_caches_without_other_edits(tmp_path, calls):  # noqa: F811
    out = tmp_path / "run"
    first = runner_mod.run_chain(_scene(), out, quiet=True, figures=False)
    registry = planner_mod.REGISTRY.inserted(Toy(), after="macroscale")
    second = runner_mod.run_chain(_scene(), out, quiet=True, figures=True, registry=registry)

    for name, e in first.entries.items():
        e2 = second.entries[name]
        assert e2.key == e.key, f"{name}: cache key changed by adding a stage"
        if e.ran:
            assert e2.status == "cached", f"{name} was recomputed"
            assert e2.cached.record["seed"] == e.cached.record["seed"]
    assert second.entries["toy"].status == "computed"
    assert all(n == 1 for n in calls.values()), calls

    rep = _rows(out)
    assert [r["name"] for r in rep["stages"]] == list(registry.names)
    row = next(r for r in rep["stages"] if r["name"] == "toy")
    assert row["ran"] is True and row["reason"].startswith("toy:")
    assert rep["results"]["toy"]["values"]["bytes"] > 0
    assert rep["stage_details"]["toy"]["upstream"] == {
        "contact": f"{second.result('contact').key}:{second.result('contact').record['output_id']}"
    }
    assert (
        rep["figures"]["toy"] == "figures/toy.png"
        and (out / "figures" / "toy.png").stat().st_size > 0
    )
    assert "A toy figure" in (out / "report.md").read_text()

    # The cache handles it like any stage: a third run reuses it; --force toy recomputes only it.
    third = runner_mod.run_chain(_scene(), out, quiet=True, figures=False, registry=registry)
    assert third.entries["toy"].status == "cached"
    forced = runner_mod.run_chain(
        _scene(), out, quiet=True, figures=False, registry=registry, force=["toy"]
    )
    assert (
        forced.entries["toy"].status == "computed" and forced.entries["contact"].status == "cached"
    )


def test_cli_force_choices_are_the_registry():
    import argparse

    from tribolmp.chain.registry import REGISTRY
    from tribolmp.cli import run as run_cli

    parser = argparse.ArgumentParser()
    run_cli.configure(parser)
    force = next(a for a in parser._actions if a.dest == "force")
    assert tuple(force.choices) == (*REGISTRY.names, "all")


def test_scene_output_choices_are_the_stages_outputs():
    # The scene sits below the chain and cannot import the registry: [outputs].requested's choices
    # are kept equal to what the registered stages serve by this test (a new output of a new stage
    # is one entry in scene/schema.py OUTPUT_CHOICES).
    from tribolmp.chain.registry import REGISTRY
    from tribolmp.scene.schema import OUTPUT_CHOICES

    served = {o for s in REGISTRY for o in s.outputs}
    assert served == set(OUTPUT_CHOICES)
