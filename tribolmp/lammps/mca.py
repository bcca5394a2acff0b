"""Driver of the MCA friction experiment: ``run_mca(params, out_dir, *, seed, resume=False, np=1)``.

The driver validates the parameters before LAMMPS starts, builds the system
with ASE (:mod:`tribolmp.lammps.build`), maps the material onto bond and
contact coefficients (:mod:`tribolmp.lammps.mapping`), runs the single deck
``lammps_inputs/mca_friction.in`` through :class:`LammpsSession` in chunks of
one restart interval, checks every chunk for lost atoms, links stretched past
the communication cutoff and non-finite forces, and keeps the last restart
file.  ``np > 1`` runs the same code under the mpich wheel's ``mpiexec``
(``python -m tribolmp.lammps.mca``).

Output directory contract (read by :mod:`tribolmp.analysis`):
``traj.lammpstrj`` (``id mol type x y z vx vy vz radius c_nbond``, LAMMPS nano
units), ``friction.csv`` (``time_s,friction_N,normal_N,top_x_m``, SI),
``run.log``, ``restart.<step>.bin``, ``meta.json`` and, when the analysis
package provides it, ``rates.json``.
"""

from __future__ import annotations

import dataclasses
import json
import math
import os
import re
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import BlowUpError, LammpsError, ParameterError, RunError
from ..models.base import Result, check_int
from ..rng import as_generator, lammps_seed
from ..scene.fields import param, validate_dataclass
from .decks import deck_path
from .mapping import MaterialSpec, link_deck_variables, map_material

__all__ = [
    "PRESETS",
    "MCAParams",
    "deck_variables",
    "main",
    "params_from_scene",
    "preset_params",
    "run_mca",
]

MOLECULES = {"1": "base", "2": "lower body", "3": "upper body", "4": "rigid slider"}


