"""Parallel efficiency of the sweep engine: N tasks of length T on k workers of a LocalCluster.

    python benchmarks/sweep_parallel_efficiency.py [--quick] [--tasks N] [--seconds T]
        [--workers 1,2] [--kinds sleep,cpu]

Two kinds of task, through the same Dask engine as ``tribolmp sweep``
(:func:`tribolmp.campaign.make_client`: worker processes on 127.0.0.1):

* ``sleep``: a task that waits T s.  It costs no CPU, so it measures what the
  engine itself adds (start-up, scheduling, result transfer) independently
  of how busy the machine is;
* ``cpu``: a task that does a fixed amount of numpy work (about T s on an idle
  core).  It measures the real speed-up on this machine; on a shared machine
  its efficiency is bounded by the free cores.

Efficiency E = (N x T_task) / (k x T), T_task the mean of the tasks' own
measured durations: ``efficiency_run`` with T the time from submission to the
last result (cluster up), ``efficiency_total`` with T including the cluster's
start-up and shutdown (what a short sweep pays once).
Writes ``benchmarks/results/sweep_parallel_efficiency[_quick].csv``.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from tribolmp.benchmarking import print_table, write_csv  # noqa: E402
from tribolmp.campaign import make_client  # noqa: E402

RESULTS = Path(__file__).resolve().parent / "results"


def _sleep_task(seconds: float) -> float:
    t0 = time.perf_counter()
    time.sleep(seconds)
    return time.perf_counter() - t0


def _calibrate(seconds: float) -> int:
    """Count the 256x256 matrix products that take ``seconds`` on one core (measured here)."""
    import numpy as np

    a = np.random.default_rng(0).normal(size=(256, 256))
    t0, n = time.perf_counter(), 0
    while time.perf_counter() - t0 < 0.5:
        a = np.tanh(a @ a * 1e-2)
        n += 1
    return max(1, int(n * seconds / (time.perf_counter() - t0)))


def _cpu_task(reps: int) -> float:
    import numpy as np

    t0 = time.perf_counter()
    a = np.random.default_rng(1).normal(size=(256, 256))
    for _ in range(reps):
        a = np.tanh(a @ a * 1e-2)
    return time.perf_counter() - t0


def run(kind: str, n_tasks: int, seconds: float, workers: int, reps: int) -> dict:
    """One measurement."""
    t0 = time.perf_counter()
    client, cluster = make_client(workers)
    try:
        client.wait_for_workers(workers)
        t1 = time.perf_counter()
        fn, arg = (_sleep_task, seconds) if kind == "sleep" else (_cpu_task, reps)
        futs = [client.submit(fn, arg, pure=False, key=f"{kind}-{i}") for i in range(n_tasks)]
        durations = client.gather(futs)
        t2 = time.perf_counter()
    finally:
        client.close()
        cluster.close()
    wall = time.perf_counter() - t0
    t_task = sum(durations) / len(durations)
    work = n_tasks * t_task
    return {
        "kind": kind,
        "tasks": n_tasks,
        "workers": workers,
        "task_s": round(t_task, 3),
        "startup_s": round(t1 - t0, 3),
        "run_s": round(t2 - t1, 3),
        "wall_s": round(wall, 3),
        "ideal_run_s": round(work / workers, 3),
        # E_run: scheduling only (cluster up); E_total: also cluster start-up and shutdown.
        "efficiency_run": round(work / (workers * (t2 - t1)), 4),
        "efficiency_total": round(work / (workers * wall), 4),
        "cpus": os.cpu_count(),
        "load_1min": round(os.getloadavg()[0], 2),
    }


def main(argv=None) -> int:
    """Run the grid and write the CSV."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument(
        "--quick",
        action="store_true",
        help="2 s tasks (a smoke run; the goal is stated for >= 10 s tasks)",
    )
    ap.add_argument("--tasks", type=int, default=8)
    ap.add_argument("--seconds", type=float, default=10.0)
    ap.add_argument("--workers", default="1,2")
    ap.add_argument("--kinds", default="sleep,cpu")
    args = ap.parse_args(argv)
    seconds = 2.0 if args.quick else args.seconds
    reps = _calibrate(seconds) if "cpu" in args.kinds else 0
    rows = [
        run(kind, args.tasks, seconds, int(k), reps)
        for kind in args.kinds.split(",")
        for k in args.workers.split(",")
    ]
    print_table(
        f"sweep engine: {args.tasks} tasks of ~{seconds:g} s (goal E >= 0.9 for tasks >= 10 s)",
        rows,
    )
    name = "sweep_parallel_efficiency_quick.csv" if args.quick else "sweep_parallel_efficiency.csv"
    print(f"wrote {write_csv(RESULTS / name, rows)}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
