"""Material mapping: lattice elasticity formulas, validation, and measurement in LAMMPS."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tribolmp.errors import ParameterError
from tribolmp.lammps.mapping import (
    MaterialSpec,
    lattice_moduli,
    map_material,
    measure_uniaxial,
    stability_factor,
)


def test_central_spring_lattices_match_textbook_moduli():
    # hexagonal spring network: E_2D = 2k/sqrt(3) (per unit thickness d), nu
    # = 1/3; FCC nearest-neighbour springs along [100]: C11 = 2k/a, C12 =
    # k/a -> E = 4k/(3a), nu = 1/3, a = sqrt(2) d
    e2, nu2 = lattice_moduli(1.0, 0.0, 1.0, 2)
    e3, nu3 = lattice_moduli(1.0, 0.0, 1.0, 3)
    assert e2 == pytest.approx(2.0 / math.sqrt(3.0), rel=1e-12)
    assert e3 == pytest.approx(4.0 / (3.0 * math.sqrt(2.0)), rel=1e-12)
    assert nu2 == pytest.approx(1.0 / 3.0, rel=1e-12) and nu3 == pytest.approx(1.0 / 3.0, rel=1e-12)


def test_hex_lattice_with_shear_springs_matches_closed_form():
    # nu = (kn - ks) / (3 kn + ks), E = 2 sqrt(3) kn (kn + ks) / (3 kn + ks)
    # / d (plane stress, thickness d)
    kn, ks = 3.0, 0.7
    e, nu = lattice_moduli(kn, ks, 1.0, 2)
    assert nu == pytest.approx((kn - ks) / (3 * kn + ks), rel=1e-12)
    assert e == pytest.approx(2 * math.sqrt(3) * kn * (kn + ks) / (3 * kn + ks), rel=1e-12)


def test_verlet_limit_within_independent_bounds():
    # omega_max^2 of the hexagonal spring lattice lies between that of one of its rows (a
    # chain: 4 k/m) and the Gershgorin bound sum over 3 bond directions of 2 * 2 k/m = 12 k/m
    f = stability_factor(2, 0.0)
    lam = (2.0 / f) ** 2
    assert 4.0 <= lam <= 12.0


def test_rotational_mapping_reaches_target_poisson_ratio():
    for dim in (2, 3):
        c = map_material(MaterialSpec(dim=dim, bond_style="bpm/rotational", poisson_ratio=0.25))
        e, nu = lattice_moduli(c.k_n, c.k_s, 2.5, dim)
        assert nu == pytest.approx(0.25, abs=1e-9)
        assert e * 1e6 == pytest.approx(206e9, rel=1e-9)  # LAMMPS pressure unit 1e6 Pa


@pytest.mark.parametrize(
    "field, value, fragment",
    [
        ("diameter", 0.3e-9, "diameter"),
        ("diameter", 60e-9, "diameter"),
        ("ultimate_strength", 100e6, "ultimate_strength"),
        ("bond_style", "harmonic", "bond_style"),
        ("failure_strain", 0.001, "failure_strain"),
    ],
)
def test_bad_material_rejected(field, value, fragment):
    with pytest.raises(ParameterError) as err:
        MaterialSpec(**{field: value})
    assert fragment in str(err.value) and "\n" not in str(err.value)


# ---------------------------------------------------------------- measurement in LAMMPS
#
# Tolerances (issue 7): E within 10 %, yield and ultimate strength within 15 %.  The
# plastic link has no hardening, so its plateau sits at (sigma_y + sigma_u)/2 by design:
# measured yield and ultimate are both that plateau (+8 % / -7 % for steel), which the
# 15 % bound checks honestly; a mapping error (e.g. a wrong lattice factor of 3 in 3D or
# a missing thickness in 2D) would miss by >= 30 %.


def _check_plastic(res, spec, mode):
    assert res.youngs_modulus == pytest.approx(spec.youngs_modulus, rel=0.10)
    assert res.yield_strength == pytest.approx(spec.yield_strength, rel=0.15)
    assert res.ultimate_strength == pytest.approx(spec.ultimate_strength, rel=0.15)
    # central springs: nu is fixed at the lattice's 1/3 (not steel's 0.3);
    # the barostat lag allows 3 %
    assert res.poisson_ratio == pytest.approx(1.0 / 3.0, rel=0.03)
    if mode == "tension":
        # past the failure strain the links rupture and the stress falls
        assert res.bonds_broken > 0
        assert res.stress[-1] < 0.5 * res.stress.max()


@pytest.mark.lammps
@pytest.mark.parametrize("mode", ["tension", "compression"])
def test_plastic_2d_block_measures_mapped_properties(lammps_available, mode, tmp_path):
    spec = MaterialSpec(dim=2)
    _check_plastic(measure_uniaxial(spec, mode=mode, out_dir=tmp_path, n=10), spec, mode)


@pytest.mark.lammps
@pytest.mark.slow
@pytest.mark.parametrize("mode", ["tension", "compression"])
def test_plastic_3d_block_measures_mapped_properties(lammps_available, mode, tmp_path):
    spec = MaterialSpec(dim=3)
    _check_plastic(measure_uniaxial(spec, mode=mode, out_dir=tmp_path, n=4), spec, mode)


@pytest.mark.lammps
@pytest.mark.slow
@pytest.mark.parametrize("dim", [2, 3])
def test_rotational_block_matches_e_nu_and_ultimate(lammps_available, dim, tmp_path):
    spec = MaterialSpec(dim=dim, bond_style="bpm/rotational")
    res = measure_uniaxial(spec, mode="tension", out_dir=tmp_path, n=10 if dim == 2 else 4)
    assert res.youngs_modulus == pytest.approx(spec.youngs_modulus, rel=0.10)
    # shear springs reproduce steel's nu; 0.01 absolute covers the barostat
    # lag measured (0.295-0.298)
    assert res.poisson_ratio == pytest.approx(0.3, abs=0.01)
    # brittle: rupture at sigma_u, no yield plateau
    assert res.ultimate_strength == pytest.approx(spec.ultimate_strength, rel=0.15)
    assert math.isnan(res.yield_strength)
    assert res.stress[-1] < 0.5 * res.stress.max()
    assert np.all(np.isfinite(res.stress))