@dataclass(frozen=True)
class MCAParams:
    """Parameters of one MCA friction run (SI units).

    Defaults are the seed's steel couple at the ``smoke`` size; see
    :data:`PRESETS` for the larger ones.
    """

    dim: int = param(2, choices=(2, 3), doc="Spatial dimension (2: hexagonal sheet, 3: FCC).")
    automaton_diameter: float = param(
        2.5e-9, unit="m", lo=0.5e-9, hi=50e-9, doc="Automaton size d."
    )
    bond_style: str = param(
        "bpm/spring/plastic", choices=("bpm/spring/plastic", "bpm/rotational"), doc="Link model."
    )
    sliding_velocity: float = param(
        5.0, unit="m/s", lo=0.0, lo_open=True, hi=100.0, doc="Slider velocity."
    )
    pressure: float = param(
        150e6, unit="Pa", lo=0.0, lo_open=True, hi=2e9, doc="Normal pressure on the slider."
    )
    duration: float = param(1e-9, unit="s", lo=0.0, lo_open=True, hi=1e-5, doc="Simulated time.")
    box_length: float = param(
        50e-9, unit="m", lo=0.0, lo_open=True, hi=1e-5, doc="Periodic length along x."
    )
    box_width: float = param(
        10e-9, unit="m", lo=0.0, lo_open=True, hi=1e-5, doc="Periodic width along z (3D)."
    )
    body_height: float = param(
        15e-9, unit="m", lo=0.0, lo_open=True, hi=1e-5, doc="Height of each body."
    )
    roughness_rms: float = param(
        1.5e-9, unit="m", lo=0.0, hi=1e-6, doc="Rms height of each rough surface."
    )
    hurst: float = param(0.8, lo=0.0, hi=1.0, lo_open=True, doc="Hurst exponent of the surfaces.")
    youngs_modulus: float = param(206e9, unit="Pa", lo=0.0, lo_open=True, hi=2e12, doc="E.")
    poisson_ratio: float = param(0.3, lo=-1.0, hi=0.5, lo_open=True, hi_open=True, doc="nu.")
    yield_strength: float = param(480e6, unit="Pa", lo=0.0, lo_open=True, hi=1e11, doc="sigma_y.")
    ultimate_strength: float = param(
        552e6, unit="Pa", lo=0.0, lo_open=True, hi=1e11, doc="sigma_u."
    )
    density: float = param(7800.0, unit="kg/m^3", lo=0.0, lo_open=True, hi=1e5, doc="Mass density.")
    failure_strain: float = param(
        0.05, lo=0.0, hi=0.5, lo_open=True, doc="Link rupture strain (uniaxial)."
    )
    damping_ratio: float = param(
        0.1, lo=0.0, hi=1.0, doc="Link/contact damping, fraction of critical."
    )
    contact_friction: float = param(0.5, lo=0.0, hi=10.0, doc="Coulomb cap of contact viscosity.")
    dt_factor: float = param(0.1, lo=0.0, lo_open=True, hi=10.0, doc="Timestep / sqrt(m/k).")
    ramp_time: float = param(0.1e-9, unit="s", lo=0.0, hi=1e-6, doc="Velocity ramp 0 -> V.")
    approach_velocity: float = param(
        5.0,
        unit="m/s",
        lo=0.0,
        lo_open=True,
        hi=100.0,
        doc="Dashpot speed of the slider under F_N.",
    )
    rebond_factor: float = param(1.0, lo=0.0, hi=1.0, doc="Strength of re-formed links / original.")
    rebond_strain: float = param(
        0.01, lo=0.0, hi=0.2, doc="Extra compression below contact for re-linking."
    )
    rebond_interval: float = param(
        5e-12, unit="s", lo=0.0, lo_open=True, hi=1e-6, doc="Re-linking check interval."
    )
    sink_depth: float = param(
        0.0,
        unit="m",
        lo=0.0,
        hi=1e-5,
        doc="Thickness of the heat-sink layers next to base and slider (0: none).",
    )
    sink_tau: float = param(
        10e-12, unit="s", lo=0.0, lo_open=True, hi=1e-6, doc="Heat-sink time constant."
    )
    dump_interval: float = param(
        50e-12, unit="s", lo=0.0, lo_open=True, hi=1e-3, doc="Trajectory interval."
    )
    print_interval: float = param(
        5e-12, unit="s", lo=0.0, lo_open=True, hi=1e-3, doc="friction.csv interval."
    )
    restart_interval: float = param(
        0.25e-9, unit="s", lo=0.0, lo_open=True, hi=1e-3, doc="Restart file interval."
    )
    preset: str = param(
        "smoke",
        choices=("smoke", "default", "paper", "custom"),
        doc="Name of the size/time preset.",
    )

    def __post_init__(self) -> None:
        validate_dataclass(self)
        d = self.automaton_diameter
        if self.box_length < 8 * d:
            raise ParameterError(
                "box_length", f"a value >= 8 automaton diameters ({8 * d:g} m)", self.box_length
            )
        if self.body_height < 4 * d:
            raise ParameterError(
                "body_height", f"a value >= 4 automaton diameters ({4 * d:g} m)", self.body_height
            )
        if self.dim == 3 and self.box_width < 2.9 * d:
            raise ParameterError(
                "box_width", f"a value >= 2 FCC cells ({2.9 * d:g} m)", self.box_width
            )
        if self.roughness_rms > self.body_height / 4:
            raise ParameterError(
                "roughness_rms",
                f"a value <= body_height/4 ({self.body_height / 4:g} m)",
                self.roughness_rms,
            )
        spec = self.material()  # validates the material cross-checks
        coeff = map_material(spec)
        if self.dt_factor > 0.5 * coeff.dt_max_factor:
            # half the Verlet limit of the lattice: contacts and damping need margin
            raise ParameterError(
                "dt_factor",
                f"a value <= {0.5 * coeff.dt_max_factor:.3g} (half the lattice's Verlet stability limit)",
                self.dt_factor,
            )
        if self.pressure >= coeff.flow_stress:
            raise ParameterError(
                "pressure",
                f"a value below the lattice's flow stress {coeff.flow_stress:g} Pa (it would crush the lattice)",
                self.pressure,
            )
        if self.duration < self.ramp_time:
            raise ParameterError(
                "duration", f"a value >= ramp_time ({self.ramp_time:g} s)", self.duration
            )

    def material(self) -> MaterialSpec:
        """The :class:`MaterialSpec` of the bodies."""
        return MaterialSpec(
            youngs_modulus=self.youngs_modulus,
            poisson_ratio=self.poisson_ratio,
            yield_strength=self.yield_strength,
            ultimate_strength=self.ultimate_strength,
            diameter=self.automaton_diameter,
            density=self.density,
            dim=self.dim,
            bond_style=self.bond_style,
            failure_strain=self.failure_strain,
            damping_ratio=self.damping_ratio,
            contact_friction=self.contact_friction,
        )

    def replace(self, **changes: Any) -> MCAParams:
        """A copy with some fields changed (validated again)."""
        return dataclasses.replace(self, **changes)


