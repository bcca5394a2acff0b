"""The method choice behind ``[contact].method = "auto"``.

Pressure ranges and the MDR closed-line limit.
"""

from __future__ import annotations

import pytest

from tribolmp.models.contact.choice import choose_method

# A synthetic table: MDR cheap but only good at low reduced pressure and closing at high,
# BEM slower and uniformly accurate.
TABLE = {
    "rows": [
        {
            "method": "mdr",
            "mesh": 256,
            "rel_error": 0.1,
            "time_s": 0.01,
            "reduced_pressure_range": [0.003, 0.01],
            "closed_fraction_max": 0.0,
        },
        {
            "method": "mdr",
            "mesh": 256,
            "rel_error": 0.4,
            "time_s": 0.01,
            "reduced_pressure_range": [0.01, 0.03],
            "closed_fraction_max": 0.05,
        },
        {
            "method": "mdr",
            "mesh": 256,
            "rel_error": 0.2,
            "time_s": 0.01,
            "reduced_pressure_range": [0.03, 0.1],
            "closed_fraction_max": 0.6,
        },
        {
            "method": "bem",
            "mesh": 128,
            "rel_error": 0.03,
            "time_s": 0.1,
            "reduced_pressure_range": [0.003, 0.1],
        },
        {
            "method": "bem",
            "mesh": 512,
            "rel_error": 0.004,
            "time_s": 2.0,
            "reduced_pressure_range": [0.003, 0.1],
        },
    ]
}


@pytest.mark.parametrize(
    ("pressures", "tol", "method", "mesh"),
    [
        ([0.005], 0.3, "mdr", 256),        # low range: MDR within 0.1
        ([0.005, 0.02], 0.3, "bem", 128),  # the range asked includes MDR's 0.4 row
        ([0.05], 0.3, "bem", 128),         # MDR's 0.2 would pass, but 60 % of its lines close there
        ([0.005], 0.01, "bem", 512),
        ([0.005], 0.001, "bem", 512),      # nothing reaches 1e-3: the most accurate
    ],
)
def test_choice_uses_the_pressure_range_asked(pressures, tol, method, mesh):
    c = choose_method(tol, TABLE, reduced_pressures=pressures)
    assert (c["method"], c["mesh"]) == (method, mesh), c["why"]


def test_mdr_never_picked_with_closed_lines():
    c = choose_method(0.3, TABLE, reduced_pressures=[0.05])
    assert "MDR excluded" in c["why"]
    # a run-time closed fraction above 10 % excludes MDR even where the table allows it
    assert (
        choose_method(0.3, TABLE, reduced_pressures=[0.005], closed_fraction=0.2)["method"] == "bem"
    )
    assert (
        choose_method(0.3, TABLE, reduced_pressures=[0.005], closed_fraction=0.05)["method"]
        == "mdr"
    )


def test_outside_the_measured_range_uses_the_nearest_and_says_so():
    c = choose_method(0.3, TABLE, reduced_pressures=[1e-4])
    assert (c["method"], c["mesh"]) == ("mdr", 256) and "outside the measured pressure range" in c[
        "why"
    ]


def test_axisymmetric_scene_uses_the_exact_mdr():
    import dataclasses

    from tribolmp.models.contact.choice import choose_method_for_scene
    from tribolmp.scene import load_scene, scene_path

    scene = load_scene(scene_path("default"))
    sphere = dataclasses.replace(
        scene, geometry=dataclasses.replace(scene.geometry, profile="sphere")
    )
    assert choose_method_for_scene(sphere, TABLE)["method"] == "mdr"
    # the rough default scene is judged at its reduced pressures (1e-5 ...
    # 1e-2): MDR's 0.4 row is in range
    c = choose_method_for_scene(scene, TABLE)
    assert c["method"] == "bem" and c["reduced_pressure_range"][1] == pytest.approx(
        0.0114, rel=0.01
    )
