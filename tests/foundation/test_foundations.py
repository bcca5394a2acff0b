"""Foundation modules: the shared Rates record, JSON sanitising and atomic writes, range checks."""

from __future__ import annotations

import dataclasses
import json
import math

import numpy as np
import pytest

from tribolmp.errors import ParameterError
from tribolmp.jsonio import (
    atomic_write_json,
    canonical_json,
    dumps,
    finite_or_none,
    jsonable,
    scalars,
)
from tribolmp.params import check_int, check_range
from tribolmp.records import RATES_GROUPS, Rates


def test_rates_record_reads_rates_json_and_c1_fields():
    data = {
        "mu": 0.16,
        "mu_err": 0.07,
        "diffusion_m2_s": 5.3e-11,
        "step_length_m": 4.3e-9,
        "step_time_s": 3.5e-7,
        "velocity_m_s": 5.0,
        "pressure_Pa": 1.5e8,
        "dimension": 2,
        "units": {"mu": "1"},
        "warnings": ["w"],
        "mu_per_s": 1.0,
        "d0_m2_s": 2e-18,
        "dz": 3e-30,
        "dx_l2": 4e-45,
        "valid": {"dz": False, "mu_per_s": True},
        "modes_used": [1, 2, 3],
        "layer_persistence": {"x": [1]},
    }
    r = Rates.from_mapping(data, source="rates.json")
    assert (r.mu, r.sliding_velocity_m_s, r.dim, r.pressure_Pa) == (0.16, 5.0, 2, 1.5e8)
    assert r.flagged == ("dz",) and r.modes_used == (1, 2, 3) and r.warnings == ("w",)
    assert r.has_eq23 and r.source == "rates.json"
    # a C1 conditions block is flattened
    c = Rates.from_mapping(
        {"conditions": {"pressure_Pa": 1e8, "sliding_velocity_m_s": 1.0, "law": "bpm", "dim": 2}}
    )
    assert (c.pressure_Pa, c.sliding_velocity_m_s, c.law, c.dim) == (1e8, 1.0, "bpm", 2)
    assert not c.has_eq23
    with pytest.raises(ParameterError, match=r"rates\.mu_per_s"):
        c.require("mu_per_s")


@pytest.mark.parametrize(
    ("field", "value"),
    [
        ("mu", -0.1),
        ("mu", math.nan),
        ("step_time_s", 0.0),
        ("dz", -1.0),
        ("dim", 4),
        ("flagged", ("nonsense",)),
    ],
)
def test_rates_record_rejects_bad_values(field, value):
    with pytest.raises(ParameterError, match=rf"rates\.{field}"):
        Rates(**{field: value})


def test_rates_units_cover_every_numeric_field():
    units = Rates.units()
    numeric = (
        {f.name for f in dataclasses.fields(Rates)}
        - set(RATES_GROUPS["provenance"])
        - {"law", "dim"}
    )
    assert set(units) == numeric
    assert units["dx_l2"] == "m^5/s" and units["dz"] == "m^3/s" and units["mu_per_s"] == "1/s"
    assert set(sum(RATES_GROUPS.values(), ())) == {f.name for f in dataclasses.fields(Rates)}


def test_scene_rates_section_is_the_record():
    from tribolmp.scene import load_scene, scene_path
    from tribolmp.scene.schema import RATES_SCENE_DEFAULTS, SECTIONS

    section = {f.name: f for f in dataclasses.fields(SECTIONS["rates"])}
    record = {f.name: f for f in dataclasses.fields(Rates)}
    assert set(section) == set(record) - set(RATES_GROUPS["provenance"])
    for name, f in section.items():  # same unit, range and doc: one definition
        assert f.metadata == record[name].metadata
        assert f.default == RATES_SCENE_DEFAULTS.get(name, record[name].default)
    scene = load_scene(scene_path("rates_given"))
    rec = scene.rates.to_record()
    assert isinstance(rec, Rates) and rec.mu == 0.16 and rec.source == "[rates]"
    # optional fields that a scene does not give stay out of the scene dict (it must stay TOML)
    assert "dz" not in scene.to_dict()["rates"] and scene.to_dict()["rates"]["mu"] == 0.16


def test_analysis_units_agree_with_the_record():
    from tribolmp.analysis.rates import RATES_UNITS

    for k, u in Rates.units().items():
        assert RATES_UNITS[k] == u, k


def test_jsonable_sanitises_numpy_nan_and_paths(tmp_path):
    obj = {
        "a": np.arange(3),
        "b": np.float64("nan"),
        "c": (1, np.int64(2)),
        3: tmp_path,
        "d": np.bool_(True),
        "e": [math.inf, 1.5],
    }
    out = jsonable(obj)
    assert out == {
        "a": [0, 1, 2],
        "b": None,
        "c": [1, 2],
        "3": str(tmp_path),
        "d": True,
        "e": [None, 1.5],
    }
    json.loads(dumps(obj))  # strict JSON
    p = atomic_write_json(tmp_path / "x" / "r.json", obj)
    assert json.loads(p.read_text()) == out and not list(p.parent.glob(".*tmp"))
    with pytest.raises(TypeError):
        jsonable(object())


def test_canonical_json_distinguishes_nan_and_is_order_free():
    assert canonical_json({"b": 1, "a": (1.0,)}) == canonical_json({"a": [1.0], "b": 1})
    assert canonical_json({"x": math.nan}) != canonical_json({"x": None})


def test_small_helpers():
    assert (
        finite_or_none("2.5") == 2.5
        and finite_or_none(math.nan) is None
        and finite_or_none(None) is None
    )
    assert finite_or_none(True) is None
    assert scalars(
        {"a": np.float32(1.5), "b": np.zeros(100), "c": [1, 2], "d": "s", "e": math.nan}
    ) == {"a": 1.5, "c": [1, 2], "d": "s", "e": None}
    assert check_range("x", np.float64(2.0), 0, 3) == 2.0
    with pytest.raises(ParameterError, match=r"x: expected a number in \(0, inf\) Pa"):
        check_range("x", 0.0, 0.0, None, lo_open=True, unit="Pa")
    assert check_int("n", np.int64(3), 1) == 3
    with pytest.raises(ParameterError):
        check_int("n", True)


def test_renamed_fields_keep_the_old_name_working():
    from dataclasses import dataclass, replace

    from tribolmp.params import build_dataclass, param, renamed, validate_dataclass

    @renamed(modulus="E_star")
    @dataclass(frozen=True)
    class P:
        E_star: float = param(1e11, unit="Pa", lo=0.0, lo_open=True)
        n: int = param(3)

        def __post_init__(self):
            validate_dataclass(self)

    assert P(modulus=2e11).E_star == 2e11 and P(E_star=3e11).modulus == 3e11
    assert replace(P(E_star=1.0), modulus=5.0).E_star == 5.0
    assert replace(P(E_star=1.0), n=4).E_star == 1.0
    assert build_dataclass(P, {"modulus": 4.0}).E_star == 4.0
    with pytest.raises(ParameterError, match=r"^modulus: expected"):
        P(modulus=-1.0)  # the error names the field as the caller spelled it
    with pytest.raises(ParameterError, match=r"^E_star: expected"):
        P(E_star=-1.0)
    with pytest.raises(TypeError):
        renamed(x="nonexistent")(P)
