"""Geometry: four-part stack, molecule ids, rough surfaces, bonds, and the bpm/sphere data file."""

from __future__ import annotations

import numpy as np
import pytest

from tribolmp.lammps.build import (
    BOND_ATTACH,
    BOND_BODY,
    MOL_BASE,
    MOL_LOWER,
    MOL_SLIDER,
    MOL_UPPER,
    build_system,
    self_affine_profile,
    write_bpm_data,
)


def test_self_affine_profile_has_exact_rms_and_hurst_slope(rng):
    h = self_affine_profile(4096, 2.0, 0.8, rng)
    assert h.mean() == pytest.approx(0.0, abs=1e-12)
    assert h.std() == pytest.approx(2.0, rel=1e-12)
    # PSD ~ q^-(1 + 2H): fitted slope of one realisation within 0.15 of -2.6
    # (chi^2 scatter of 2000 modes)
    q = np.fft.rfftfreq(h.size)[1:]
    psd = np.abs(np.fft.rfft(h))[1:] ** 2
    slope = np.polyfit(np.log(q), np.log(psd), 1)[0]
    assert slope == pytest.approx(-(1 + 2 * 0.8), abs=0.15)


def test_profiles_depend_only_on_the_generator():
    a = self_affine_profile(64, 1.0, 0.7, np.random.default_rng(3))
    b = self_affine_profile(64, 1.0, 0.7, np.random.default_rng(3))
    c = self_affine_profile(64, 1.0, 0.7, np.random.default_rng(4))
    assert np.array_equal(a, b) and not np.array_equal(a, c)


@pytest.mark.parametrize("dim,texture", [(2, "aligned"), (3, "aligned"), (3, "rotated")])
def test_stack_layers_and_bonds(dim, texture, rng):
    g = build_system(
        dim=dim, d=2.5, length=40.0, body_height=12.0, roughness_rms=1.0, rng=rng, width=8.0,
        texture=texture,
    )
    mol = g.atoms.arrays["mol_id"]
    y = g.atoms.positions[:, 1]
    assert set(np.unique(mol)) == {MOL_BASE, MOL_LOWER, MOL_UPPER, MOL_SLIDER}
    # bodies stacked bottom to top
    assert (
        y[mol == MOL_BASE].max()
        < y[mol == MOL_LOWER].mean()
        < y[mol == MOL_UPPER].mean()
        < y[mol == MOL_SLIDER].min()
    )
    # the rough surfaces touch without overlap: nearest cross-interface distance is one diameter
    lo, up = g.atoms.positions[mol == MOL_LOWER], g.atoms.positions[mol == MOL_UPPER]
    dv = lo[:, None, :] - up[None, :, :]
    dv[..., 0] -= (
        40.0 * np.round(dv[..., 0] / 40.0)
        if dim == 2
        else g.box[0, 1] * np.round(dv[..., 0] / g.box[0, 1])
    )
    if dim == 3:
        dv[..., 2] -= g.box[2, 1] * np.round(dv[..., 2] / g.box[2, 1])
    dist = np.linalg.norm(dv, axis=2)
    # aligned lattices stack column on column, so the closest pair is exactly one diameter apart;
    # rotated ones are closed column-wise (vertical gap <= d) with the closest pair offset
    # laterally within its column bin: measured 1.042 d, bounded here by 1.1 d (no overlap
    # either way)
    top = 1.01 if texture == "aligned" else 1.1
    assert dist.min() >= 0.99 * 2.5 and dist.min() < top * 2.5
    b = g.bonds
    mi, mj = mol[b[:, 1]], mol[b[:, 2]]
    assert not np.any(
        ((mi == MOL_LOWER) & (mj == MOL_UPPER)) | ((mi == MOL_UPPER) & (mj == MOL_LOWER))
    )
    assert np.all(mi[b[:, 0] == BOND_BODY] == mj[b[:, 0] == BOND_BODY])
    att = b[:, 0] == BOND_ATTACH
    assert np.all(np.isin(np.minimum(mi[att], mj[att]), [MOL_BASE, MOL_UPPER]))
    # every bond joins nearest neighbours (minimum image along periodic x / z)
    dvec = g.atoms.positions[b[:, 1]] - g.atoms.positions[b[:, 2]]
    lengths = g.box[:, 1] - g.box[:, 0]
    for ax in (0, 2) if dim == 3 else (0,):
        dvec[:, ax] -= lengths[ax] * np.round(dvec[:, ax] / lengths[ax])
    assert np.allclose(np.linalg.norm(dvec, axis=1), 2.5, rtol=1e-9)
    # coordination in the bulk of the bodies: 6 (hexagonal) or 12 (FCC)
    deg = np.bincount(b[:, 1:].ravel(), minlength=g.n_atoms)
    assert deg.max() == (6 if dim == 2 else 12)


