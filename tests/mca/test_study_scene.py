"""The shipped study scene runs the study's reduced grid point (docs/mca_study.md).

`tribolmp sweep tribolmp/data/scenes/mca_study.toml --vary nanoscale.pressure=...` is documented
as the same runs as `workflows/mca_friction_sweep.py --quick --duration 20e-9
--contact-viscosity 0.175 --dt-factor 0.05`: the parameters must agree field for field (a
changed scene default or preset would otherwise silently run another experiment).
"""

from __future__ import annotations

import dataclasses

import pytest

from tribolmp.lammps.mca import params_from_scene, preset_params
from tribolmp.scene import load_scene, scene_path

pytestmark = pytest.mark.lammps  # imports the LAMMPS driver package (not LAMMPS itself)


def test_study_scene_is_the_workflows_grid_point():
    scene = load_scene(scene_path("mca_study"))
    got = dataclasses.asdict(params_from_scene(scene))
    want = dataclasses.asdict(
        preset_params(
            "smoke",
            duration=20e-9,
            contact_viscosity=0.175,
            dt_factor=0.05,
            sliding_velocity=5.0,
            pressure=150e6,
        )
    )
    assert {k: (got[k], want[k]) for k in want if got[k] != want[k]} == {}
    # only the nanoscale stage: the scene requests rates and nothing downstream
    assert list(scene.outputs.requested) == ["rates"]
