"""Parameter campaigns on dask.distributed: ``tribolmp sweep``.

Each point of the product of the ``--vary`` lists (times ``--seeds``) is one
Dask task that runs the scene through the chain's public entry point
(:func:`tribolmp.chain.run_chain`, what ``tribolmp run`` calls) into
``OUT/points/<id>/``, with ONE stage cache shared by all points
(``OUT/cache`` or ``--cache-dir``).  So:

* a killed sweep resumes: finished points are read back from their
  ``point.json``; stages of the interrupted points that were committed are
  reused from the cache;
* two sweeps (or two points) that share a stage's inputs compute it once,
  because the cache key is the hash of the stage's inputs;
* a failing point is recorded as one line (``status: "failed"``) and the
  other points go on.

The default engine is a ``LocalCluster`` of worker processes bound to
127.0.0.1 (no dashboard, no network); ``scheduler=ADDRESS`` connects to any
running Dask cluster instead (e.g. one started by dask-jobqueue on SLURM or
PBS: see docs/sweep.md).

Outputs: ``OUT/sweep.csv`` and ``OUT/sweep.json`` (one row per point with
every scalar the chain reported, ``stage.key``, and the errors the stages
give, plus the mean and standard error over seeds), and figures in
``OUT/figures/`` (mu against pressure per velocity with error bars, and any
scalar as a colour map over the first two varied fields).
"""

from __future__ import annotations

import copy
import csv
import hashlib
import json
import math
import sys
import time
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from itertools import product
from pathlib import Path
from typing import Any

from .errors import ParameterError, SetupError
from .jsonio import atomic_write_json, atomic_write_text, canonical_json

__all__ = [
    "Vary",
    "parse_vary",
    "expand_points",
    "point_id",
    "run_point",
    "run_sweep",
    "SweepResult",
    "flatten_values",
]

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib


@dataclass(frozen=True)
class Vary:
    """One ``--vary section.field=v1,v2,...`` axis."""

    section: str
    field: str
    values: tuple[Any, ...]

    @property
    def key(self) -> str:
        """``section.field``."""
        return f"{self.section}.{self.field}"


def _literal(token: str) -> Any:
    # A TOML literal (number, bool, quoted string, array); a bare word is a
    # string (e.g. a law name).
    tok = token.strip()
    try:
        return tomllib.loads(f"v = {tok}")["v"]
    except tomllib.TOMLDecodeError:
        return tok


def parse_vary(text: str) -> Vary:
    """Parse ``section.field=v1,v2,...`` (values as TOML literals; bare words are strings).

    Raises
    ------
    ParameterError
        One line naming ``--vary`` and the expected form.
    """
    if "=" not in text or "." not in text.split("=", 1)[0]:
        raise ParameterError(
            "--vary", "section.field=v1,v2,... (e.g. nanoscale.pressure=50e6,150e6)", text
        )
    name, vals = text.split("=", 1)
    section, _, fld = name.strip().partition(".")
    if not section or not fld or "." in fld:
        raise ParameterError("--vary", "section.field=v1,v2,... with one dot in the name", text)
    values = tuple(_literal(v) for v in vals.split(",") if v.strip())
    if not values:
        raise ParameterError("--vary", f"at least one value for {name.strip()}", text)
    return Vary(section, fld, values)


def point_id(vary: Mapping[str, Any], seed: int) -> str:
    """Stable short id of a point (folder name): hash of its varied values and seed."""
    return hashlib.sha256(
        canonical_json({"vary": dict(vary), "seed": int(seed)}).encode()
    ).hexdigest()[:12]


def expand_points(
    base: Mapping[str, Any], axes: Sequence[Vary], seeds: int
) -> list[dict[str, Any]]:
    """All points ``{"vary": {key: value}, "seed": int, "id": str}`` of the product.

    Seeds innermost.

    Seeds are ``[scene].seed + i`` for ``i < seeds`` (the scene's master seed when ``seeds == 1``).
    """
    if isinstance(seeds, bool) or not isinstance(seeds, int) or seeds < 1:
        raise ParameterError("--seeds", "an integer >= 1", seeds)
    keys = [a.key for a in axes]
    if len(set(keys)) != len(keys):
        raise ParameterError("--vary", "each section.field at most once", ", ".join(keys))
    master = int(base.get("scene", {}).get("seed", _default_seed()))
    points = []
    for combo in product(*[a.values for a in axes]) if axes else [()]:
        vary = dict(zip(keys, combo))
        for i in range(seeds):
            seed = master + i
            points.append({"vary": vary, "seed": seed, "id": point_id(vary, seed)})
    return points


