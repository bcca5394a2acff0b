"""MPI relaunch: ``mpiexec -n N python -m tribolmp.lammps.mca OUT [--restart FILE]``.

The calling process prepares the folder (data file, ``meta.json``); every rank
then runs :func:`tribolmp.lammps.mca.runner.run_lammps`; rank 0 writes
``counters.json``.  Failures come back as one line (the last line of the
ranks' stderr) and exit code 3.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
from pathlib import Path
from typing import Any

from ...errors import MissingFeatureError, RunError
from .faults import RestartUnreadableError
from .restart import atomic_write_json

__all__ = ["launch", "main", "mpi_command"]


def mpi_command(np_: int) -> list[str]:
    """``[mpiexec, -n, np_]`` of the mpich wheel next to this Python."""
    mpiexec = Path(sys.executable).parent / "mpiexec"
    if not mpiexec.exists():
        raise MissingFeatureError(
            f"mpiexec: expected the mpich wheel's mpiexec next to {sys.executable}, got none"
        )
    return [str(mpiexec), "-n", str(np_)]


def launch(out: Path, np_: int, restart: tuple[int, Path] | None) -> dict[str, Any]:
    """Run the folder's deck on ``np_`` ranks; return rank 0's counters.

    Raises
    ------
    RunError
        One line: the ranks' last error line, or the signal that ended them.
    """
    (out / "counters.json").unlink(missing_ok=True)
    cmd = mpi_command(np_) + [sys.executable, "-m", "tribolmp.lammps.mca", str(out)]
    if restart is not None:
        cmd += ["--restart", str(restart[1]), "--restart-step", str(restart[0])]
    env = {k: v for k, v in os.environ.items() if k != "LD_LIBRARY_PATH"}
    # own process group: an interrupt of the caller reaches mpiexec and the ranks, and a caller's
    # kill leaves no rank writing into the folder after the caller is gone
    proc = subprocess.Popen(
        cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env,
        start_new_session=True,
    )
    try:
        _stdout, stderr = proc.communicate()
    except BaseException:
        _kill_group(proc)
        raise
    if proc.returncode != 0 or not (out / "counters.json").exists():
        lines = [ln for ln in stderr.strip().splitlines() if ln.strip()]
        last = lines[-1] if lines else f"exit code {proc.returncode}"
        if proc.returncode == RestartUnreadableError.rank_exit_code:
            raise RestartUnreadableError(last)
        if proc.returncode < 0:
            last = f"ranks ended by signal {signal.Signals(-proc.returncode).name}"
        raise RunError(f"MCA run under mpiexec -n {np_} failed: {last}; last restart kept in {out}")
    return json.loads((out / "counters.json").read_text())


def _kill_group(proc: subprocess.Popen) -> None:
    try:
        os.killpg(proc.pid, signal.SIGTERM)
        proc.wait(timeout=10)
    except (ProcessLookupError, subprocess.TimeoutExpired):
        try:
            os.killpg(proc.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass


def main(argv: list[str] | None = None) -> int:
    """Entry point of every rank (see the module docstring)."""
    import argparse

    from .runner import run_lammps

    ap = argparse.ArgumentParser(prog="python -m tribolmp.lammps.mca")
    ap.add_argument("out")
    ap.add_argument("--restart")
    ap.add_argument("--restart-step", type=int)
    args = ap.parse_args(argv)
    out = Path(args.out).resolve()
    meta = json.loads((out / "meta.json").read_text())
    restart = (args.restart_step, Path(args.restart)) if args.restart else None
    try:
        counters = run_lammps(meta["deck_variables"], out, law=meta["law"], restart=restart)
    except RestartUnreadableError as exc:
        print(f"{exc}", file=sys.stderr)
        return RestartUnreadableError.rank_exit_code
    except RunError as exc:
        print(f"{exc}", file=sys.stderr)
        return 3
    if counters.pop("is_root"):
        atomic_write_json(out / "counters.json", counters)
    return 0
