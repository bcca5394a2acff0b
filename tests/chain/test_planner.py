"""The planner's choices for each example scene, and the contact auto-selection rule."""

from __future__ import annotations

import subprocess
import sys
import textwrap

import pytest

from tribolmp.chain import STAGES, choose_contact_method, plan_scene
from tribolmp.chain.planner import speed_error_table
from tribolmp.errors import SceneError
from tribolmp.scene import example_scenes, load_scene, parse_scene, scene_path


def _plan(name):
    return plan_scene(load_scene(scene_path(name)))


def test_example_scenes_shipped():
    assert {"default", "lubricated", "polishing", "rates_given"} <= set(example_scenes())


@pytest.mark.parametrize("name", ["default", "lubricated", "polishing", "rates_given"])
def test_every_stage_has_a_decision_and_a_reason(name):
    plan = _plan(name)
    assert [s.name for s in plan.stages] == list(STAGES)
    for s in plan.stages:
        assert s.reason and "\n" not in s.reason
        assert set(s.needs) <= set(plan.running), (s.name, s.needs)


def test_default_scene_plan():
    plan = _plan("default")
    assert plan.running == ["nanoscale", "topography", "contact", "macroscale", "tribospectroscopy"]
    assert plan["topography"].needs == ("nanoscale",)
    assert plan["contact"].needs == ("topography",)
    assert "dry" in plan["lubrication"].reason
    # Tribospectroscopy models the probe's own tips; from the chain it takes only mu. Issue 15:
    # both also take the running-in hand-off of topography (mu_s, mu_k at the part; the length).
    assert plan["tribospectroscopy"].needs == ("nanoscale", "topography")
    assert plan["macroscale"].needs == ("contact", "nanoscale", "topography")


def test_rates_given_scene_never_plans_lammps():
    plan = _plan("rates_given")
    assert not plan["nanoscale"].run and "[rates]" in plan["nanoscale"].reason
    assert plan["topography"].run and plan["topography"].needs == ()
    assert "rates" in plan["topography"].sections  # the given rates are part of its cache key
    assert not plan["lubrication"].run


def test_lubricated_scene_plan():
    plan = _plan("lubricated")
    assert plan.running == ["contact", "lubrication", "macroscale"]
    assert "no [topography]" in plan["topography"].reason and "sphere" in plan["topography"].reason
    assert plan["contact"].options["method"] == "mdr"
    assert plan["macroscale"].needs == ("contact",)
    assert plan["macroscale"].options["contact_law"] == "mdr"


def test_polishing_scene_plan():
    plan = _plan("polishing")
    assert plan.running == ["topography", "contact", "lubrication"]
    assert plan["lubrication"].options["polishing"] is True


def test_scene_without_topography_uses_given_surface(tmp_path):
    import numpy as np

    np.save(tmp_path / "h.npy", np.zeros((8, 8)))
    scene = parse_scene(
        {
            "geometry": {"profile": "rough"},
            "roughness": {"surface_file": str(tmp_path / "h.npy")},
            "rates": {},
            "outputs": {"requested": ["stiffness"]},
        }
    )
    plan = plan_scene(scene)
    assert not plan["topography"].run and "h.npy" in plan["topography"].reason
    assert plan["contact"].run and plan["contact"].needs == ()
    assert plan["contact"].options["surface"] == "given height map"


def test_mca_snapshot_without_nanoscale_is_a_scene_error():
    scene = parse_scene({"rates": {}, "outputs": {"requested": ["mca_snapshot"]}}, source="s.toml")
    with pytest.raises(SceneError, match=r"\[nanoscale\]"):
        plan_scene(scene)


TABLE = {
    "rows": [
        {"method": "mdr", "mesh": 500, "rel_error": 0.30, "time_s": 0.01},
        {"method": "mdr", "mesh": 4000, "rel_error": 0.25, "time_s": 0.05},
        {"method": "bem", "mesh": 64, "rel_error": 0.08, "time_s": 0.5},
        {"method": "bem", "mesh": 256, "rel_error": 0.01, "time_s": 9.0},
    ]
}


@pytest.mark.parametrize(
    ("tol", "method", "mesh"),
    [
        (0.5, "mdr", 500),
        (0.27, "mdr", 4000),
        (0.1, "bem", 64),
        (0.02, "bem", 256),
        (0.001, "bem", 256),
    ],
)
def test_auto_picks_cheapest_within_tolerance(tol, method, mesh):
    c = choose_contact_method(tol, TABLE)
    assert (c["method"], c["mesh"]) == (method, mesh)
    if tol < 0.01:
        assert "no measured solver reaches" in c["why"]


def test_auto_uses_the_shipped_table():
    table = speed_error_table()
    # the package ships the measured table (tribolmp/data/contact_speed_error.json)
    assert table is not None, "contact_speed_error.json is missing from the package data"
    assert table.get("provenance"), "the shipped table must state where its numbers come from"
    scene = load_scene(scene_path("default"))
    opts = plan_scene(scene)["contact"].options
    from tribolmp.models.contact.choice import reduced_pressures_of_scene

    # the plan judges the rough-surface table at the scene's own reduced pressures p/(E* h'rms)
    best = choose_contact_method(
        scene.contact.tolerance, table, reduced_pressures=reduced_pressures_of_scene(scene)
    )
    assert (opts["method"], opts["mesh"]) == (best["method"], best["mesh"])


def _imports_after_planning(scene_file: str) -> str:
    code = textwrap.dedent(
        f"""
        import sys
        from tribolmp.scene import load_scene
        from tribolmp.chain import plan_scene
        from tribolmp.chain import runner, stages, report, cache
        plan_scene(load_scene({scene_file!r}))
        lub = "tribolmp.models.lubrication"
        print(sorted(m for m in sys.modules if m in ("lammps",) or m.startswith(lub)))
        """
    )
    return subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True
    ).stdout.strip()


def test_planning_imports_no_model_code():
    assert _imports_after_planning(str(scene_path("default"))) == "[]"
