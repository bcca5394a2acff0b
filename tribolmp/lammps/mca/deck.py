"""The ``-var`` values of ``lammps_inputs/mca_friction.in``.

LAMMPS ``units nano``, computed from SI parameters.

Every conversion goes through :mod:`tribolmp.units`.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from ...units import from_lammps, to_lammps
from ..decks import laws_dir
from ..laws import NEIGHBOR_SKIN, get_law
from .params import MCAParams

__all__ = ["deck_variables", "steps_of"]


def steps_of(t: float, dt_s: float) -> int:
    """Whole timesteps in ``t`` seconds (at least one)."""
    return max(1, int(round(t / dt_s)))


def deck_variables(
    params: MCAParams, *, data: str | Path, out: str | Path, seed: int, geom_info: dict
) -> dict[str, Any]:
    """Return the ``-var`` values of ``mca_friction.in`` for ``params`` (LAMMPS nano units).

    Parameters
    ----------
    params : MCAParams
    data, out : path
        Data file and output directory.
    seed : int
        LAMMPS seed (the heat sinks' Langevin streams; they draw no random
        force at T = 0, so the default deck is deterministic).
    geom_info : dict
        ``lx_nm``, ``lz_nm``, ``sink_lo_nm``, ``sink_hi_nm`` from the built system (nm).
    """
    law = get_law(params.bond_style)
    c = law.map_material(params.material())
    dt = params.dt_factor * c.dt_unit  # LAMMPS time unit (ns)
    dt_s = from_lammps(dt, "time")
    area = geom_info["lx_nm"] * geom_info["lz_nm"]  # nm^2 (LAMMPS area)
    fn = to_lammps(params.pressure, "pressure") * area  # LAMMPS force (pressure x area)
    d = to_lammps(params.automaton_diameter, "length")
    every = steps_of(params.print_interval, dt_s)
    # restarts on whole averaging windows of friction.csv, so that a resumed
    # run repeats them exactly
    restart_every = max(1, round(steps_of(params.restart_interval, dt_s) / every)) * every
    variables: dict[str, Any] = {
        "data": str(data),
        "out": str(out),
        "lawdir": str(laws_dir()),
        "dim": params.dim,
        "bond": law.keyword,
        "drive": "python",
        "seed": seed,
        "dt": f"{dt:.10g}",
        "steps": steps_of(params.duration, dt_s),
        "ramp_steps": steps_of(params.ramp_time, dt_s) if params.ramp_time > 0 else 1,
        "thermo_every": every * 10,
        "dump_every": steps_of(params.dump_interval, dt_s),
        "print_every": every,
        "restart_every": restart_every,
        "V": f"{to_lammps(params.sliding_velocity, 'velocity'):.10g}",
        "FN": f"{fn:.10g}",
        "approach_v": f"{to_lammps(params.approach_velocity, 'velocity'):.10g}",
        **law.deck_variables(c),
        "rebond_factor": max(params.rebond_factor, 1e-6),
        "kc": f"{c.k_contact:.10g}",
        "gc": f"{c.gamma_contact:.10g}",
        "muc": c.mu_contact,
        "rebond_every": steps_of(params.rebond_interval, dt_s),
        "rebond_r": f"{c.contact_diameter * (1.0 - params.rebond_strain):.10g}",
        "sink_lo": f"{geom_info['sink_lo_nm']:.10g}",
        "sink_hi": f"{geom_info['sink_hi_nm']:.10g}",
        "sink_tau": f"{to_lammps(params.sink_tau, 'time'):.10g}",
        # per law: the bpm links may stretch to (1 + rupture strain) d, and 2.2 d keeps them
        # and their partners' neighbours visible; the mca law needs its neighbour range only
        "comm_cut": f"{law.ghost_cutoff * d:.10g}",
        "skin": f"{NEIGHBOR_SKIN * d:.10g}",
        # SI value of one LAMMPS unit, for the SI columns of friction.csv
        "si_force": f"{from_lammps(1.0, 'force'):.10g}",
        "si_length": f"{from_lammps(1.0, 'length'):.10g}",
        "si_time": f"{from_lammps(1.0, 'time'):.10g}",
    }
    if law.setup is not None:
        variables.update(law.setup())
    return variables