#: Size/time presets.  ``smoke``: < 1 min for CI.  ``default``: the issue's
#: feasibility size (200 x ~100 nm, d = 2.5 nm, ~3.6k automata) for 20 ns.
#: ``paper``: the same size for 100 ns (the seed's time to dynamic equilibrium).
PRESETS: dict[str, dict[str, Any]] = {
    "smoke": dict(
        box_length=50e-9,
        body_height=15e-9,
        duration=1e-9,
        roughness_rms=1.5e-9,
        restart_interval=0.25e-9,
    ),
    "default": dict(
        box_length=200e-9,
        body_height=45e-9,
        duration=20e-9,
        roughness_rms=2e-9,
        box_width=10e-9,
        dump_interval=0.2e-9,
        print_interval=10e-12,
        restart_interval=2e-9,
        sink_depth=5e-9,
    ),
    "paper": dict(
        box_length=200e-9,
        body_height=45e-9,
        duration=100e-9,
        roughness_rms=2e-9,
        box_width=10e-9,
        dump_interval=0.5e-9,
        print_interval=20e-12,
        restart_interval=5e-9,
        sink_depth=5e-9,
    ),
}


def preset_params(name: str = "smoke", **changes: Any) -> MCAParams:
    """Parameters of a named preset, with optional changes."""
    if name not in PRESETS:
        raise ParameterError("preset", f"one of {sorted(PRESETS)}", name)
    return MCAParams(**{**PRESETS[name], "preset": name, **changes})


def params_from_scene(scene) -> MCAParams:
    """Read ``[nanoscale]`` and ``[material]`` of a :class:`tribolmp.scene.Scene`."""
    nano = scene.nanoscale
    if nano is None:
        raise ParameterError("[nanoscale]", "a [nanoscale] section in the scene", None)
    mat = scene.material
    return preset_params(
        nano.preset,
        dim=nano.dim,
        automaton_diameter=nano.automaton_diameter,
        bond_style=nano.bond_style,
        sliding_velocity=nano.sliding_velocity,
        pressure=nano.pressure,
        duration=nano.duration,
        box_length=nano.box_length,
        body_height=nano.body_height,
        roughness_rms=nano.roughness_rms,
        youngs_modulus=mat.youngs_modulus,
        poisson_ratio=mat.poisson_ratio,
        yield_strength=mat.yield_strength,
        ultimate_strength=mat.ultimate_strength,
        density=mat.density,
    )


# ---------------------------------------------------------------------- deck


def _steps(t: float, dt: float) -> int:
    return max(1, int(round(t / dt)))


def deck_variables(
    params: MCAParams, *, data: str | Path, out: str | Path, seed: int, geom_info: dict
) -> dict[str, Any]:
    """The ``-var`` values of ``mca_friction.in`` for ``params`` (LAMMPS nano units).

    Parameters
    ----------
    params : MCAParams
    data, out : path
        Data file and output directory.
    seed : int
        LAMMPS seed (not used by the deterministic default deck, recorded).
    geom_info : dict
        ``lx_nm``, ``lz_nm``, ``sink_lo_nm``, ``sink_hi_nm`` from the built system.
    """
    c = map_material(params.material())
    dt = params.dt_factor * c.dt_unit  # ns
    dt_s = dt * 1e-9
    area_nm2 = geom_info["lx_nm"] * geom_info["lz_nm"]
    fn = params.pressure / 1e6 * area_nm2  # pressure unit 1e6 Pa x nm^2 = 1e-12 N
    d_nm = params.automaton_diameter * 1e9
    rot = params.bond_style == "bpm/rotational"
    every = _steps(params.print_interval, dt_s)
    # restarts on whole averaging windows of friction.csv, so that a resumed run repeats them exactly
    restart_every = max(1, round(_steps(params.restart_interval, dt_s) / every)) * every
    return {
        "data": str(data),
        "out": str(out),
        "dim": params.dim,
        "bond": "rotational" if rot else "plastic",
        "drive": "python",
        "seed": seed,
        "dt": f"{dt:.10g}",
        "steps": _steps(params.duration, dt_s),
        "ramp_steps": _steps(params.ramp_time, dt_s) if params.ramp_time > 0 else 1,
        "thermo_every": _steps(params.print_interval, dt_s) * 10,
        "dump_every": _steps(params.dump_interval, dt_s),
        "print_every": every,
        "restart_every": restart_every,
        "V": params.sliding_velocity,
        "FN": f"{fn:.10g}",
        "approach_v": params.approach_velocity,
        **link_deck_variables(c),
        "rebond_factor": max(params.rebond_factor, 1e-6),
        "kc": f"{c.k_contact:.10g}",
        "gc": f"{c.gamma_contact:.10g}",
        "muc": c.mu_contact,
        "rebond_every": _steps(params.rebond_interval, dt_s),
        "rebond_r": f"{c.contact_diameter * (1.0 - params.rebond_strain):.10g}",
        "maxbond": 6 if params.dim == 2 else 12,
        "sink_lo": f"{geom_info['sink_lo_nm']:.10g}",
        "sink_hi": f"{geom_info['sink_hi_nm']:.10g}",
        "sink_tau": f"{params.sink_tau * 1e9:.10g}",
        # links may stretch to (1 + rupture strain) d; 2.2 d keeps them and their partners' neighbours visible
        "comm_cut": f"{2.2 * d_nm:.10g}",
    }


