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

    Raises
    ------
    BlowUpError
        Lost atoms, links past the communication cutoff, NaN (step and cause named).
    LammpsError
        Any other LAMMPS error (e.g. an unreadable restart file).
    """
    from ..session import LammpsSession

    variables = dict(variables)
    steps = int(variables["steps"])
    chunk = int(variables["restart_every"])
    start_step = 0
    if restart is not None:
        start_step = restart[0]
        variables["restart"] = str(restart[1])
        variables["resume"] = 1
    t0 = time.perf_counter()
    with LammpsSession(log=None, variables=variables) as lmp:
        lmp.require_styles(get_law(law).styles)
        is_root = lmp.rank == 0
        if start_step > 0 and is_root:
            truncate_outputs(out, start_step, from_lammps(float(variables["dt"]), "time"))
        try:
            lmp.file(deck_path("mca_friction"))  # setup errors are not blow-ups: LammpsError as is
        except LammpsError as exc:
            if restart is None:
                raise
            raise RestartUnreadableError(
                f"restart file {restart[1].name} unreadable: {exc.message}"
            ) from None
        natoms = lmp.natoms()
        step = int(lmp.thermo("step"))
        t_run = time.perf_counter()
        while step < steps:
            target = min(steps, (step // chunk + 1) * chunk)
            try:
                lmp.command(f"run {target} upto post no")
            except LammpsError as exc:
                raise classify(exc, exc.step) from None
            step = int(lmp.thermo("step"))
            vals = [
                lmp.thermo("ke"),
                lmp.lmp.extract_variable("friction"),
                lmp.lmp.extract_variable("normal"),
            ]
            if not all(math.isfinite(float(v)) for v in vals):
                raise nonfinite_error(step, out)
            # every chunk ends on a restart step (or the last step): the state to resume from
            write_restart(lmp, out, step, is_root=is_root)
            if is_root:
                prune_restarts(out)
        wall_run = time.perf_counter() - t_run
        nprocs = lmp.nprocs
        bonds = int(lmp.thermo("bonds"))
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
