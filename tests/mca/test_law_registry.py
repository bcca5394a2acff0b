"""The mca entry of the bond-law registry: mapping, validation, fragment, a friction run."""

from __future__ import annotations

import math

import pytest

from tribolmp.errors import ParameterError
from tribolmp.lammps.law_mca import McaLaw, map_spec, pair_area
from tribolmp.lammps.laws import DEFAULT_LAW, get_law, law_names
from tribolmp.lammps.mapping import MaterialSpec


def test_mca_is_registered_and_the_default():
    assert "mca" in law_names()
    assert DEFAULT_LAW == "mca"
    from tribolmp.lammps.mca import preset_params

    assert preset_params("smoke").bond_style == "mca"
    law = get_law("mca")
    assert law.keyword == "mca" and law.setup is not None and not law.coordination_cap
    from tribolmp.lammps.decks import laws_dir

    assert (laws_dir() / "mca.in").is_file()


def test_mapping_from_si():
    c = map_spec(MaterialSpec(bond_style="mca"))
    law = c.law
    # G = E / (2 (1 + nu)) in LAMMPS pressure units (1e6 Pa)
    v = get_law("mca").deck_variables(c)
    assert float(v["G"]) == pytest.approx(206e9 / 2.6 / 1e6, rel=1e-9)
    assert float(v["H"]) == pytest.approx((552 - 480) / 0.05, rel=1e-9)
    # mass = density x automaton volume (2D sheet of thickness d): 7800 kg/m^3 * sqrt(3)/2 d^3
    assert c.mass == pytest.approx(7800 * math.sqrt(3) / 2 * (2.5e-9) ** 3 / 1e-21, rel=1e-9)
    assert c.density_column * math.pi * 2.5**3 / 6 == pytest.approx(c.mass, rel=1e-12)
    # contact stiffness Kc A / d, Kc = 2G / (1 - 2 nu) in plane strain
    kc = 2 * law.shear_modulus / (1 - 0.6) / 1e6
    assert c.k_contact == pytest.approx(kc * pair_area(2.5, 2) / 2.5, rel=1e-9)
    assert 0.1 <= 0.5 * c.dt_max_factor  # the driver's default dt_factor 0.1 is allowed


@pytest.mark.parametrize("field,value", [("poisson_ratio", 0.55), ("yield_strength", -1.0)])
def test_validation_is_one_line_naming_the_field(field, value):
    with pytest.raises(ParameterError) as exc:
        MaterialSpec(bond_style="mca", **{field: value})
    assert field in str(exc.value) and "\n" not in str(exc.value)


def test_3d_nu_range_is_narrower():
    McaLaw(dim=2, poisson_ratio=-0.4)
    with pytest.raises(ParameterError, match="poisson_ratio"):
        McaLaw(dim=3, poisson_ratio=-0.4)


@pytest.mark.slow
@pytest.mark.lammps
def test_friction_smoke_welds_across_the_interface_at_150_MPa(lammps_available, tmp_path):
    """The friction deck with the mca law: the bodies weld (issue 13: 0 cross-body links before)."""
    from tribolmp.lammps.mca import preset_params, run_mca
    from tribolmp.lammps.plugin import plugin_path
    from tribolmp.lammps.session import LammpsSession

    p = preset_params("smoke").replace(bond_style="mca", pressure=150e6)
    res = run_mca(p, tmp_path / "run", seed=1)
    assert res["status"] == 0
    last = sorted((tmp_path / "run").glob("restart.*.bin"))[-1]
    with LammpsSession(log=None, require=()) as s:
        s.command(f"plugin load {plugin_path()}")
        s.command(f"read_restart {last}")
        s.command("compute t all pair mca")
        s.command("run 0")
        t = [s.lmp.extract_compute("t", 0, 1)[k] for k in range(7)]
    # cumulative cross-body links formed (C2 tally 3) > 0; links remain in the bodies
    assert t[2] > 0
    assert t[0] > 0