# ---------------------------------------------------------------------- preparation


def _prepare(params: MCAParams, out: Path, seed: int, overrides: dict[str, Any]) -> dict[str, Any]:
    """Build the system, write ``system.data`` and ``meta.json``; return the deck variables."""
    from .build import MOL_LOWER, MOL_UPPER, build_system, write_bpm_data

    rng = as_generator(seed)
    lmp_seed = lammps_seed(rng)
    out.mkdir(parents=True, exist_ok=True)
    c = map_material(params.material())
    d_nm = params.automaton_diameter * 1e9
    geom = build_system(
        dim=params.dim,
        d=d_nm,
        length=params.box_length * 1e9,
        body_height=params.body_height * 1e9,
        roughness_rms=params.roughness_rms * 1e9,
        width=params.box_width * 1e9,
        hurst=params.hurst,
        rng=rng,
    )
    data = write_bpm_data(
        out / "system.data", geom, density=c.density_column, diameter=c.contact_diameter
    )
    pos = geom.atoms.positions
    mol = geom.atoms.arrays["mol_id"]
    sink = params.sink_depth * 1e9
    if sink > 0:
        sink_lo = pos[mol == MOL_LOWER, 1].min() + sink
        sink_hi = pos[mol == MOL_UPPER, 1].max() - sink
    else:
        sink_lo, sink_hi = -1e9, 1e9
    lx = geom.box[0, 1] - geom.box[0, 0]
    lz = geom.box[2, 1] - geom.box[2, 0]
    info = {"lx_nm": lx, "lz_nm": lz, "sink_lo_nm": sink_lo, "sink_hi_nm": sink_hi}
    variables = deck_variables(params, data=data, out=out, seed=lmp_seed, geom_info=info)
    unknown = sorted(set(overrides) - set(variables))
    if unknown:
        raise ParameterError("overrides", f"names of deck variables {sorted(variables)}", unknown)
    variables.update(overrides)
    dt_s = float(variables["dt"]) * 1e-9
    every = int(variables["dump_every"])
    meta = {
        "units": {
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
        },
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
        "normal_force_N": float(variables["FN"]) * 1e-12,
        "automaton_diameter_m": params.automaton_diameter,
        "contact_diameter_m": c.contact_diameter * 1e-9,
        "box_m": (geom.box * 1e-9).tolist(),
        "dimension": params.dim,
        "normal_axis": "y",
        "sliding_axis": "x",
        "density_kg_m3": params.density,
        "automaton_mass_kg": c.mass * 1e-21,
        "molecules": MOLECULES,
        "atom_types": {"1": "deformable", "2": "base", "3": "slider"},
        "bond_types": {"1": "original link", "2": "re-formed link", "3": "unbreakable attachment"},
        "n_atoms": geom.n_atoms,
        "n_atoms_by_mol": {str(m): geom.count(m) for m in (1, 2, 3, 4)},
        "interface_y_m": geom.interface_y * 1e-9,
        "seed": seed,
        "lammps_seed": lmp_seed,
        "params": dataclasses.asdict(params),
        "mapping": {
            k: (float(v) if isinstance(v, (float, np.floating)) else v)
            for k, v in c.as_dict().items()
        },
        "deck": str(deck_path("mca_friction")),
        "deck_variables": {k: str(v) for k, v in variables.items()},
        "overrides": {k: str(v) for k, v in overrides.items()},
    }
    (out / "meta.json").write_text(json.dumps(meta, indent=1))
    return variables