def _default_seed() -> int:
    from .scene.schema import SceneMeta

    return int(SceneMeta().seed)


def point_scene_dict(base: Mapping[str, Any], vary: Mapping[str, Any], seed: int) -> dict[str, Any]:
    """Return the scene mapping of one point: ``base`` with its varied fields and seed set."""
    d = copy.deepcopy(dict(base))
    for key, value in vary.items():
        section, fld = key.split(".", 1)
        d.setdefault(section, {})
        if not isinstance(d[section], dict):
            raise ParameterError(
                f"--vary {key}", f"[{section}] to be a table", type(d[section]).__name__
            )
        d[section][fld] = value
    d.setdefault("scene", {})["seed"] = int(seed)
    return d


def flatten_values(report: Mapping[str, Any]) -> tuple[dict[str, Any], dict[str, str]]:
    """Scalar results of a ``report.json`` as ``{"stage.key": value}`` and their units.

    Lists and nested tables are left out (they stay in each point's report.json).
    """
    values: dict[str, Any] = {}
    units: dict[str, str] = {}
    for stage, res in (report.get("results") or {}).items():
        for k, v in (res.get("values") or {}).items():
            if v is None or isinstance(v, (bool, int, float, str)):
                values[f"{stage}.{k}"] = v
                u = (res.get("units") or {}).get(k)
                if u is not None:
                    units[f"{stage}.{k}"] = u
    return values, units


def _one_line(exc: BaseException) -> str:
    text = " ".join(str(exc).split()) or type(exc).__name__
    return text if ":" in text[:60] else f"{type(exc).__name__}: {text}"


def run_point(
    base: Mapping[str, Any],
    source: str,
    vary: Mapping[str, Any],
    seed: int,
    out_dir: str,
    cache_dir: str,
    figures: bool = False,
) -> dict[str, Any]:
    """Run one point through the chain (a Dask task; also callable directly).

    Returns ``{"vary", "seed", "id", "status": "ok"|"failed", "values", "units", "message",
    "time_s", "report"}``; never raises for a failing point (the failure is the one-line
    ``message``).
    """
    from .chain import run_chain
    from .scene import parse_scene

    pid = point_id(vary, seed)
    out = Path(out_dir)
    t0 = time.perf_counter()
    row: dict[str, Any] = {
        "vary": dict(vary),
        "seed": int(seed),
        "id": pid,
        "status": "failed",
        "values": {},
        "units": {},
        "message": "",
        "time_s": 0.0,
        "report": str(out / "report.json"),
    }
    try:
        scene = parse_scene(point_scene_dict(base, vary, seed), source=source)
        try:
            kwargs = dict(
                cache_dir=cache_dir, quiet=True, figures=figures, on_stage=_stage_event(pid)
            )
            run_chain(scene, out, **kwargs)
        except (
            TypeError
        ) as exc:  # a chain entry point without on_stage: run without per-stage events
            if "on_stage" not in str(exc):
                raise
            run_chain(scene, out, cache_dir=cache_dir, quiet=True, figures=figures)
        report = json.loads((out / "report.json").read_text())
        row["values"], row["units"] = flatten_values(report)
        row["status"] = "ok"
        ran = [s["name"] for s in report.get("stages", []) if s.get("ran")]
        row["message"] = f"{len(ran)} stage(s): {', '.join(ran)}"
    except KeyboardInterrupt:
        raise
    except BaseException as exc:  # noqa: BLE001 - one line per failing point; the sweep goes on
        row["message"] = _one_line(exc)
        rep = out / "report.json"
        if rep.exists():  # stages that finished before the failure still report their values
            try:
                row["values"], row["units"] = flatten_values(json.loads(rep.read_text()))
            except (OSError, ValueError):
                pass
    row["time_s"] = time.perf_counter() - t0
    out.mkdir(parents=True, exist_ok=True)
    atomic_write_json(out / "point.json", row)
    return row


