"""The run loop: the friction deck in chunks of one restart interval, checked after every chunk.

Works on one rank and under MPI (every rank runs this loop; rank 0 touches files).
"""

from __future__ import annotations

import math
import time
from pathlib import Path
from typing import Any

from ...errors import LammpsError
from ...units import from_lammps
from ..decks import deck_path
from ..laws import get_law
from .faults import RestartUnreadableError, classify, nonfinite_error
from .restart import prune_restarts, truncate_outputs, write_restart

__all__ = ["run_lammps"]


def run_lammps(
    variables: dict[str, Any], out: Path, *, law: str, restart: tuple[int, Path] | None
) -> dict[str, Any]:
    """Run ``mca_friction.in`` from the start or from ``restart`` = (step, file); return counters.

    Every chunk of one restart interval starts (after ``clear``) from the previous chunk's
    restart file (the first from the data file or from ``restart``), so an
    uninterrupted run passes through exactly the states a resumed run starts from: a resume
    repeats the uninterrupted run bit for bit on one rank, whatever LAMMPS does not keep in a
    restart file (neighbour lists, special-list order, per-run fix state).

    Raises
    ------
    BlowUpError
        Lost atoms, links past the communication cutoff, NaN (step and cause named).
    RestartUnreadableError
        LAMMPS could not set up from ``restart``.
    LammpsError
        Any other LAMMPS error.
    """
    from ..session import LammpsSession

    steps = int(variables["steps"])
    chunk = int(variables["restart_every"])
    start_step = restart[0] if restart is not None else 0
    law_def = get_law(law)
    styles = law_def.styles
    t0 = time.perf_counter()
    wall_run = 0.0
    step, current = start_step, restart
    natoms = nprocs = bonds = 0
    is_root = True
    first = True
    chunk_vars = dict(variables)
    if current is not None:
        chunk_vars.update(restart=str(current[1]), resume=1)
    with LammpsSession(log=None, variables=chunk_vars) as lmp:
        lmp.require_styles(styles)
        is_root = lmp.rank == 0
        nprocs = lmp.nprocs
        if start_step > 0 and is_root:
            truncate_outputs(out, start_step, from_lammps(float(variables["dt"]), "time"))
        while first or step < steps:
            if not first:
                # the next chunk starts from the restart file just written, as a resumed run would
                lmp.command("clear")
                lmp.set_variable("resume", 1)
                lmp.set_variable("restart", str(current[1]))
            try:
                lmp.file(deck_path("mca_friction"))  # setup errors are not blow-ups
            except LammpsError as exc:
                if current is None or not first:
                    raise
                raise RestartUnreadableError(
                    f"restart file {current[1].name} unreadable: {exc.message}"
                ) from None
            natoms = lmp.natoms()
            step = int(lmp.thermo("step"))
            first = False
            if step >= steps:
                bonds = int(lmp.thermo("bonds"))
                break
            target = min(steps, (step // chunk + 1) * chunk)
            t_run = time.perf_counter()
            try:
                if law_def.deferred_fragment is not None:
                    # see lammps_inputs/laws/bpm_relink.in: up to the step before a re-link step
                    every = int(variables["rebond_every"])
                    before = min(target, step + (-(step + 1)) % every)
                    if before > step:
                        lmp.command(f"run {before} upto post no")
                    lmp.command(f"include {Path(variables['lawdir']) / law_def.deferred_fragment}")
                lmp.command(f"run {target} upto post no")
            except LammpsError as exc:
                raise classify(exc, exc.step) from None
            wall_run += time.perf_counter() - t_run
            step = int(lmp.thermo("step"))
            vals = [
                lmp.thermo("ke"),
                lmp.lmp.extract_variable("friction"),
                lmp.lmp.extract_variable("normal"),
            ]
            if not all(math.isfinite(float(v)) for v in vals):
                raise nonfinite_error(step, out)
            bonds = int(lmp.thermo("bonds"))
            # the state to resume from, and the next chunk's start
            current = (step, write_restart(lmp, out, step, is_root=is_root))
            if is_root:
                prune_restarts(out)
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