# ---------------------------------------------------------------------- restarts and resume

_RESTART = re.compile(r"restart\.(\d+)\.bin$")


def restart_files(out: Path) -> list[tuple[int, Path]]:
    """Restart files in ``out`` as (step, path), oldest first."""
    found = []
    for p in Path(out).glob("restart.*.bin"):
        m = _RESTART.search(p.name)
        if m:
            found.append((int(m.group(1)), p))
    return sorted(found)


def _prune_restarts(out: Path, keep: int = 2) -> None:
    for _step, p in restart_files(out)[:-keep]:
        p.unlink(missing_ok=True)


def _truncate_outputs(out: Path, step: int, dt_s: float) -> None:
    """Drop friction.csv rows and trajectory frames from ``step`` on (the resumed run writes them again)."""
    csv = out / "friction.csv"
    if csv.exists():
        lines = csv.read_text().splitlines()
        t_max = step * dt_s * (1 + 1e-9)
        kept = [lines[0]] + [ln for ln in lines[1:] if ln and float(ln.split(",")[0]) <= t_max]
        csv.write_text("\n".join(kept) + "\n")
    traj = out / "traj.lammpstrj"
    if traj.exists():
        text = traj.read_text()
        frames = text.split("ITEM: TIMESTEP\n")
        kept = [f for f in frames[1:] if int(f.split("\n", 1)[0]) <= step]
        traj.write_text("".join("ITEM: TIMESTEP\n" + f for f in kept))


def _dedupe_outputs(out: Path) -> None:
    """Drop repeated friction.csv rows and dump frames, keeping the first of each.

    LAMMPS's ``fix print`` and ``dump`` also write on the first step of every ``run`` command, so the
    step that ends one chunk (or the restart step of a resumed run) is written twice; the first copy
    is the one of the uninterrupted run.
    """
    csv = out / "friction.csv"
    if csv.exists():
        lines = csv.read_text().splitlines()
        seen: set[str] = set()
        kept = [lines[0]]
        for ln in lines[1:]:
            key = ln.split(",", 1)[0]
            if ln and key not in seen:
                seen.add(key)
                kept.append(ln)
        csv.write_text("\n".join(kept) + "\n")
    traj = out / "traj.lammpstrj"
    if traj.exists():
        frames = traj.read_text().split("ITEM: TIMESTEP\n")[1:]
        steps = [f.split("\n", 1)[0] for f in frames]
        if len(set(steps)) != len(steps):
            seen = set()
            with traj.open("w") as fh:
                for st, fr in zip(steps, frames, strict=True):
                    if st not in seen:
                        seen.add(st)
                        fh.write("ITEM: TIMESTEP\n" + fr)


# ---------------------------------------------------------------------- running

_CAUSES = (
    (re.compile(r"lost atoms", re.IGNORECASE), "lost atoms (an automaton left the box)"),
    (
        re.compile(r"bond atoms? .*missing|atom missing in bpm bond", re.IGNORECASE),
        "a link stretched past the communication cutoff (bond atoms missing)",
    ),
    (
        re.compile(r"non-numeric atom|out of range atoms|\bnan\b.*(force|coord|position)", re.IGNORECASE),
        "non-finite positions or forces (NaN)",
    ),
)


def _classify(exc: LammpsError, step: int | None) -> RunError:
    for pattern, cause in _CAUSES:
        if pattern.search(exc.message):
            return BlowUpError(
                f"MCA run failed at step {step if step is not None else '?'}: {cause}; last restart kept; LAMMPS: {exc.message}"
            )
    return exc


