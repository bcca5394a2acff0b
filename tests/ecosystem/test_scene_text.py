"""``parse_scene`` takes TOML text as well as a mapping (issue 16 item 3)."""

from __future__ import annotations

import pytest

from tribolmp.errors import SceneError
from tribolmp.scene import parse_scene

TEXT = """
[scene]
name = "from text"
[material]
youngs_modulus = 100e9
"""


def test_toml_text_gives_the_same_scene_as_the_mapping():
    from_text = parse_scene(TEXT, source="cell")
    from_map = parse_scene(
        {"scene": {"name": "from text"}, "material": {"youngs_modulus": 100e9}}, source="cell"
    )
    assert from_text == from_map
    assert from_text.material.youngs_modulus == 100e9


def test_bad_toml_text_is_one_line_naming_toml():
    with pytest.raises(SceneError) as err:
        parse_scene("[scene\nname = 1", source="cell")
    msg = str(err.value)
    assert "\n" not in msg and "TOML" in msg


@pytest.mark.parametrize("bad", [42, ["scene"], None])
def test_neither_mapping_nor_text_names_both_accepted_kinds(bad):
    with pytest.raises(SceneError) as err:
        parse_scene(bad)
    msg = str(err.value)
    assert "mapping" in msg and "TOML text" in msg and type(bad).__name__ in msg
