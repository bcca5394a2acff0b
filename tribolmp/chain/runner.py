"""Run a planned scene stage by stage, through the cache, and write the report.

Fault model:

* every finished stage is committed to the cache atomically before the next
  one starts, and ``report.json`` is rewritten (atomically) after each stage,
  so a Ctrl-C or a kill loses at most the stage that was running;
* rerunning the same scene reuses committed stages (their inputs hash to the
  same key) and resumes the interrupted one from its ``.partial`` folder
  (LAMMPS restart files);
* a stage that raises is recorded as failed with a one-line reason, stages
  that do not depend on it still run, the report is written, and only then
  the failure is raised (:class:`~tribolmp.errors.StageError`, exit 3; or a
  :class:`~tribolmp.errors.SetupError`, exit 2, when the cause was bad input).
"""

from __future__ import annotations

import sys
import time
import uuid
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import SetupError, StageError
from ..locking import DirLock, prepare_dir
from ..scene import Scene
from .cache import CachedStage, StageCache, hash_inputs
from .planner import Plan, plan_scene
from .registry import Registry
from .stage import StageContext, code_hash, stage_seed

__all__ = ["run_chain", "ChainRun", "StageEntry", "Progress", "stage_seed"]


@dataclass
class StageEntry:
    """What happened to one stage in this run (the report's ``stages`` row plus details)."""

    name: str
    ran: bool
    reason: str
    time_s: float = 0.0
    status: str = "skipped"  # skipped | computed | cached | failed | interrupted
    key: str | None = None
    cached: CachedStage | None = None
    error: BaseException | None = None

    def row(self) -> dict[str, Any]:
        """Return the contract row ``{"name", "ran", "reason", "time_s"}``."""
        return {
            "name": self.name,
            "ran": self.ran,
            "reason": self.reason,
            "time_s": round(self.time_s, 6),
        }


@dataclass
class ChainRun:
    """Everything the report needs: scene, plan, per-stage entries, paths."""

    scene: Scene
    plan: Plan
    out_dir: Path
    entries: dict[str, StageEntry] = field(default_factory=dict)
    started: float = field(default_factory=time.time)
    wall_time_s: float = 0.0
    complete: bool = False

    def result(self, name: str) -> CachedStage | None:
        """Return the committed result of stage ``name`` (None if it did not run)."""
        e = self.entries.get(name)
        return e.cached if e is not None and e.ran else None

    @property
    def failed(self) -> list[StageEntry]:
        """Entries of failed stages."""
        return [e for e in self.entries.values() if e.status == "failed"]


class Progress:
    """Plain-text progress bars on stderr (one line per event; safe in logs and CI).

    Parameters
    ----------
    total : int
        Number of stages that will be computed.
    stream : file, optional
        Where to write (default stderr); ``None`` disables output when ``quiet``.
    quiet : bool
        Print nothing.
    """

    width = 24

    def __init__(self, total: int, stream=None, quiet: bool = False):
        self.total = max(total, 1)
        self.done = 0
        self.stream = stream or sys.stderr
        self.quiet = quiet
        self._t0 = time.perf_counter()
        self._last = -1.0

    def _bar(self, frac: float) -> str:
        n = int(round(frac * self.width))
        return "[" + "#" * n + "." * (self.width - n) + f"] {100 * frac:5.1f}%"

    def _print(self, text: str) -> None:
        if not self.quiet:
            print(text, file=self.stream, flush=True)

    def start(self, name: str, what: str) -> None:
        """Announce a stage."""
        self._print(f"{self._bar(self.done / self.total)} {name}: {what}")
        self._last = -1.0

    def update(self, name: str, frac: float, what: str = "") -> None:
        """Within-stage progress ``frac`` in [0, 1] (printed in 10 % steps)."""
        frac = min(max(float(frac), 0.0), 1.0)
        if frac - self._last < 0.1 and frac < 1.0:
            return
        self._last = frac
        overall = (self.done + frac) / self.total
        self._print(f"{self._bar(overall)} {name}: {100 * frac:3.0f}% {what}".rstrip())

    def finish(self, name: str, status: str, seconds: float) -> None:
        """Close a stage."""
        self.done += 1
        self._print(
            f"{self._bar(self.done / self.total)} {name}: {status} "
            f"({seconds:.1f} s; total {time.perf_counter() - self._t0:.1f} s)"
        )