def _stage_event(pid: str) -> Callable[[Any], None] | None:
    """Per-stage progress from inside a Dask worker, as a worker event the client prints."""
    try:
        from distributed import get_worker

        worker = get_worker()
    except (ImportError, ValueError):
        return None

    def _event(chain_run) -> None:
        entries = getattr(chain_run, "entries", {})
        done = [n for n, e in entries.items() if getattr(e, "ran", False)]
        plan = getattr(chain_run, "plan", None)
        total = len(getattr(plan, "running", []) or []) or max(len(done), 1)
        last = done[-1] if done else ""
        worker.log_event(
            "tribolmp-sweep", {"id": pid, "stage": last, "done": len(done), "total": total}
        )

    return _event


@dataclass
class SweepResult:
    """Outcome of a sweep: one row per point, the table paths, workers and wall time."""

    points: list[dict[str, Any]]
    table_csv: Path
    table_json: Path
    workers: int
    wall_time_s: float
    figures: dict[str, str] = field(default_factory=dict)
    resumed: int = 0

    def to_json_dict(self) -> dict[str, Any]:
        """Return the ``tribolmp sweep --json`` contract."""
        return {
            "points": [
                {k: p[k] for k in ("vary", "seed", "status", "values", "message")}
                | {"id": p["id"], "units": p.get("units", {})}
                for p in self.points
            ],
            "table": str(self.table_csv),
            "table_json": str(self.table_json),
            "workers": self.workers,
            "wall_time_s": self.wall_time_s,
            "figures": self.figures,
            "resumed": self.resumed,
        }


class _Bar:
    width = 24

    def __init__(self, total: int, stream, quiet: bool):
        self.total, self.done, self.stream, self.quiet = max(total, 1), 0, stream, quiet
        self.t0 = time.perf_counter()

    def line(self, text: str) -> None:
        if not self.quiet:
            frac = self.done / self.total
            n = int(round(frac * self.width))
            bar = "[" + "#" * n + "." * (self.width - n) + f"] {self.done}/{self.total}"
            print(
                f"{bar} {text} ({time.perf_counter() - self.t0:.1f} s)",
                file=self.stream,
                flush=True,
            )


def _label(vary: Mapping[str, Any], seed: int) -> str:
    return " ".join(f"{k}={v}" for k, v in vary.items()) + f" seed={seed}"


def run_sweep(
    scene_path: str | Path,
    axes: Sequence[Vary],
    *,
    seeds: int = 1,
    out: str | Path = "tribolmp-sweep",
    workers: int = 2,
    scheduler: str | None = None,
    cache_dir: str | Path | None = None,
    resources: Mapping[str, float] | None = None,
    figures: bool = True,
    map_keys: Iterable[str] = (),
    quiet: bool = False,
    stream=None,
) -> SweepResult:
    """Run every point of the campaign on Dask and write the table and figures.

    Parameters
    ----------
    scene_path : str or Path
        The base scene (TOML).
    axes : sequence of Vary
        The varied fields; the points are their product, times ``seeds``.
    seeds : int
        Seeds per point: ``[scene].seed + i``.
    out : str or Path
        Output folder (``points/``, ``cache/``, ``sweep.csv``, ``sweep.json``, ``figures/``).
    workers : int
        Worker processes of the embedded LocalCluster (ignored with ``scheduler``).
    scheduler : str, optional
        Address of a running Dask scheduler (``tcp://host:8786``) instead of a LocalCluster.
    cache_dir : str or Path, optional
        Stage cache shared by all points (default ``out/cache``); share it between sweeps.
    resources : mapping, optional
        Dask resources each task reserves (e.g. ``{"MPI": 4}`` for ``[nanoscale].ranks = 4``).
    figures : bool
        Draw the figures.
    map_keys : iterable of str
        Scalars (``stage.key``) drawn as colour maps over the first two varied fields.
    quiet : bool
        No progress lines.

    Returns
    -------
    SweepResult
    """
    from .scene import load_scene

    scene_path = Path(scene_path)
    load_scene(
        scene_path
    )  # validate the base scene before starting a cluster (one-line SceneError)
    base = tomllib.loads(scene_path.read_text())
    points = expand_points(base, axes, seeds)
    # Validate every point's scene up front: a bad --vary value is an input error, not a failed run.
    from .scene import parse_scene

    for p in points:
        parse_scene(
            point_scene_dict(base, p["vary"], p["seed"]),
            source=f"{scene_path} with {_label(p['vary'], p['seed'])}",
        )
    if scheduler is None and (
        isinstance(workers, bool) or not isinstance(workers, int) or workers < 1
    ):
        raise ParameterError("--workers", "an integer >= 1", workers)
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    cache = Path(cache_dir) if cache_dir is not None else out / "cache"
    source = str(scene_path.resolve())
    stream = stream or sys.stderr
    bar = _Bar(len(points), stream, quiet)
    t0 = time.perf_counter()
    rows: dict[str, dict[str, Any]] = {}
    todo = []
    for p in points:
        done = out / "points" / p["id"] / "point.json"
        if done.exists():
            try:
                row = json.loads(done.read_text())
            except ValueError:
                row = None
            if row is not None and row.get("status") == "ok":
                rows[p["id"]] = row
                bar.done += 1
                bar.line(f"{_label(p['vary'], p['seed'])}: done earlier (resumed)")
                continue
        todo.append(p)
    resumed = len(rows)
    n_workers = workers
    if todo:
        n_workers = _run_on_dask(
            todo, base, source, out, cache, workers, scheduler, resources, bar, rows
        )
    ordered = [rows[p["id"]] for p in points]
    wall = time.perf_counter() - t0
    table_csv, table_json = write_table(out, axes, ordered)
    figs = draw_figures(out, axes, ordered, map_keys) if figures else {}
    res = SweepResult(ordered, table_csv, table_json, n_workers, wall, figs, resumed)
    atomic_write_json(out / "sweep_result.json", res.to_json_dict())
    return res


