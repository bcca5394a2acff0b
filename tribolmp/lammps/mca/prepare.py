"""System preparation: build the bodies (ASE), write ``system.data`` and ``meta.json``."""

from __future__ import annotations

import dataclasses
from pathlib import Path
from typing import Any

import numpy as np

from ...errors import ParameterError
from ...rng import as_generator, lammps_seed
from ...units import from_lammps, to_lammps
from ..decks import deck_path
from ..laws import get_law
from .deck import deck_variables
from .params import MCAParams
from .restart import atomic_write_json

__all__ = ["MOLECULES", "prepare"]

MOLECULES = {"1": "base", "2": "lower body", "3": "upper body", "4": "rigid slider"}

META_UNITS = {
    "dt_s": "s",
    "dump_interval_s": "s",
    "velocity_m_s": "m/s",
    "pressure_Pa": "Pa",
    "automaton_diameter_m": "m",
    "box_m": "m",
    "density_kg_m3": "kg/m^3",
    "normal_force_N": "N",
    "traj.lammpstrj": "LAMMPS units nano: nm, nm/ns (= m/s)",
    "friction.csv": "SI",
    "time_s": "s",
    "atom_steps_per_s": "1/s",
    "wall_time_s": "s",
}


def prepare(params: MCAParams, out: Path, seed: int, overrides: dict[str, Any]) -> dict[str, Any]:
    """Build the system, write ``system.data`` and ``meta.json``; return the deck variables.

    ``meta.json`` is written last and atomically: a folder with a ``meta.json``
    has a complete data file.
    """
    from ..build import MOL_LOWER, MOL_UPPER, build_system, write_bpm_data

    rng = as_generator(seed)
    lmp_seed = lammps_seed(rng)
    out.mkdir(parents=True, exist_ok=True)
    c = get_law(params.bond_style).map_material(params.material())
    geom = build_system(
        dim=params.dim,
        d=to_lammps(params.automaton_diameter, "length"),
        length=to_lammps(params.box_length, "length"),
        body_height=to_lammps(params.body_height, "length"),
        roughness_rms=to_lammps(params.roughness_rms, "length"),
        width=to_lammps(params.box_width, "length"),
        hurst=params.hurst,
        rng=rng,
        texture=params.texture,
        grain_size=to_lammps(params.grain_size, "length"),
    )
    data = write_bpm_data(
        out / "system.data", geom, density=c.density_column, diameter=c.contact_diameter
    )
    pos = geom.atoms.positions
    mol = geom.atoms.arrays["mol_id"]
    sink = to_lammps(params.sink_depth, "length")
    if sink > 0:
        sink_lo = pos[mol == MOL_LOWER, 1].min() + sink
        sink_hi = pos[mol == MOL_UPPER, 1].max() - sink
    else:
        sink_lo, sink_hi = -1e9, 1e9  # no sink: bounds far outside any box (nm)
    lx = geom.box[0, 1] - geom.box[0, 0]
    lz = geom.box[2, 1] - geom.box[2, 0]
    info = {"lx_nm": lx, "lz_nm": lz, "sink_lo_nm": sink_lo, "sink_hi_nm": sink_hi}
    variables = deck_variables(params, data=data, out=out, seed=lmp_seed, geom_info=info)
    unknown = sorted(set(overrides) - set(variables))
    if unknown:
        raise ParameterError("overrides", f"names of deck variables {sorted(variables)}", unknown)
    variables.update(overrides)
    dt_s = from_lammps(float(variables["dt"]), "time")
    every = int(variables["dump_every"])
    meta = {
        "units": META_UNITS,
        "lammps_units": "nano",
        "dt_s": dt_s,
        "dump_interval_steps": every,
        "dump_interval_s": dt_s * every,
        "print_interval_steps": int(variables["print_every"]),
        "restart_interval_steps": int(variables["restart_every"]),
        "steps": int(variables["steps"]),
        "ramp_steps": int(variables["ramp_steps"]),
        "velocity_m_s": params.sliding_velocity,
        "pressure_Pa": params.pressure,
        "normal_force_N": from_lammps(float(variables["FN"]), "force"),
        "automaton_diameter_m": params.automaton_diameter,
        "contact_diameter_m": from_lammps(c.contact_diameter, "length"),
        "box_m": from_lammps(geom.box, "length").tolist(),
        "dimension": params.dim,
        "normal_axis": "y",
        "sliding_axis": "x",
        "density_kg_m3": params.density,
        "automaton_mass_kg": from_lammps(c.mass, "mass"),
        "molecules": MOLECULES,
        "atom_types": {"1": "deformable", "2": "base", "3": "slider"},
        "bond_types": {"1": "original link", "2": "re-formed link", "3": "unbreakable attachment"},
        "n_atoms": geom.n_atoms,
        "n_atoms_by_mol": {str(m): geom.count(m) for m in (1, 2, 3, 4)},
        "interface_y_m": from_lammps(geom.interface_y, "length"),
        "seed": seed,
        "lammps_seed": lmp_seed,
        "params": dataclasses.asdict(params),
        "law": params.bond_style,
        "body_texture": params.texture,
        "mapping": {
            k: (float(v) if isinstance(v, (float, np.floating)) else v)
            for k, v in c.as_dict().items()
        },
        "deck": str(deck_path("mca_friction")),
        "deck_variables": {k: str(v) for k, v in variables.items()},
        "overrides": {k: str(v) for k, v in overrides.items()},
    }
    atomic_write_json(out / "meta.json", meta)
    return variables
