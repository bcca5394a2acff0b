"""The squeeze film feeds the rigid body: planner keys, cache invalidation, physics direction."""

from __future__ import annotations

import dataclasses

import numpy as np

from tests.chain.test_runner import calls  # noqa: F401  (fixture: counting stage functions)
from tribolmp.chain import runner as runner_mod
from tribolmp.chain.planner import plan_scene
from tribolmp.scene import load_scene, scene_path


def _lubricated():
    return load_scene(scene_path("lubricated"))


def _dry(scene):
    """Return the same body without oil (and without asking for the lubrication output)."""
    req = tuple(r for r in scene.outputs.requested if r != "lubrication")
    return dataclasses.replace(
        scene, lubricant=None, outputs=dataclasses.replace(scene.outputs, requested=req)
    )


def test_dry_macroscale_key_inputs_unchanged():
    # What a dry scene's macroscale stage hashed before the film fed the rigid body: any extra
    # section, option or source folder would silently invalidate every existing dry cache.
    for name in ("rates_given", "default"):
        sp = plan_scene(load_scene(scene_path(name)))["macroscale"]
        assert sp.sections[:6] == (
            "kinematics",
            "load",
            "geometry",
            "material",
            "counter_material",
            "contact",
        )
        assert "lubricant" not in sp.sections and "roughness" not in sp.sections
        assert set(sp.options) == {"contact_law"}


def test_lubricated_macroscale_reads_the_film():
    sp = plan_scene(_lubricated())["macroscale"]
    assert {"lubricant", "roughness"} <= set(sp.sections)
    assert sp.options["squeeze_film"] is True and "squeeze film" in sp.reason
    # squeeze_approach calls the lubrication package's damper: its source is in the stage's code
    # closure (tests/chain/test_cache.py), computed from the imports for dry and wet scenes alike.


def test_viscosity_invalidates_macroscale_not_contact(tmp_path, calls):  # noqa: F811
    scene = _lubricated()
    out = tmp_path / "run"
    first = runner_mod.run_chain(scene, out, quiet=True, figures=False)
    thicker = dataclasses.replace(
        scene,
        lubricant=dataclasses.replace(scene.lubricant, viscosity=2 * scene.lubricant.viscosity),
    )
    second = runner_mod.run_chain(thicker, out, quiet=True, figures=False)
    assert second.result("macroscale").key != first.result("macroscale").key
    assert calls["macroscale"] == 2 and calls["lubrication"] == 2
    assert calls["contact"] == 1 and second.result("contact").key == first.result("contact").key


def test_film_makes_first_slip_earlier(tmp_path):
    wet_scene = _lubricated()
    wet = (
        runner_mod.run_chain(wet_scene, tmp_path / "wet", quiet=True, figures=False)
        .result("macroscale")
        .record
    )
    dry = (
        runner_mod.run_chain(_dry(wet_scene), tmp_path / "dry", quiet=True, figures=False)
        .result("macroscale")
        .record
    )
    w, d = wet["values"], dry["values"]
    assert "film_rupture_gap_m" not in d and d["first_slip_time_s"] is not None
    # No [roughness]: the film ruptures where it started.
    assert w["film_rupture_gap_m"] == wet_scene.lubricant.film_thickness
    assert "film_thickness" in w["film_rupture_gap_source"]
    # The film time constant 6 pi eta R^2 / W (~47 us here) is comparable to the stick time
    # mu W / (k_d V) (100 us): while the film still carries part of the load, the solid contact's
    # normal load, hence the static friction mu F_c, is lower, and the rising drive force reaches
    # it sooner.  So the first slip comes EARLIER than dry.  The 10 % margin is far above the
    # integrators' tolerance (rtol 1e-8 .. 1e-6) yet well below the measured ~24 % shift.
    assert w["first_slip_time_s"] < 0.9 * d["first_slip_time_s"]
    # By the end (0.05 s = 1000 film time constants) the solid carries the whole load: the
    # film thins exponentially, so the residual share is ~exp(-1000) -- 1e-9 is pure round-off room.
    assert w["squeeze_status"] == 0
    assert abs(w["final_load_share"] - 1.0) < 1e-9
    # At rupture (t = 0) the solids only just touch: the first output sample after 0 carries load.
    assert 0.0 < w["time_to_solid_contact_s"] <= wet_scene.kinematics.duration / 2000 * (1 + 1e-12)


def test_thin_rupture_gap_reports_film_still_thinning(tmp_path):
    # h_c (0.1 um) below the Hertz indentation at 10 N (~0.96 um): the solid can never carry the
    # load, so the film keeps thinning; the stage must say so and still run (no exception).
    scene = _lubricated()
    scene = dataclasses.replace(
        scene, lubricant=dataclasses.replace(scene.lubricant, film_thickness=1e-7)
    )
    w = (
        runner_mod.run_chain(scene, tmp_path / "o", quiet=True, figures=False)
        .result("macroscale")
        .record
    )
    assert w["values"]["squeeze_status"] == 1
    assert "film still thinning" in w["message"] and "\n" not in w["message"]
    assert w["values"]["final_load_share"] < 1.0
    assert np.isfinite(w["values"]["final_load_share"])
