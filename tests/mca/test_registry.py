"""The bond-law registry (issue 11 item 4).

One entry plus one deck fragment make a law; SI only at the boundary.
"""

from __future__ import annotations

import dataclasses
import re
import shutil
from pathlib import Path

import numpy as np
import pytest

from tribolmp.errors import ParameterError
from tribolmp.lammps import laws
from tribolmp.lammps.decks import laws_dir
from tribolmp.lammps.mca import MCAParams, preset_params
from tribolmp.scene.schema import Material, Nanoscale

PKG = Path(__file__).resolve().parents[2] / "tribolmp" / "lammps"


def _declared(text: str) -> set[str]:
    return set(re.findall(r"^variable\s+(\S+)\s+index\b", text, re.MULTILINE))


@pytest.mark.parametrize("name", laws.law_names())
def test_every_law_has_a_fragment_declaring_its_variables(name):
    law = laws.get_law(name)
    frag = laws_dir() / f"{law.keyword}.in"
    assert frag.is_file(), frag
    spec = preset_params("smoke", bond_style=name).material()
    names = set(law.deck_variables(law.map_material(spec)))
    assert names and names <= _declared(frag.read_text())
    assert all(len(s) == 2 for s in law.styles)


def test_unknown_law_is_one_line():
    with pytest.raises(ParameterError) as err:
        preset_params("smoke", bond_style="harmonic")
    assert str(err.value).startswith("bond_style") and "bpm/spring/plastic" in str(err.value)


def test_param_defaults_are_the_scene_defaults():
    # one default per quantity: MCAParams must not repeat a
    # [nanoscale]/[material] default differently
    ours = {f.name: f.default for f in dataclasses.fields(MCAParams)}
    for section in (Nanoscale, Material):
        for f in dataclasses.fields(section):
            if f.name in ours and f.name != "preset":
                assert ours[f.name] == f.default, (section.__name__, f.name)


def test_no_raw_unit_factors_in_the_driver():
    # conversions at the LAMMPS boundary go through tribolmp.units (to_lammps/from_lammps)
    pattern = re.compile(r"[*/]\s*1e[-+]?\d+\b")
    for path in sorted((PKG / "mca").glob("*.py")) + [PKG / "mapping.py", PKG / "laws.py"]:
        for k, line in enumerate(path.read_text().splitlines(), 1):
            code = line.split("#", 1)[0]
            assert not pattern.search(code), f"{path.name}:{k}: {line.strip()}"


@pytest.mark.lammps
def test_a_new_law_is_one_entry_plus_its_fragment(tmp_path, monkeypatch, lammps_available):
    # a toy law: the plastic law's mapping under a new name and keyword, with its own fragment file
    frags = tmp_path / "laws"
    frags.mkdir()
    for f in laws_dir().glob("*.in"):
        shutil.copy(f, frags / f.name)
    (frags / "toy.in").write_text((laws_dir() / "plastic.in").read_text())
    base = laws.get_law("bpm/spring/plastic")
    toy = dataclasses.replace(base, name="toy", keyword="toy", doc="copy of the plastic law")
    monkeypatch.setattr(laws, "BOND_LAWS", {**laws.BOND_LAWS, "toy": toy})
    from tribolmp.lammps.mca import deck as deck_mod
    from tribolmp.lammps.mca import driver, run_mca

    monkeypatch.setattr(deck_mod, "laws_dir", lambda: frags)
    monkeypatch.setattr(driver, "compute_rates", lambda out: None)
    params = preset_params("smoke", duration=0.1e-9, ramp_time=0.05e-9, bond_style="toy")
    run_mca(params, tmp_path / "toy", seed=3)
    ref = preset_params(
        "smoke", duration=0.1e-9, ramp_time=0.05e-9, bond_style="bpm/spring/plastic"
    )
    run_mca(ref, tmp_path / "ref", seed=3)
    a = np.loadtxt(tmp_path / "toy" / "friction.csv", delimiter=",", skiprows=1)
    b = np.loadtxt(tmp_path / "ref" / "friction.csv", delimiter=",", skiprows=1)
    # same mapping, same fragment text: the new entry reproduces the law it copies bit for bit
    assert np.array_equal(a, b)
