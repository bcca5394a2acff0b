"""Runner mechanics with instrumented stage functions: cache reuse, --force, failures, interrupts.

The stage functions here are counters that write a file: they test the
runner's bookkeeping (which is independent of the physics), not any model.
End-to-end runs with the real models are in ``test_smoke.py``.
"""

from __future__ import annotations

import json

import pytest

from tribolmp.chain import planner as planner_mod
from tribolmp.chain import runner as runner_mod
from tribolmp.chain.registry import REGISTRY
from tribolmp.chain.stage import StageOutput
from tribolmp.errors import SetupError, StageError
from tribolmp.scene import load_scene, scene_path


def with_run(stage, fn):
    """Return a copy of ``stage`` whose ``run`` is ``fn``.

    Same module, so the same code closure and cache key.
    """
    cls = type(stage)
    return type(
        cls.__name__, (cls,), {"run": lambda self, ctx: fn(ctx), "__module__": cls.__module__}
    )()


def set_run(monkeypatch, name, fn):
    """Replace stage ``name``'s computation in the registry the planner uses."""
    monkeypatch.setattr(
        planner_mod, "REGISTRY", planner_mod.REGISTRY.replaced(name, with_run(REGISTRY[name], fn))
    )


@pytest.fixture
def calls(monkeypatch):
    """Replace every stage's computation by a counter that writes one file per declared hand-off."""
    counts: dict[str, int] = {}

    def make(stage):
        def fn(ctx):
            counts[stage.name] = counts.get(stage.name, 0) + 1
            (ctx.workdir / "out.txt").write_text(f"{stage.name} {ctx.seed} {sorted(ctx.upstream)}")
            files = {"out": "out.txt", **{h.file: "out.txt" for h in stage.produces}}
            return StageOutput(
                values={"calls": counts[stage.name]}, units={"calls": "1"}, files=files
            )

        return fn

    for stage in REGISTRY:
        set_run(monkeypatch, stage.name, make(stage))
    return counts


def _scene():
    return load_scene(scene_path("rates_given"))


def _report(out):
    return json.loads((out / "report.json").read_text())


def test_rerun_reuses_cache_and_force_recomputes(tmp_path, calls):
    out = tmp_path / "run"
    first = runner_mod.run_chain(_scene(), out, quiet=True, figures=False)
    ran = [e.name for e in first.entries.values() if e.ran]
    assert ran == ["topography", "contact", "macroscale", "tribospectroscopy"]
    assert all(calls[n] == 1 for n in ran)
    rep = _report(out)
    assert [r["name"] for r in rep["stages"]] == list(REGISTRY.names)
    assert all(set(r) == {"name", "ran", "reason", "time_s"} for r in rep["stages"])
    assert rep["complete"] is True
    # Downstream stages saw their upstream results.
    assert "['topography']" in first.result("contact").file("out").read_text()

    second = runner_mod.run_chain(_scene(), out, quiet=True, figures=False)
    assert all(calls[n] == 1 for n in ran), "cached stages must not be recomputed"
    assert all(second.entries[n].status == "cached" for n in ran)
    assert second.result("contact").key == first.result("contact").key

    runner_mod.run_chain(_scene(), out, quiet=True, figures=False, force=["contact"])
    assert calls["contact"] == 2 and calls["topography"] == 1
    # A recomputed stage invalidates what depends on it, and nothing else.
    assert calls["macroscale"] == 2 and calls["tribospectroscopy"] == 1


def test_changed_input_invalidates_only_downstream(tmp_path, calls):
    import dataclasses

    out = tmp_path / "run"
    scene = _scene()
    runner_mod.run_chain(scene, out, quiet=True, figures=False)
    # [tribospectroscopy] is read by that stage only (issue 15: [roughness] is now the part's
    # surface, which the running-in topography evolves, so it invalidates every stage).
    changed = dataclasses.replace(
        scene, tribospectroscopy=dataclasses.replace(scene.tribospectroscopy, frequency=60e3)
    )
    runner_mod.run_chain(changed, out, quiet=True, figures=False)
    assert calls["topography"] == 1 and calls["contact"] == 1 and calls["macroscale"] == 1
    assert calls["tribospectroscopy"] == 2
    changed = dataclasses.replace(
        scene,
        roughness=dataclasses.replace(
            scene.roughness, realizations=scene.roughness.realizations + 1
        ),
    )
    runner_mod.run_chain(changed, out, quiet=True, figures=False)
    assert calls["topography"] == 2 and calls["contact"] == 2 and calls["macroscale"] == 2


def test_failing_stage_is_reported_and_others_kept(tmp_path, calls, monkeypatch):
    def boom(ctx):
        raise RuntimeError("solver diverged\nat step 7")

    set_run(monkeypatch, "contact", boom)
    out = tmp_path / "run"
    with pytest.raises(StageError) as info:
        runner_mod.run_chain(_scene(), out, quiet=True, figures=False)
    msg = str(info.value)
    assert "\n" not in msg and "contact" in msg and "solver diverged at step 7" in msg
    rows = {r["name"]: r for r in _report(out)["stages"]}
    assert rows["topography"]["ran"] and rows["tribospectroscopy"]["ran"]
    assert not rows["contact"]["ran"] and rows["contact"]["reason"].startswith("failed:")
    assert (
        not rows["macroscale"]["ran"] and "upstream stage contact" in rows["macroscale"]["reason"]
    )


def test_setup_error_in_a_stage_maps_to_setup_error(tmp_path, calls, monkeypatch):
    from tribolmp.errors import ParameterError

    def bad(ctx):
        raise ParameterError("[contact].springs", "an integer >= 3", 1)

    set_run(monkeypatch, "contact", bad)
    with pytest.raises(SetupError, match=r"stage 'contact' failed: \[contact\].springs"):
        runner_mod.run_chain(_scene(), tmp_path / "run", quiet=True, figures=False)


def test_interrupt_keeps_finished_stages_and_resumes(tmp_path, calls, monkeypatch):
    real_contact = planner_mod.REGISTRY["contact"].run

    def interrupted(ctx):
        (ctx.workdir / "checkpoint").write_text("half done")
        raise KeyboardInterrupt

    set_run(monkeypatch, "contact", interrupted)
    out = tmp_path / "run"
    with pytest.raises(KeyboardInterrupt):
        runner_mod.run_chain(_scene(), out, quiet=True, figures=False)
    rep = _report(out)
    assert rep["complete"] is False
    rows = {r["name"]: r for r in rep["stages"]}
    assert rows["topography"]["ran"] and "interrupted" in rows["contact"]["reason"]
    partial = list((out / "cache").glob("contact-*.partial"))
    assert len(partial) == 1 and (partial[0] / "checkpoint").read_text() == "half done"

    seen = {}

    def resumed(ctx):
        seen["checkpoint"] = (ctx.workdir / "checkpoint").read_text()
        return real_contact(ctx)

    set_run(monkeypatch, "contact", resumed)
    run = runner_mod.run_chain(_scene(), out, quiet=True, figures=False)
    assert seen["checkpoint"] == "half done", (
        "the rerun must find the interrupted stage's checkpoint"
    )
    assert calls["topography"] == 1 and run.entries["topography"].status == "cached"
    assert run.entries["contact"].status == "computed" and _report(out)["complete"] is True


def test_unknown_force_stage_is_a_setup_error(tmp_path, calls):
    with pytest.raises(SetupError, match="--force"):
        runner_mod.run_chain(_scene(), tmp_path / "run", quiet=True, force=["bogus"])