def _one_line(exc: BaseException) -> str:
    text = " ".join(str(exc).split()) or type(exc).__name__
    return (
        text
        if isinstance(exc, (SetupError, StageError)) or ":" in text[:40]
        else f"{type(exc).__name__}: {text}"
    )


def preflight(scene: Scene, plan: Plan) -> list[str]:
    """Every running stage's :meth:`~tribolmp.chain.stage.Stage.preflight` (refusals raise).

    Returns
    -------
    list of str
        ``"stage: note"`` lines (cost estimates, warnings).
    """
    notes: list[str] = []
    for sp in plan.stages:
        if sp.run:
            notes += [f"{sp.name}: {n}" for n in plan.registry[sp.name].preflight(scene, sp)]
    return notes


def run_chain(
    scene: Scene,
    out_dir: str | Path,
    *,
    force: Iterable[str] | bool = (),
    cache_dir: str | Path | None = None,
    progress: Progress | None = None,
    quiet: bool = False,
    figures: bool | None = None,
    on_stage: Callable[[ChainRun], None] | None = None,
    registry: Registry | None = None,
) -> ChainRun:
    """Run ``scene`` through the multiscale chain into ``out_dir``.

    Parameters
    ----------
    scene : Scene
        A validated scene.
    out_dir : str or Path
        Output folder (``report.json``, ``report.md``, ``figures/``, ``cache/``).
    force : iterable of str or bool
        Stages to recompute even when cached; ``True`` means all.
    cache_dir : str or Path, optional
        Cache folder (default ``out_dir/cache``); share it between runs to reuse LAMMPS results.
    progress : Progress, optional
        Progress printer (default: bars on stderr unless ``quiet``).
    quiet : bool
        No progress output.
    figures : bool, optional
        Draw PNG figures (default ``[outputs].figures``).
    on_stage : callable, optional
        Called with the :class:`ChainRun` after each stage (tests use it to interrupt).
    registry : Registry, optional
        The stages (default: :data:`~tribolmp.chain.registry.REGISTRY`).

    Returns
    -------
    ChainRun

    Raises
    ------
    StageError
        After the report is written, when a stage failed at run time (one line naming it).
    SetupError
        After the report is written, when a stage rejected its inputs.
    """
    out = prepare_dir(out_dir, "--out")
    if cache_dir is not None:
        prepare_dir(cache_dir, "--cache-dir")
    # One run per output folder: a second one would interleave report.json and the LAMMPS
    # outputs of the first.  The flock dies with its holder, so a killed run never blocks.
    with DirLock(out, what="output folder"):
        return _run_chain_locked(
            scene,
            out,
            force=force,
            cache_dir=cache_dir,
            progress=progress,
            quiet=quiet,
            figures=figures,
            on_stage=on_stage,
            registry=registry,
        )