def make_client(
    workers: int = 2, scheduler: str | None = None, resources: Mapping[str, float] | None = None
):
    """Open the sweep's Dask client: ``(client, cluster)``; ``cluster`` is None with ``scheduler``.

    The LocalCluster is bound to 127.0.0.1 with no dashboard, one thread per
    worker process (the benchmark uses the same engine as the sweep).
    """
    try:
        from distributed import Client, LocalCluster
    except ImportError:  # pragma: no cover - a core dependency
        raise SetupError(
            "tribolmp sweep: expected the 'distributed' "
            "package (pip install distributed), got ImportError"
        ) from None
    cluster = None
    if scheduler is None:
        # Loopback only (scheduler, workers and their HTTP endpoints on 127.0.0.1, free ports: a
        # busy 8787 is no obstacle): nothing listens beyond this machine.  One thread per worker
        # process: the chain's numpy/LAMMPS work is not GIL-free, processes give real parallelism.
        # Tasks that reserve resources (--resources MPI=R) need workers that have them: each local
        # worker gets exactly one task's worth, so a worker runs one such task at a time.
        extra = {"resources": dict(resources)} if resources else {}
        cluster = LocalCluster(
            n_workers=workers,
            threads_per_worker=1,
            processes=True,
            host="127.0.0.1",
            dashboard_address="127.0.0.1:0",
            worker_dashboard_address="127.0.0.1:0",
            silence_logs=40,
            **extra,
        )
        client = Client(cluster)
    else:
        try:
            client = Client(scheduler, timeout=30)
        except (OSError, TimeoutError) as exc:
            raise SetupError(
                "--scheduler: expected a reachable Dask "
                f"scheduler, got {scheduler} ({_one_line(exc)})"
            ) from None
    return client, cluster


def _run_on_dask(todo, base, source, out, cache, workers, scheduler, resources, bar, rows) -> int:
    from distributed import as_completed

    client, cluster = make_client(workers, scheduler, resources)
    try:
        n_workers = len(client.scheduler_info().get("workers", {})) or workers
        labels = {p["id"]: _label(p["vary"], p["seed"]) for p in todo}

        def _on_event(event):
            _, msg = event if isinstance(event, tuple) else (None, event)
            if isinstance(msg, dict) and msg.get("id") in labels:
                bar.line(
                    f"{labels[msg['id']]}: stage "
                    f"{msg.get('done')}/{msg.get('total')} {msg.get('stage', '')} done"
                )

        try:
            client.subscribe_topic("tribolmp-sweep", _on_event)
        except AttributeError:  # pragma: no cover - older distributed: overall progress only
            pass
        by_id = {p["id"]: p for p in todo}

        def _submit(p, attempt):
            pdir = out / "points" / p["id"]
            return client.submit(
                run_point,
                base,
                source,
                p["vary"],
                p["seed"],
                str(pdir),
                str(cache),
                key=f"tribolmp-point-{attempt}-{p['id']}",
                pure=False,
                resources=dict(resources) if resources else None,
            )

        futures = [_submit(p, 0) for p in todo]
        bar.line(f"{len(futures)} point(s) submitted")
        retry = []
        for fut in as_completed(futures):
            row = _row_of(fut, by_id, out)
            if row["status"] != "ok":
                # Two points sharing a stage's inputs may compute it at the same
                # moment and one of them loses the race for the cache folder:
                # each failed point runs once more, on the committed stages.
                retry.append(by_id[row["id"]])
                bar.line(
                    f"{_label(row['vary'], row['seed'])}: "
                    f"failed ({row['message']}); will retry once"
                )
                continue
            _record(row, rows, bar)
        for fut in as_completed([_submit(p, 1) for p in retry]):
            row = _row_of(fut, by_id, out)
            row["retried"] = True
            _record(row, rows, bar)
        return n_workers
    finally:
        client.close()
        if cluster is not None:
            cluster.close()