@pytest.mark.lammps
@pytest.mark.parametrize("dim", [2, 3])
def test_data_file_reads_back_in_lammps(lmp, dim, rng, tmp_path):
    g = build_system(
        dim=dim, d=2.5, length=30.0, body_height=10.0, roughness_rms=0.8, rng=rng, width=8.0
    )
    path = write_bpm_data(tmp_path / "s.data", g, density=0.02, diameter=2.4)
    lmp.commands(
        [
            "units nano",
            f"dimension {dim}",
            "boundary p f p",
            "atom_style bpm/sphere",
            "newton on off",
            f"read_data {path}",
        ]
    )
    assert lmp.natoms() == g.n_atoms
    assert int(lmp.lmp.get_thermo("bonds")) == len(g.bonds)
    mol = np.array(lmp.lmp.numpy.extract_atom("molecule"))
    ids = np.array(lmp.lmp.numpy.extract_atom("id"))
    assert np.array_equal(mol[np.argsort(ids)], g.atoms.arrays["mol_id"])
    radius = np.array(lmp.lmp.numpy.extract_atom("radius"))
    assert np.allclose(radius, 1.2)
    # LAMMPS mass = density * pi D^3 / 6 in 2D and 3D
    rmass = np.array(lmp.lmp.numpy.extract_atom("rmass"))
    assert np.allclose(rmass, 0.02 * np.pi * 2.4**3 / 6)


def _inplane_bond_angles(g, mol_id):
    """Angles (deg, mod 90) of the in-plane (x-z) nearest-neighbour links inside one body."""
    mol = g.atoms.arrays["mol_id"]
    b = g.bonds[(mol[g.bonds[:, 1]] == mol_id) & (mol[g.bonds[:, 2]] == mol_id)]
    dv = g.atoms.positions[b[:, 1]] - g.atoms.positions[b[:, 2]]
    for ax in (0, 2):
        length = g.box[ax, 1] - g.box[ax, 0]
        dv[:, ax] -= length * np.round(dv[:, ax] / length)
    flat = np.abs(dv[:, 1]) < 1e-9  # links within one (010) lattice plane
    return np.degrees(np.arctan2(dv[flat, 2], dv[flat, 0])) % 90.0


def test_rotated_3d_bodies_meet_at_the_sigma5_misorientation(rng):
    """3D ``rotated``: each body's cube axes turned by -+atan(1/3) about the normal.

    The in-plane links of an FCC (010) plane run at 45 deg (mod 90) to the cube axes, so the
    lower body's must sit at 45 - 18.43 and the upper body's at 45 + 18.43 deg; the bodies
    then meet 36.87 deg apart and neither has a close-packed row along the sliding direction
    (aligned bodies: both at exactly 45 deg).  Exact up to rounding, because the coincidence
    period sqrt(10) a makes both lattices periodic in the box without stretching.
    """
    theta = np.degrees(np.arctan(1.0 / 3.0))
    g = build_system(
        dim=3, d=2.5, length=40.0, body_height=12.0, roughness_rms=1.0, rng=rng, width=8.0,
        texture="rotated",
    )
    lo, up = _inplane_bond_angles(g, MOL_LOWER), _inplane_bond_angles(g, MOL_UPPER)
    assert lo.size > 100 and up.size > 100
    np.testing.assert_allclose(lo, 45.0 - theta, atol=1e-6)
    np.testing.assert_allclose(up, 45.0 + theta, atol=1e-6)
    # the box is whole coincidence periods along x and z
    period = np.sqrt(10.0) * np.sqrt(2.0) * 2.5
    for ax in (0, 2):
        n = (g.box[ax, 1] - g.box[ax, 0]) / period
        assert n == pytest.approx(round(n), abs=1e-9)
    ga = build_system(
        dim=3, d=2.5, length=40.0, body_height=12.0, roughness_rms=1.0,
        rng=np.random.default_rng(0), width=8.0,
    )
    np.testing.assert_allclose(_inplane_bond_angles(ga, MOL_LOWER), 45.0, atol=1e-6)