def _run_lammps(variables: dict[str, Any], out: Path, *, resume: bool) -> dict[str, Any]:
    """Run the deck in chunks of one restart interval; returns counters.  Works under MPI."""
    from .session import LammpsSession

    variables = dict(variables)
    steps = int(variables["steps"])
    chunk = int(variables["restart_every"])
    start_step = 0
    if resume:
        found = restart_files(out)
        if found:
            start_step, path = found[-1]
            variables["restart"] = str(path)
            variables["resume"] = 1
    t0 = time.perf_counter()
    with LammpsSession(log=None, variables=variables) as lmp:
        lmp.require_styles()
        is_root = lmp.rank == 0
        if resume and start_step > 0 and is_root:
            _truncate_outputs(out, start_step, float(variables["dt"]) * 1e-9)
        lmp.file(deck_path("mca_friction"))  # setup errors are not blow-ups: LammpsError as is
        natoms = lmp.natoms()
        step = int(lmp.thermo("step"))
        t_run = time.perf_counter()
        while step < steps:
            target = min(steps, (step // chunk + 1) * chunk)
            try:
                lmp.command(f"run {target} upto post no")
            except LammpsError as exc:
                raise _classify(exc, exc.step) from None
            step = int(lmp.thermo("step"))
            vals = [
                lmp.thermo("ke"),
                lmp.lmp.extract_variable("friction"),
                lmp.lmp.extract_variable("normal"),
            ]
            if not all(math.isfinite(float(v)) for v in vals):
                raise BlowUpError(
                    f"MCA run failed at step {step}: non-finite kinetic energy or forces (NaN); last restart kept in {out}"
                )
            if is_root:
                _prune_restarts(out)
        wall_run = time.perf_counter() - t_run
        if step % chunk:
            lmp.command(f"write_restart {out}/restart.{step}.bin")
            if is_root:
                _prune_restarts(out)
        nprocs = lmp.nprocs
        bonds = int(lmp.thermo("bonds"))
    if is_root:
        _dedupe_outputs(out)
    return {
        "steps_run": steps - start_step,
        "start_step": start_step,
        "final_step": step,
        "natoms": natoms,
        "wall_run_s": wall_run,
        "wall_s": time.perf_counter() - t0,
        "nprocs": nprocs,
        "bonds": bonds,
        "is_root": is_root,
    }


def _mpi_command(np_: int) -> list[str]:
    mpiexec = Path(sys.executable).parent / "mpiexec"
    if not mpiexec.exists():
        from ..errors import MissingFeatureError

        raise MissingFeatureError(
            f"mpiexec: expected the mpich wheel's mpiexec next to {sys.executable}, got none"
        )
    return [str(mpiexec), "-n", str(np_)]


def run_mca(
    params: MCAParams,
    out_dir: str | os.PathLike,
    *,
    seed: int,
    resume: bool = False,
    np: int = 1,
    overrides: dict[str, Any] | None = None,
) -> Result:
    """Run the MCA friction experiment and write the output-directory contract.

    Parameters
    ----------
    params : MCAParams
        Validated parameters (SI).
    out_dir : path
        Output directory (created).
    seed : int
        Seed of the geometry (surface roughness) and of the LAMMPS seed.
    resume : bool
        Continue from the newest ``restart.<step>.bin`` in ``out_dir``
        (outputs after that step are dropped and re-run).  Without a restart
        file the run starts from the beginning.
    np : int
        MPI ranks; ``np > 1`` runs ``mpiexec -n np python -m tribolmp.lammps.mca``.
    overrides : dict, optional
        Expert use (experiments, failure tests): deck variables (LAMMPS nano
        units) that replace the mapped values after validation.  Recorded in
        ``meta.json``.

    Returns
    -------
    Result
        ``out_dir``, ``mu``, ``mu_err``, ``layer_depth_m``, ``diffusion_m2_s``,
        ``transfer_rate`` (from ``rates.json`` when the analysis package is
        present, else ``mu`` from ``friction.csv`` over the second half),
        ``atom_steps_per_s``, ``time_s`` (simulated), ``wall_time_s``,
        ``natoms``, ``nprocs``, ``rates_path``.
    """
    if not isinstance(params, MCAParams):
        raise ParameterError("params", "an MCAParams instance", type(params).__name__)
    np_ = check_int("np", np, 1, 64)
    seed = check_int("seed", seed, 0, 2**63 - 1)
    out = Path(out_dir).resolve()
    t0 = time.perf_counter()
    meta_path = out / "meta.json"
    if resume and meta_path.exists() and restart_files(out):
        variables = json.loads(meta_path.read_text())["deck_variables"]
    else:
        resume = False
        variables = _prepare(params, out, seed, overrides or {})
    if np_ == 1:
        counters = _run_lammps(variables, out, resume=resume)
    else:
        cmd = (
            _mpi_command(np_)
            + [sys.executable, "-m", "tribolmp.lammps.mca", str(out)]
            + (["--resume"] if resume else [])
        )
        env = {k: v for k, v in os.environ.items() if k != "LD_LIBRARY_PATH"}
        proc = subprocess.run(cmd, capture_output=True, text=True, env=env, check=False)
        if proc.returncode != 0:
            last = (proc.stderr.strip().splitlines() or ["(no output)"])[-1]
            raise RunError(f"MCA run under mpiexec -n {np_} failed: {last}")
        counters = json.loads((out / "counters.json").read_text())
    return _finish(out, counters, t0)


def _finish(out: Path, counters: dict[str, Any], t0: float) -> Result:
    meta = json.loads((out / "meta.json").read_text())
    dt_s = meta["dt_s"]
    rate = counters["natoms"] * counters["steps_run"] / max(counters["wall_run_s"], 1e-12)
    meta.update(
        {
            "time_s": counters["final_step"] * dt_s,
            "atom_steps_per_s": rate,
            "wall_time_s": counters["wall_s"],
            "nprocs": counters["nprocs"],
            "final_step": counters["final_step"],
            "bonds_final": counters["bonds"],
        }
    )
    (out / "meta.json").write_text(json.dumps(meta, indent=1))
    res = Result(
        out_dir=str(out),
        atom_steps_per_s=rate,
        time_s=counters["final_step"] * dt_s,
        wall_time_s=time.perf_counter() - t0,
        natoms=counters["natoms"],
        nprocs=counters["nprocs"],
        nit=counters["final_step"],
        method="lammps/" + meta["params"]["bond_style"],
        units={
            "mu": "1",
            "mu_err": "1",
            "layer_depth_m": "m",
            "diffusion_m2_s": "m^2/s",
            "transfer_rate": "1/m",
            "atom_steps_per_s": "1/s",
            "time_s": "s",
            "wall_time_s": "s",
        },
    )
    fr = np.loadtxt(out / "friction.csv", delimiter=",", skiprows=1, ndmin=2)
    half = fr[fr[:, 0] >= 0.5 * fr[-1, 0]]
    res["mu_raw"] = (
        float(half[:, 1].mean() / half[:, 2].mean()) if half[:, 2].mean() > 0 else float("nan")
    )
    rates = _rates(out)
    if rates is not None:
        for key in ("mu", "mu_err", "layer_depth_m", "diffusion_m2_s", "transfer_rate"):
            res[key] = rates.get(key)
        res["rates_path"] = str(out / "rates.json")
        res["rates"] = rates
        res["message"] = "run finished; rates.json written"
    else:
        res.update(
            mu=res["mu_raw"],
            mu_err=None,
            layer_depth_m=None,
            diffusion_m2_s=None,
            transfer_rate=None,
            rates_path=None,
            status=1,
            message="run finished; tribolmp.analysis.rates not available, mu from friction.csv",
        )
    return res


def _rates(out: Path) -> dict | None:
    import importlib.util

    if importlib.util.find_spec("tribolmp.analysis.rates") is None:
        return None
    from ..analysis.rates import compute_rates  # lazy: MDAnalysis is heavy

    return compute_rates(out)


def main(argv: list[str] | None = None) -> int:
    """MPI entry point: ``mpiexec -n N python -m tribolmp.lammps.mca OUT_DIR [--resume]``.

    ``OUT_DIR`` must hold ``meta.json`` and ``system.data`` written by
    :func:`run_mca`'s preparation step; rank 0 writes ``counters.json``.
    """
    import argparse

    ap = argparse.ArgumentParser(prog="python -m tribolmp.lammps.mca")
    ap.add_argument("out")
    ap.add_argument("--resume", action="store_true")
    args = ap.parse_args(argv)
    out = Path(args.out).resolve()
    variables = json.loads((out / "meta.json").read_text())["deck_variables"]
    try:
        counters = _run_lammps(variables, out, resume=args.resume)
    except RunError as exc:
        print(f"{exc}", file=sys.stderr)
        return 3
    if counters.pop("is_root"):
        (out / "counters.json").write_text(json.dumps(counters))
    return 0


if __name__ == "__main__":  # pragma: no cover - exercised through mpiexec
    sys.exit(main())