def _row_of(fut, by_id, out: Path) -> dict[str, Any]:
    try:
        return fut.result()
    except Exception as exc:  # noqa: BLE001 - a worker died: the point failed, the others go on
        pid = str(fut.key).rsplit("-", 1)[-1]
        p = by_id[pid]
        row = {
            "vary": p["vary"],
            "seed": p["seed"],
            "id": pid,
            "status": "failed",
            "values": {},
            "units": {},
            "message": _one_line(exc),
            "time_s": 0.0,
            "report": "",
        }
        atomic_write_json(out / "points" / pid / "point.json", row)
        return row


def _record(row, rows, bar) -> None:
    rows[row["id"]] = row
    bar.done += 1
    state = "ok" if row["status"] == "ok" else f"FAILED: {row['message']}"
    bar.line(f"{_label(row['vary'], row['seed'])}: {state} ({row['time_s']:.1f} s)")


# ------------------------------------------------------------------ table


def _error_key(key: str, values: Mapping[str, Any]) -> str | None:
    for cand in (f"{key}_err", f"{key}_error"):
        if cand in values:
            return cand
    return None


def _numeric(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def summarize(axes: Sequence[Vary], rows: Sequence[Mapping[str, Any]]) -> list[dict[str, Any]]:
    """Mean and standard error over seeds of every numeric value.

    Per combination of varied values.
    """
    groups: dict[str, list[Mapping[str, Any]]] = {}
    for r in rows:
        if r["status"] == "ok":
            groups.setdefault(canonical_json(r["vary"]), []).append(r)
    out = []
    for _, rs in groups.items():
        keys = sorted({k for r in rs for k, v in r["values"].items() if _numeric(v)})
        entry: dict[str, Any] = {
            "vary": dict(rs[0]["vary"]),
            "n_seeds": len(rs),
            "mean": {},
            "sem": {},
        }
        for k in keys:
            xs = [r["values"][k] for r in rs if _numeric(r["values"].get(k))]
            m = sum(xs) / len(xs)
            entry["mean"][k] = m
            # Standard error of the mean over seeds (None for one seed: no spread to measure).
            entry["sem"][k] = (
                math.sqrt(sum((x - m) ** 2 for x in xs) / (len(xs) - 1) / len(xs))
                if len(xs) > 1
                else None
            )
        out.append(entry)
    return out


def write_table(
    out: Path, axes: Sequence[Vary], rows: Sequence[Mapping[str, Any]]
) -> tuple[Path, Path]:
    """``sweep.csv`` (one row per point) and ``sweep.json``.

    The JSON holds the rows, units and the per-combination mean and sem.
    """
    vkeys = [a.key for a in axes]
    value_keys = sorted(
        {k for r in rows for k, v in r["values"].items() if not isinstance(v, (list, dict))}
    )
    units: dict[str, str] = {}
    for r in rows:
        units.update(r.get("units", {}))
    header = [
        "id",
        *vkeys,
        "seed",
        "status",
        *[f"{k} [{units[k]}]" if k in units else k for k in value_keys],
        "message",
    ]
    lines = []
    import io

    buf = io.StringIO()
    w = csv.writer(buf)
    w.writerow(header)
    for r in rows:
        w.writerow([r["id"], *[r["vary"].get(k) for k in vkeys], r["seed"], r["status"],
                    *[r["values"].get(k, "") for k in value_keys], r["message"]])
    lines.append(buf.getvalue())
    table_csv = atomic_write_text(out / "sweep.csv", "".join(lines))
    table_json = atomic_write_json(out / "sweep.json", {
        "vary": {a.key: list(a.values) for a in axes},
        "columns": value_keys,
        "units": units,
        "rows": [dict(r) for r in rows],
        "summary": summarize(axes, rows),
    })
    return table_csv, table_json


# ------------------------------------------------------------------ figures


def _find(keys: Iterable[str], *names: str) -> str | None:
    keys = list(keys)
    for n in names:
        for k in keys:
            if k == n or k.endswith("." + n):
                return k
    return None


def draw_figures(
    out: Path, axes: Sequence[Vary], rows: Sequence[Mapping[str, Any]], map_keys: Iterable[str] = ()
) -> dict[str, str]:
    """Draw mu against pressure per velocity and colour maps of requested scalars.

    mu carries error bars; returns name -> path.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figs: dict[str, str] = {}
    fdir = out / "figures"
    fdir.mkdir(parents=True, exist_ok=True)
    summary = summarize(axes, rows)
    if not summary:
        return figs
    vkeys = [a.key for a in axes]
    all_keys = sorted({k for s in summary for k in s["mean"]})
    mu = _find(all_keys, "mu")
    pkey = _find(vkeys, "pressure", "pressure_Pa", "normal_force")
    vkey = _find(
        [k for k in vkeys if k != pkey], "sliding_velocity", "sliding_velocity_m_s", "velocity"
    )
    if mu is not None and pkey is not None:
        fig, ax = plt.subplots(figsize=(5.5, 4))
        groups: dict[Any, list] = {}
        for s in summary:
            groups.setdefault(s["vary"].get(vkey) if vkey else None, []).append(s)
        for v, ss in sorted(
            groups.items(), key=lambda kv: (kv[0] is None, kv[0] if _numeric(kv[0]) else str(kv[0]))
        ):
            ss = sorted(ss, key=lambda s: s["vary"][pkey])
            xs = [s["vary"][pkey] for s in ss]
            ys = [s["mean"].get(mu) for s in ss]
            err_key = _error_key(mu, ss[0]["mean"])
            errs = [
                s["sem"].get(mu)
                if s["sem"].get(mu) is not None
                else (s["mean"].get(err_key) if err_key else None) or 0.0
                for s in ss
            ]
            ax.errorbar(
                xs,
                ys,
                yerr=errs,
                marker="o",
                capsize=3,
                label=f"{vkey.split('.')[-1]} = {v}" if vkey else None,
            )
        ax.set_xlabel(f"{pkey} (Pa)" if "pressure" in pkey else pkey)
        ax.set_ylabel(f"{mu} (mean ± s.e. over seeds)")
        if vkey:
            ax.legend(fontsize=8)
        ax.set_title("friction coefficient against pressure", fontsize=9)
        fig.tight_layout()
        path = fdir / "mu_vs_pressure.png"
        fig.savefig(path, dpi=100)
        plt.close(fig)
        figs["mu_vs_pressure"] = str(path)
    if len(vkeys) >= 2:
        xk, yk = vkeys[0], vkeys[1]
        xs = sorted(
            {s["vary"][xk] for s in summary},
            key=lambda v: (not _numeric(v), v if _numeric(v) else str(v)),
        )
        ys = sorted(
            {s["vary"][yk] for s in summary},
            key=lambda v: (not _numeric(v), v if _numeric(v) else str(v)),
        )
        for key in list(map_keys) or ([mu] if mu else []):
            if key not in all_keys:
                continue
            import numpy as np

            grid = np.full((len(ys), len(xs)), np.nan)
            for s in summary:
                # Mean over seeds and over any further varied fields.
                i, j = ys.index(s["vary"][yk]), xs.index(s["vary"][xk])
                val = s["mean"].get(key)
                if val is not None:
                    grid[i, j] = val if np.isnan(grid[i, j]) else 0.5 * (grid[i, j] + val)
            fig, ax = plt.subplots(figsize=(5.5, 4))
            im = ax.imshow(grid, origin="lower", aspect="auto", cmap="viridis")
            ax.set_xticks(
                range(len(xs)), [f"{v:g}" if _numeric(v) else str(v) for v in xs], fontsize=8
            )
            ax.set_yticks(
                range(len(ys)), [f"{v:g}" if _numeric(v) else str(v) for v in ys], fontsize=8
            )
            ax.set_xlabel(xk)
            ax.set_ylabel(yk)
            fig.colorbar(im, ax=ax, label=key)
            fig.tight_layout()
            name = "map_" + key.replace(".", "_")
            path = fdir / f"{name}.png"
            fig.savefig(path, dpi=100)
            plt.close(fig)
            figs[name] = str(path)
    return figs
