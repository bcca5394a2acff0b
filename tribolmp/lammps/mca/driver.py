"""``run_mca(params, out_dir, *, seed, resume=False, np=1)``: prepare, run or resume, finish."""

from __future__ import annotations

import dataclasses
import json
import os
import time
from pathlib import Path
from typing import Any

import numpy as np

from ...errors import ParameterError
from ...models.base import Result, check_int
from .faults import RestartUnreadableError
from .mpi import launch
from .params import MCAParams
from .prepare import prepare
from .rates import compute_rates
from .restart import (
    atomic_write_json,
    check_folder,
    discard_run_files,
    finalize_outputs,
    restart_files,
)
from .runner import run_lammps

__all__ = ["run_mca"]


def _expected(params: MCAParams, seed: int, overrides: dict[str, Any]) -> dict[str, Any]:
    # what meta.json must say for a folder to be resumed (a JSON round trip makes tuples lists)
    return json.loads(
        json.dumps(
            {
                "params": dataclasses.asdict(params),
                "seed": seed,
                "overrides": {k: str(v) for k, v in overrides.items()},
            }
        )
    )


def run_mca(
    params: MCAParams,
    out_dir: str | os.PathLike,
    *,
    seed: int,
    resume: bool = False,
    np: int = 1,
    overrides: dict[str, Any] | None = None,
    on_conflict: str = "refuse",
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
        Continue from the newest readable ``restart.<step>.bin`` in
        ``out_dir`` if the folder holds this very run (same parameters, seed
        and overrides in ``meta.json``); outputs after that step are dropped
        and re-run.  Idempotent: resuming a finished run only finishes it
        again.  A folder without work (no restart file, no finished
        ``rates.json``) simply starts over.
    np : int
        MPI ranks; ``np > 1`` runs ``mpiexec -n np python -m tribolmp.lammps.mca``.
    overrides : dict, optional
        Expert use (experiments, failure tests): deck variables (LAMMPS nano
        units) that replace the mapped values after validation.  Recorded in
        ``meta.json``.
    on_conflict : {"refuse", "overwrite", "archive"}
        When ``out_dir`` holds work this call would destroy (a run with other
        parameters, seed or overrides, or any earlier run when ``resume`` is
        false): raise :class:`~tribolmp.errors.SetupError` naming the fields
        that differ (default), discard it, or move it into
        ``out_dir/superseded/<n>/`` (the chain's stage folders).

    Returns
    -------
    Result
        ``out_dir``, ``mu``, ``mu_err``, ``layer_depth_m``, ``diffusion_m2_s``,
        ``transfer_rate`` (from ``rates.json``; ``mu`` from ``friction.csv``
        over the second half when the rates were not computed),
        ``atom_steps_per_s``, ``time_s`` (simulated), ``wall_time_s``,
        ``natoms``, ``nprocs``, ``rates_path``, ``resumed_from_step``,
        ``discarded_restarts``, ``superseded_run`` (where another run's work
        was moved, or None).
    """
    if not isinstance(params, MCAParams):
        raise ParameterError("params", "an MCAParams instance", type(params).__name__)
    np_ = check_int("np", np, 1, 64)
    seed = check_int("seed", seed, 0, 2**63 - 1)
    overrides = dict(overrides or {})
    out = Path(out_dir).resolve()
    t0 = time.perf_counter()
    meta, superseded = check_folder(
        out, _expected(params, seed, overrides), resume=resume, on_conflict=on_conflict
    )
    discarded: list[str] = []
    while True:
        restarts = restart_files(out) if meta is not None else []
        if meta is None or not restarts:
            discard_run_files(out) if out.is_dir() else None
            variables = prepare(params, out, seed, overrides)
            meta = json.loads((out / "meta.json").read_text())
            restart = None
        else:
            variables = meta["deck_variables"]
            restart = restarts[-1]
        try:
            if np_ == 1:
                counters = run_lammps(variables, out, law=params.bond_style, restart=restart)
            else:
                counters = launch(out, np_, restart)
            break
        except RestartUnreadableError:
            # a restart file LAMMPS cannot read (cut by a kill before restart files were written
            # atomically, or foreign): drop it and resume from the previous one, or start over
            assert restart is not None
            discarded.append(restart[1].name)
            restart[1].unlink(missing_ok=True)
    finalize_outputs(out, int(variables["dump_every"]))
    res = _finish(out, counters, t0, discarded)
    res["superseded_run"] = str(superseded) if superseded else None
    return res


def _finish(out: Path, counters: dict[str, Any], t0: float, discarded: list[str]) -> Result:
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
            "resumed_from_step": counters["start_step"],
        }
    )
    atomic_write_json(out / "meta.json", meta)
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
    res["resumed_from_step"] = counters["start_step"]
    res["discarded_restarts"] = discarded
    fr = np.loadtxt(out / "friction.csv", delimiter=",", skiprows=1, ndmin=2)
    half = fr[fr[:, 0] >= 0.5 * fr[-1, 0]]
    res["mu_raw"] = (
        float(half[:, 1].mean() / half[:, 2].mean()) if half[:, 2].mean() > 0 else float("nan")
    )
    rates = compute_rates(out)
    # None: the rates were skipped (the driver tests replace compute_rates to test the
    # simulation side alone).
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
            message="run finished; rates not computed, mu from friction.csv",
        )
    return res
