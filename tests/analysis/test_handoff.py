"""Hand-offs: ASE Atoms in ASE units from an MCA dump (issue 16 item 3)."""

from __future__ import annotations

import json

import numpy as np
import pytest

from tribolmp.analysis import read_atoms
from tribolmp.analysis.synthetic import write_dump, write_meta


def _write(tmp_path):
    pos = np.array([[1.0, 6.0, 0.0], [2.0, 9.0, 0.0], [3.0, 12.0, 0.0], [4.0, 14.0, 0.0]])  # nm
    box = np.array([[-10.0, 10.0], [5.0, 15.0], [-0.5, 0.5]])
    frames = [
        dict(
            step=100 * k,
            box=box,
            mol=np.array([1, 2, 3, 4]),
            pos=pos + [k, 0, 0],
            vel=np.full((4, 3), 5.0),
            radius=1.25,
            nbond=np.array([3, 2, 1, 0]),
        )
        for k in range(3)
    ]
    write_dump(tmp_path / "traj.lammpstrj", frames)
    write_meta(tmp_path, dt_s=2e-14, dump_interval_steps=100, velocity_m_s=5.0, diameter_m=2.5e-9,
               box_m=box * 1e-9, automaton_mass_kg=1.0554684608622843e-22)
    return pos, box


def test_read_atoms_is_in_ase_units(tmp_path):
    from ase import units

    pos, box = _write(tmp_path)
    atoms = read_atoms(tmp_path / "traj.lammpstrj")
    # nm -> Angstrom: x 10 (ASE's own reader without units="nano" would keep
    # the nm numbers as Angstrom)
    np.testing.assert_allclose(atoms.positions, (pos + [2, 0, 0]) * 10.0, atol=1e-4)
    np.testing.assert_allclose(atoms.cell.lengths(), [200.0, 100.0, 10.0])
    # 5 m/s = 5e-5 Angstrom/fs
    np.testing.assert_allclose(atoms.get_velocities() * units.fs, 5e-5, rtol=1e-6)
    # amu: 1.0555e-22 kg / 1.6605e-27 kg
    np.testing.assert_allclose(
        atoms.get_masses(), 1.0554684608622843e-22 / 1.66053906660e-27, rtol=1e-9
    )
    np.testing.assert_array_equal(atoms.get_tags(), [1, 2, 3, 4])
    np.testing.assert_allclose(atoms.get_array("diameter"), 25.0)  # 2 x 1.25 nm in Angstrom
    np.testing.assert_array_equal(atoms.get_array("c_nbond"), [3, 2, 1, 0])
    assert atoms.info["step"] == 200 and atoms.info["time_s"] == pytest.approx(4e-12)
    assert list(atoms.pbc) == [True, False, True]
    frames = read_atoms(tmp_path, index=slice(None))
    assert len(frames) == 3 and frames[0].info["step"] == 0


def test_raw_ase_reading_is_in_nm(tmp_path):
    """Why the hand-off exists: ase.io reads the nano dump as if it were Angstrom (metal units)."""
    import ase.io

    pos, _ = _write(tmp_path)
    raw = ase.io.read(tmp_path / "traj.lammpstrj", format="lammps-dump-text", index=0)
    # the numbers are the nm values taken as Angstrom: distances 10x too small
    ours = read_atoms(tmp_path, index=0)
    assert np.ptp(raw.positions[:, 1]) == pytest.approx(np.ptp(pos[:, 1]), rel=1e-6)
    assert np.ptp(ours.positions[:, 1]) == pytest.approx(10 * np.ptp(raw.positions[:, 1]), rel=1e-6)


def test_missing_dump_is_one_line(tmp_path):
    from tribolmp.errors import DataFileError

    with pytest.raises(DataFileError, match="no such file"):
        read_atoms(tmp_path / "nope.lammpstrj")
    _write(tmp_path)
    (tmp_path / "meta.json").unlink()
    atoms = read_atoms(tmp_path)  # no meta: positions still converted, masses unknown
    assert atoms.get_array("diameter")[0] == pytest.approx(25.0)
    assert "time_s" not in atoms.info
    assert json.dumps(atoms.info)
