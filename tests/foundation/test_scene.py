"""Scene files: defaults, one-line errors for malformed input (incl. hypothesis fuzzing)."""

from __future__ import annotations

import math

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from tests.conftest import assert_one_line_error
from tribolmp.errors import SceneError
from tribolmp.scene import default_scene, example_scenes, load_scene, parse_scene, scene_path
from tribolmp.scene.schema import SECTIONS


def test_default_scene_is_the_seed_steel_couple():
    s = default_scene()
    assert s.material.youngs_modulus == 206e9
    assert s.material.poisson_ratio == 0.3
    assert s.material.density == 7800.0
    # E* for identical steels: E / (2 (1 - nu^2)), exact.
    assert s.effective_modulus == pytest.approx(206e9 / (2 * (1 - 0.09)), rel=1e-12)
    # MDR G* (PHYSICS.md 2): 1/G* = 2 (2 - nu) / (4 G)  ->  G* = 2 G / (2 - nu)
    G = 206e9 / 2.6
    assert s.effective_shear_modulus == pytest.approx(2 * G / 1.7, rel=1e-12)
    assert s.lubricant is None  # dry


def test_all_example_scenes_validate():
    names = example_scenes()
    assert "default" in names
    for name in names:
        load_scene(scene_path(name))


def _write(tmp_path, text):
    p = tmp_path / "scene.toml"
    p.write_text(text)
    return p


@pytest.mark.parametrize(
    "text, fragments",
    [
        (
            "[material]\nyoungs_modulus = -1e9\n",
            ["[material].youngs_modulus", "expected", "got -1000000000.0"],
        ),
        ("[material]\npoisson_ratio = 0.5\n", ["[material].poisson_ratio", "(-1, 0.5)"]),
        ("[material]\npoisson_ratio = -1.0\n", ["[material].poisson_ratio"]),
        ("[material]\ndensity = nan\n", ["[material].density", "finite"]),
        ("[material]\ndensity = inf\n", ["[material].density", "finite"]),
        ('[material]\nyoungs_modulus = "steel"\n', ["[material].youngs_modulus", "got 'steel'"]),
        ("[material]\ncolour = 3\n", ["[material].colour", "unknown key"]),
        ("[materials]\nE = 1\n", ["[materials]", "unknown section"]),
        ("[nanoscale]\nautomaton_diameter = 60e-9\n", ["[nanoscale].automaton_diameter", "5e-08"]),
        ("[lubricant]\npower_law_index = 0.3\n", ["[lubricant].power_law_index", "0.333333"]),
        (
            "[material]\nyield_strength = 600e6\nultimate_strength = 500e6\n",
            ["[material].ultimate_strength", "yield_strength"],
        ),
        ('[outputs]\nrequested = ["everything"]\n', ["[outputs].requested[0]", "one of"]),
        ('[outputs]\nrequested = "friction"\n', ["[outputs].requested", "list"]),
        ("[topography]\ndim = 3\n", ["[topography].dim", "one of [1, 2]"]),
        ("[topography]\ngrid_points = 2\n", ["[topography].grid_points", "[4,"]),
        ("[scene]\nseed = true\n", ["[scene].seed", "integer"]),
        ("material = 3\n", ["[material]", "table"]),
        ("[material\n", ["file", "valid TOML"]),
        ('[outputs]\nrequested = ["lubrication"]\n', ["[lubricant]"]),
        ("[nanoscale]\npressure = 600e6\n", ["[nanoscale].pressure", "yield_strength"]),
    ],
)
def test_malformed_scene_one_line(tmp_path, text, fragments):
    p = _write(tmp_path, text)
    with pytest.raises(SceneError) as info:
        load_scene(p)
    msg = str(info.value)
    assert "\n" not in msg
    assert msg.startswith(str(p) + ": ")
    for frag in fragments:
        assert frag in msg, (frag, msg)


