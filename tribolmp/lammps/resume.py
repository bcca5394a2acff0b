"""Resume an interrupted MCA run from its restart files, repairing what a kill left behind.

Moved here from the chain's nanoscale stage (issue 11: LAMMPS restart repair
is LAMMPS-layer work, not glue).  mcadriver reworks it for issue 12 (exact,
idempotent resume); the chain calls only :func:`run_mca_resuming`.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from ..errors import LammpsError

__all__ = ["run_mca_resuming"]


def run_mca_resuming(
    params: Any, out: Path, *, seed: int, ranks: int = 1
) -> tuple[Any, dict[str, Any]]:
    """Run :func:`tribolmp.lammps.mca.run_mca` into ``out``, resuming from its restart files.

    A kill while LAMMPS was writing a restart file leaves it truncated: when
    LAMMPS refuses the newest restart file, that file is dropped and the run
    continues from the previous one (or from the start when none is left).

    Parameters
    ----------
    params : MCAParams
        The run's parameters.
    out : Path
        Output folder (kept across interrupts).
    seed : int
        LAMMPS seed.
    ranks : int
        MPI ranks.

    Returns
    -------
    result : Result
        What ``run_mca`` returned.
    info : dict
        ``resumed`` (bool) and ``discarded_restarts`` (file names dropped).
    """
    from . import mca

    out = Path(out)
    resume = out.is_dir() and any(out.iterdir())
    resumed = resume
    discarded: list[str] = []
    while True:
        try:
            res = mca.run_mca(params, out, seed=seed, resume=resume, np=ranks)
            return res, {"resumed": resumed, "discarded_restarts": discarded}
        except LammpsError as exc:
            restarts = mca.restart_files(out) if resume else []
            if not restarts or "restart" not in str(exc).lower():
                raise
            newest = max(restarts)[1]
            discarded.append(newest.name)
            newest.unlink()
            resume = bool(mca.restart_files(out))
