"""Resume exact and idempotent (issue 12 item 1): interrupts at any point, repeated, then a rerun.

One rank: friction.csv, the dump and rates.json are bit-identical to the uninterrupted run with
the same seed (rates.json holds no wall time and no creation time; it names its folder, so the
compared runs use folders of the same name).  Restarts are written at chunk
ends (whole averaging windows), atomically; on resume the outputs are cut back to the restart step,
dropping the '#' header that LAMMPS's fix print writes whenever it re-opens its file.
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

from tribolmp.lammps.mca.restart import finalize_outputs, truncate_outputs

FRAME = (
    "ITEM: TIMESTEP\n{step}\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS pp ff pp\n0 1\n0 1\n0 1\n"
    "ITEM: ATOMS id mol type x y z vx vy vz radius c_nbond\n"
    "1 2 1 0.1 0.2 0 0 0 0 1.1 3\n2 2 1 0.5 0.2 0 0 0 0 1.1 3\n"
)


def test_outputs_cut_back_past_headers_and_cut_lines(tmp_path):
    # what a resumed-then-killed folder holds: fix print's '#' header of the resumed segment, a
    # duplicated restart row, a row and a dump frame cut by SIGKILL (the old code read the header
    # as a number and failed: "could not convert string to float")
    csv = tmp_path / "friction.csv"
    csv.write_text(
        "time_s,friction_N,normal_N,top_x_m\n1e-12,1,2,3\n2e-12,1,2,3\n"
        "# Fix print output for fix csv\n2e-12,9,9,9\n3e-12,1,2,3\n4e-12,1,2"
    )
    traj = tmp_path / "traj.lammpstrj"
    traj.write_text(FRAME.format(step=0) + FRAME.format(step=100) + FRAME.format(step=150)
                    + FRAME.format(step=200) + FRAME.format(step=300)[:-30])
    truncate_outputs(tmp_path, 2, 1e-12)
    assert csv.read_text() == "time_s,friction_N,normal_N,top_x_m\n1e-12,1,2,3\n2e-12,1,2,3\n"
    assert traj.read_text() == FRAME.format(step=0)  # frames after step 2 dropped
    csv.write_text(csv.read_text() + "# Fix print output for fix csv\n2e-12,9,9,9\n3e-12,1,2,3\n")
    traj.write_text(FRAME.format(step=0) + FRAME.format(step=100) + FRAME.format(step=150)
                    + FRAME.format(step=100))
    finalize_outputs(tmp_path, dump_every=100)
    # first copy of each row kept, header gone; frames off the dump interval (a re-opened dump's
    # first frame) and repeated frames dropped
    assert csv.read_text().splitlines()[1:] == ["1e-12,1,2,3", "2e-12,1,2,3", "3e-12,1,2,3"]
    assert traj.read_text() == FRAME.format(step=0) + FRAME.format(step=100)


def _cli(*args: str) -> list[str]:
    return [sys.executable, "-m", "tribolmp", *args]


def _stamp(path: Path) -> tuple[int, int] | None:
    try:
        st = path.stat()
    except OSError:
        return None
    return st.st_mtime_ns, st.st_size


def _interrupt(cmd: list[str], out: Path, sig: int, delay: float, *, wait_for: str) -> int:
    """Start ``cmd`` and send ``sig`` to its process group ``delay`` s after LAMMPS writes.

    "LAMMPS writes": ``out/wait_for`` exists and friction.csv changed since the start.
    """
    before = _stamp(out / "friction.csv")
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                            start_new_session=True)
    t0 = time.monotonic()
    while proc.poll() is None and time.monotonic() - t0 < 240:
        if list(out.glob(wait_for)) and _stamp(out / "friction.csv") not in (None, before):
            break
        time.sleep(0.02)
    time.sleep(delay)
    if proc.poll() is None:
        os.killpg(proc.pid, sig)
    proc.wait(timeout=120)
    return proc.returncode


def _same_outputs(a: Path, b: Path) -> None:
    assert (a / "friction.csv").read_bytes() == (b / "friction.csv").read_bytes()
    assert (a / "traj.lammpstrj").read_bytes() == (b / "traj.lammpstrj").read_bytes()
    # rates.json holds measurements only (no wall time, no creation time): byte for byte too
    assert (a / "rates.json").read_bytes() == (b / "rates.json").read_bytes()


@pytest.mark.lammps
def test_mca_run_resumed_twice_is_bit_identical(tmp_path, lammps_available):
    rng = np.random.default_rng(20261201)  # explicit: which signals and when
    args = ["mca", "run", "--preset", "smoke", "--time", "0.8e-9", "--seed", "4", "--json"]
    full = tmp_path / "full" / "run"  # same folder name: rates.json records it
    done = subprocess.run(_cli(*args, "--out", str(full)), capture_output=True, text=True,
                          timeout=300)
    assert done.returncode == 0, done.stderr
    part = tmp_path / "part" / "run"
    first = _cli(*args, "--out", str(part))
    resume = _cli(*args, "--out", str(part), "--resume")
    # interrupt 1: any time after LAMMPS started writing; interrupt 2: during the resumed run
    _interrupt(first, part, int(rng.choice([signal.SIGINT, signal.SIGKILL])),
               float(rng.uniform(0.5, 2.0)), wait_for="restart.*.bin")
    _interrupt(resume, part, signal.SIGTERM, float(rng.uniform(0.2, 1.5)), wait_for="restart.*.bin")
    again = subprocess.run(resume, capture_output=True, text=True, timeout=300)
    assert again.returncode == 0, again.stderr
    assert json.loads(again.stdout)["time_s"] == pytest.approx(0.8e-9, rel=1e-3)
    _same_outputs(full, part)
    # and resuming a finished run changes nothing
    third = subprocess.run(resume, capture_output=True, text=True, timeout=300)
    assert third.returncode == 0, third.stderr
    _same_outputs(full, part)