def test_check_cli_exit_codes(tmp_path, cli):
    good = cli("check", str(scene_path("default")))
    assert good.returncode == 0, good.stderr
    bad = cli("check", str(_write(tmp_path, "[material]\npoisson_ratio = 0.7\n")))
    assert_one_line_error(
        bad, "scene.toml: [material].poisson_ratio: expected a number in (-1, 0.5), got 0.7"
    )
    missing = cli("check", str(tmp_path / "nope.toml"))
    assert_one_line_error(missing, "nope.toml", "readable")
    usage = cli("check")
    assert_one_line_error(usage, "scene")


# ----------------------------------------------------------------- fuzzing
_scalars = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.integers(min_value=-(2**70), max_value=2**70),
    st.booleans(),
    st.text(max_size=8),
    st.none(),
)
_values = st.one_of(
    _scalars,
    st.lists(_scalars, max_size=4),
    st.dictionaries(st.text(max_size=5), _scalars, max_size=3),
)


@st.composite
def _scene_dicts(draw):
    names = list(SECTIONS) + ["bogus", ""]
    doc = {}
    for sec in draw(st.lists(st.sampled_from(names), max_size=4, unique=True)):
        if sec in SECTIONS:
            keys = [f for f in SECTIONS[sec].__dataclass_fields__] + ["nonsense"]
        else:
            keys = ["x"]
        table = {}
        for key in draw(st.lists(st.sampled_from(keys), max_size=4, unique=True)):
            table[key] = draw(_values)
        doc[sec] = table if draw(st.integers(0, 9)) else draw(_scalars)
    return doc


@settings(max_examples=400, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(_scene_dicts())
def test_fuzzed_scene_dicts_give_scene_or_one_line_error(doc):
    """Whatever is thrown at the loader: a valid Scene, or a one-line SceneError -- nothing else."""
    try:
        scene = parse_scene(doc, source="fuzz.toml")
    except SceneError as exc:
        msg = str(exc)
        assert "\n" not in msg and msg.startswith("fuzz.toml: ")
        assert ": expected " in msg and ", got " in msg
        return
    # accepted: every numeric field must be finite
    for sec in scene.to_dict().values():
        for v in sec.values():
            for item in v if isinstance(v, list) else [v]:
                if isinstance(item, float):
                    assert math.isfinite(item)


@settings(max_examples=200, deadline=None)
@given(st.text(max_size=200))
def test_fuzzed_toml_text(tmp_path_factory, text):
    p = tmp_path_factory.mktemp("fz") / "scene.toml"
    p.write_text(text, encoding="utf-8", errors="surrogatepass") if False else p.write_bytes(
        text.encode("utf-8", "replace")
    )
    try:
        load_scene(p)
    except SceneError as exc:
        assert "\n" not in str(exc)


def test_bond_style_choices_are_the_law_registry():
    # The scene sits below the LAMMPS layer and cannot import its registry: the two lists are
    # kept equal by this test (a new law is one BondLaw entry, its fragment and this choice).
    import dataclasses

    from tribolmp.lammps.laws import law_names
    from tribolmp.scene.schema import Nanoscale

    choices = next(f for f in dataclasses.fields(Nanoscale) if f.name == "bond_style").metadata[
        "choices"
    ]
    assert tuple(choices) == tuple(law_names())


def test_renamed_scene_key_keeps_working():
    # [nanoscale].roughness_rms is now rms_height (the [roughness] name); the old key still parses
    # and reaches the MCA run.
    from tribolmp.lammps.mca import params_from_scene
    from tribolmp.scene import parse_scene

    old = parse_scene({"nanoscale": {"roughness_rms": 1e-9}})
    new = parse_scene({"nanoscale": {"rms_height": 1e-9}})
    assert old.nanoscale == new.nanoscale and old.nanoscale.roughness_rms == 1e-9
    assert params_from_scene(old).roughness_rms == 1e-9
    with pytest.raises(SceneError, match=r"\[nanoscale\]\.roughness_rms"):
        parse_scene({"nanoscale": {"roughness_rms": -1.0}})
