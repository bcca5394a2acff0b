"""Real LAMMPS faults (issue 12 item 8) and the fault-injection must-hold of issue 12.

* a NaN produced by a real run, lost atoms: one stderr line naming step and cause, exit 3, and
  the folder recovers (the rerun without the fault discards the foreign folder and finishes);
* a 2-rank run with a rank killed: one line, exit 3; ``--resume`` finishes it, with the
  uninterrupted run's time grid and statistics;
* the default scene's nanoscale stage killed at three random points in sequence, then rerun:
  friction.csv, the dump and rates.json bit-identical to the uninterrupted run (slow).
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from tests.conftest import assert_one_line_error
from tests.mca.test_resume import _same_outputs

pytestmark = pytest.mark.lammps


def _table(out: Path) -> np.ndarray:
    return np.loadtxt(out / "friction.csv", delimiter=",", skiprows=1, ndmin=2)


@pytest.mark.parametrize(
    "fault, cause",
    [
        # F_N/approach_v overflows to inf; times the slider's initial vcm 0 gives a NaN load: a
        # real non-finite state inside LAMMPS ("Non-numeric atom coords")
        (("FN=1e300", "approach_v=1e-300"), "NaN"),
        # the slider pulled away from the bodies leaves the box
        (("FN=-2e4",), "lost atoms"),
    ],
    ids=["nan", "lost-atoms"],
)
def test_real_fault_is_one_line_exit_3_and_recoverable(
    fault, cause, cli, tmp_path, lammps_available
):
    out = tmp_path / "run"
    base = ("mca", "run", "--preset", "smoke", "--time", "0.3e-9", "--out", out)
    sets = [a for f in fault for a in ("--set", f)]
    res = cli(*base, *sets, timeout=300)
    assert_one_line_error(res, cause, "at step", code=3)
    # recoverable: the same folder, without the fault, resumes nothing foreign and finishes
    again = cli(*base, "--resume", "--json", timeout=300)
    assert again.returncode == 0, again.stderr
    assert again.json()["time_s"] == pytest.approx(0.3e-9, rel=1e-3)
    assert json.loads((out / "meta.json").read_text())["overrides"] == {}


def _rank_pids(out: Path) -> list[int]:
    """PIDs of the ranks running ``python -m tribolmp.lammps.mca OUT`` (this test's OUT only)."""
    pids = []
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            cmd = (entry / "cmdline").read_bytes().split(b"\0")
        except OSError:
            continue
        if b"tribolmp.lammps.mca" in cmd and str(out).encode() in cmd:
            pids.append(int(entry.name))
    return pids


@pytest.mark.mpi
@pytest.mark.slow
def test_two_ranks_killed_and_resumed(cli, tmp_path, lammps_available):
    args = ("mca", "run", "--preset", "smoke", "--time", "1e-9", "--seed", "5", "--np", "2")
    # the reference is the uninterrupted 2-rank run: every chunk of a run starts from its own
    # restart file, so a resumed run goes through the same read_restart calls and must give the
    # same bytes (a 1-rank run is another trajectory after ~0.4 ns: 1 vs 2 ranks is compared in
    # statistics by test_driver.py::test_two_ranks_give_statistically_the_same_mu)
    ref = tmp_path / "ref"
    done = cli(*args, "--out", ref, timeout=600)
    assert done.returncode == 0, done.stderr
    out = tmp_path / "np2"
    proc = subprocess.Popen(
        [sys.executable, "-m", "tribolmp", *args, "--out", str(out)],
        stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
    )
    t0 = time.monotonic()
    while proc.poll() is None and time.monotonic() - t0 < 300:
        if list(out.glob("restart.*.bin")):
            break
        time.sleep(0.1)
    ranks = _rank_pids(out)
    assert ranks, "no MPI rank found"
    os.kill(ranks[-1], signal.SIGKILL)  # one rank dies, as on a node failure
    _, stderr = proc.communicate(timeout=300)
    lines = [ln for ln in stderr.splitlines() if ln.strip()]
    assert proc.returncode == 3 and len(lines) == 1 and "mpiexec -n 2" in lines[0], stderr
    resumed = cli(*args, "--out", out, "--resume", "--json", timeout=600)
    assert resumed.returncode == 0, resumed.stderr
    # nothing lost, nothing twice, and the same numbers: friction.csv byte for byte
    assert (out / "friction.csv").read_bytes() == (ref / "friction.csv").read_bytes()


def _nanoscale_dir(run: Path, partial: bool) -> Path | None:
    pattern = "nanoscale-*.partial" if partial else "nanoscale-*[!l]"
    found = [p for p in (run / "cache").glob(pattern) if p.is_dir()]
    return found[0] / "mca" if found else None


@pytest.mark.slow
def test_default_scene_nanoscale_killed_three_times_is_bit_identical(tmp_path, lammps_available):
    rng = np.random.default_rng(12)  # explicit: which signal, and when
    env = {k: v for k, v in os.environ.items() if k != "LD_LIBRARY_PATH"}
    cmd = [sys.executable, "-m", "tribolmp", "run", "--out"]
    full = tmp_path / "full"
    t0 = time.monotonic()
    done = subprocess.run([*cmd, str(full)], capture_output=True, text=True, env=env, timeout=1800)
    assert done.returncode == 0, done.stderr[-2000:]
    t_full = time.monotonic() - t0
    part = tmp_path / "part"
    signals = []
    for _ in range(3):
        proc = subprocess.Popen([*cmd, str(part)], stdout=subprocess.DEVNULL,
                                stderr=subprocess.DEVNULL, env=env, start_new_session=True)
        t1 = time.monotonic()
        while proc.poll() is None and time.monotonic() - t1 < 600:
            mca = _nanoscale_dir(part, partial=True)
            if mca is not None and (mca / "friction.csv").exists():
                break
            time.sleep(0.05)
        # a random point of the stage (it takes most of the chain's time)
        time.sleep(float(rng.uniform(0.0, 0.6 * t_full)))
        sig = int(rng.choice([signal.SIGINT, signal.SIGTERM, signal.SIGKILL]))
        signals.append(sig)
        if proc.poll() is None:
            os.killpg(proc.pid, sig)
        proc.wait(timeout=300)
    last = subprocess.run([*cmd, str(part)], capture_output=True, text=True, env=env, timeout=1800)
    assert last.returncode == 0, last.stderr[-2000:]
    a, b = _nanoscale_dir(full, partial=False), _nanoscale_dir(part, partial=False)
    assert a is not None and b is not None
    _same_outputs(a, b)  # friction.csv, dump and rates.json byte for byte
