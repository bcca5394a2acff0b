"""Hand-offs of an MCA dump to the tools users already have: ASE (and the notes for OVITO).

The decks run in LAMMPS ``units nano``: the dump holds positions in nm and
velocities in nm/ns.  ASE's own LAMMPS-dump reader assumes ``units metal``
(Angstrom, ps) unless told otherwise, so ``ase.io.read(dump)`` returns
positions 10x too small (nm read as Angstrom); ``ase.io.read(dump,
format="lammps-dump-text", units="nano")`` converts, but knows nothing of
bodies, diameters or masses.  :func:`read_atoms` returns ASE ``Atoms`` in
ASE units with what the MCA analyses need.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..errors import DataFileError

__all__ = ["read_atoms"]

#: 1 amu in kg (CODATA 2018, the value ASE uses).
AMU_KG = 1.66053906660e-27


def _meta_for(dump: Path, meta):
    from .outputs import MCAMeta, read_meta

    if isinstance(meta, MCAMeta):
        return meta
    if meta is not None:
        return read_meta(meta)
    candidate = dump.parent / "meta.json"
    return read_meta(candidate) if candidate.exists() else None


def read_atoms(dump, index=-1, *, meta=None):
    """Frames of an MCA dump as ASE ``Atoms`` in ASE units.

    Parameters
    ----------
    dump : str or Path
        ``traj.lammpstrj`` of an MCA run (or its output directory).
    index : int or slice
        Frame(s) to return (default the last); a slice returns a list.
    meta : str, Path or MCAMeta, optional
        The run's ``meta.json`` (default: next to the dump).  Without it the
        masses are unknown (ASE's default per symbol) and the time is the
        MD step.

    Returns
    -------
    ase.Atoms or list of ase.Atoms
        Positions in Angstrom (nm x 10, in the absolute LAMMPS frame),
        velocities in ASE units (Angstrom per ASE time unit, from m/s), the
        cell from the dump's box (Angstrom), ``pbc`` (x, z periodic, y the
        interface normal not), masses in amu from ``meta.json``'s automaton
        mass, ``tags`` = molecule id (1 base, 2 lower body, 3 upper body,
        4 slider), and the arrays ``diameter`` (Angstrom, twice the dump
        radius), ``mol``, ``id`` and ``c_nbond``.  ``atoms.info`` holds
        ``step``, ``time_s`` (when the MD timestep is known) and
        ``units_source`` ("LAMMPS units nano converted to ASE units").
        Every automaton is the chemical symbol ``Fe`` (steel automata; the
        symbol carries no physics here).
    """
    import ase
    from ase import units

    from .outputs import DUMP_COLUMNS, MCAMeta, open_trajectory

    path = Path(dump)
    if path.is_dir():
        path = path / "traj.lammpstrj"
    if not path.exists():
        raise DataFileError(f"{path}: expected a LAMMPS dump, got no such file")
    m = _meta_for(path, meta)
    if m is None:
        # no meta.json: open with placeholder timing; only positions, ids and columns are used
        m = MCAMeta(dt_s=1e-12, dump_interval_steps=1, dump_interval_s=1e-12, velocity_m_s=1.0,
                    automaton_diameter_m=1e-9)
        known = False
    else:
        known = True
    u = open_trajectory(path.parent, m, dump=path)
    n_frames = u.trajectory.n_frames
    if isinstance(index, slice):
        frames = list(range(n_frames))[index]
    else:
        i = int(index)
        if not -n_frames <= i < n_frames:
            raise DataFileError(
                f"{path}: index: expected a frame in [{-n_frames}, {n_frames - 1}], got {index}"
            )
        frames = [i % n_frames]
    mass_kg = m.raw.get("automaton_mass_kg") if known else None
    nm_to_A = 10.0
    out = []
    for f in frames:
        ts = u.trajectory[f]
        lo = ts.data["box_lo"] * nm_to_A
        lengths = np.asarray(ts.dimensions[:3], dtype=float) * nm_to_A
        pos = ts.positions.astype(float) * nm_to_A
        n = pos.shape[0]
        atoms = ase.Atoms(["Fe"] * n, positions=pos, cell=np.diag(lengths), celldisp=lo,
                          pbc=(True, False, True))
        if mass_kg:
            atoms.set_masses(np.full(n, float(mass_kg) / AMU_KG))
        if ts.has_velocities:
            # (after the masses: ASE stores momenta) dump velocities are nm/ns = m/s; the ASE
            # velocity unit is Angstrom / (ASE time unit), and 1 s = units.second ASE time units
            atoms.set_velocities(ts.velocities.astype(float) * 1e10 / units.second)
        mol = ts.data["mol"].astype(int)
        atoms.set_tags(mol)
        atoms.set_array("mol", mol)
        atoms.set_array("id", ts.data["id"].astype(int))
        if "radius" in ts.data:
            atoms.set_array("diameter", 2.0 * ts.data["radius"].astype(float) * nm_to_A)
        if "c_nbond" in ts.data:
            atoms.set_array("c_nbond", np.rint(ts.data["c_nbond"]).astype(int))
        atoms.info["step"] = int(ts.data["step"])
        if known:
            atoms.info["time_s"] = float(ts.data["step"]) * m.dt_s
        atoms.info["units_source"] = "LAMMPS units nano converted to ASE units (Angstrom, amu)"
        atoms.info["columns"] = list(DUMP_COLUMNS)
        out.append(atoms)
    return out if isinstance(index, slice) else out[0]