def _run_chain_locked(
    scene, out, *, force, cache_dir, progress, quiet, figures, on_stage, registry
) -> ChainRun:
    from . import report as _report

    plan = plan_scene(scene, registry=registry)
    notes = preflight(scene, plan)
    names = plan.registry.names
    forced = set(names) if force is True else set(force or ())
    unknown = forced - set(names)
    if unknown:
        raise SetupError(f"--force: expected stage names from {list(names)}, got {sorted(unknown)}")
    cache = StageCache(cache_dir if cache_dir is not None else out / "cache")
    run = ChainRun(scene, plan, out)
    prog = progress or Progress(len(plan.running), quiet=quiet)
    for line in notes:
        prog._print(f"note: {line}")
    scene_dict = scene.to_dict()
    t_start = time.perf_counter()

    for sp in plan.stages:
        if not sp.run:
            run.entries[sp.name] = StageEntry(sp.name, False, sp.reason)
            continue
        missing = [n for n in sp.needs if run.result(n) is None]
        if missing:
            why = "; ".join(f"{n}: {run.entries[n].reason}" for n in missing)
            run.entries[sp.name] = StageEntry(
                sp.name,
                False,
                f"skipped: upstream stage {', '.join(missing)} has no result ({why})",
            )
            prog.finish(sp.name, "skipped", 0.0)
            continue
        seed = stage_seed(scene.scene.seed, sp.name)
        inputs = {
            "sections": {s: scene_dict.get(s) for s in sp.sections},
            "options": sp.options,
            # The identity of an upstream *result* (not only of its inputs): a forced or otherwise
            # recomputed upstream stage invalidates everything downstream of it.
            "upstream": {
                n: f"{run.result(n).key}:{run.result(n).record.get('output_id', '')}"
                for n in sp.needs
            },
            "seed": seed,
            "code": code_hash(plan.registry[sp.name]),
        }
        key = cache.key(sp.name, inputs)
        if sp.name in forced:
            cache.discard(sp.name, key)
        hit = cache.lookup(sp.name, key)
        entry_lock = None
        if hit is None:
            # Runs sharing a --cache-dir compute an entry once: wait for whoever holds it,
            # then look again (it may have been committed meanwhile).
            entry_lock = cache.entry_lock(sp.name, key, quiet=quiet).acquire()
            hit = cache.lookup(sp.name, key)
        if hit is not None:
            if entry_lock is not None:
                entry_lock.release()
            run.entries[sp.name] = StageEntry(
                sp.name, True, f"{sp.reason} (reused from cache {key})", 0.0, "cached", key, hit
            )
            prog.finish(sp.name, f"cached ({key})", 0.0)
            _report.write_json(run, partial=True)
            continue

        prog.start(sp.name, sp.reason)
        work = cache.workdir(sp.name, key)
        ctx = StageContext(
            scene=scene,
            plan=sp,
            workdir=work,
            upstream={n: run.result(n) for n in sp.needs},
            rng=np.random.default_rng(np.random.SeedSequence(seed)),
            seed=seed,
            progress=lambda frac, what="", _n=sp.name: prog.update(_n, frac, what),
        )
        t0 = time.perf_counter()
        try:
            output = plan.registry[sp.name].run(ctx)
        except KeyboardInterrupt as exc:
            entry_lock.release()
            dt = time.perf_counter() - t0
            run.entries[sp.name] = StageEntry(
                sp.name,
                False,
                "interrupted; partial work kept for resume",
                dt,
                "interrupted",
                key,
                error=exc,
            )
            run.wall_time_s = time.perf_counter() - t_start
            _report.write_json(run, partial=True)
            raise
        except Exception as exc:  # noqa: BLE001 - any failure is recorded and the chain goes on
            dt = time.perf_counter() - t0
            run.entries[sp.name] = StageEntry(
                sp.name, False, f"failed: {_one_line(exc)}", dt, "failed", key, error=exc
            )
            prog.finish(sp.name, "FAILED", dt)
        else:
            dt = time.perf_counter() - t0
            record = {
                # None marks "not applicable" inside a stage: leave such keys out of the record.
                "values": {k: v for k, v in output.values.items() if v is not None},
                "units": output.units,
                "files": output.files,
                "method": output.method,
                "message": output.message,
                "nit": output.nit,
                "time_s": dt,
                "seed": seed,
                "inputs": inputs,
                "inputs_hash": hash_inputs(inputs),
                "provenance": output.provenance,
                "created_utc": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
                "output_id": uuid.uuid4().hex,
            }
            committed = cache.commit(sp.name, key, record)
            run.entries[sp.name] = StageEntry(
                sp.name, True, sp.reason, dt, "computed", key, committed
            )
            prog.finish(sp.name, "done", dt)
        entry_lock.release()
        run.wall_time_s = time.perf_counter() - t_start
        _report.write_json(run, partial=True)
        if on_stage is not None:
            on_stage(run)

    run.wall_time_s = time.perf_counter() - t_start
    run.complete = True
    draw = scene.outputs.figures if figures is None else figures
    _report.write_report(run, figures=draw)
    failed = run.failed
    if failed:
        first = failed[0]
        if isinstance(first.error, SetupError):
            raise SetupError(
                f"stage '{first.name}' failed: {_one_line(first.error)}"
            ) from first.error
        raise StageError(first.name, _one_line(first.error)) from first.error
    return run
