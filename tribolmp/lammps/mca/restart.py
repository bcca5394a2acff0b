"""Restart files, resume and repair of an MCA output folder.

What makes a resume exact (one rank) and idempotent under any sequence of
interrupts:

* The driver runs the deck in chunks that end on restart steps (whole
  ``friction.csv`` averaging windows).  Every ``run`` command re-sorts the
  atoms and rebuilds the neighbour lists at its start, so a resumed run, which
  starts with a ``run`` at a restart step, passes through the same states as
  the uninterrupted run, which starts a ``run`` at the same step.
* Restart files are written by :func:`write_restart` to a temporary name and
  renamed: a file named ``restart.<step>.bin`` is complete.  ``meta.json`` and
  the rewritten outputs are written the same way (:func:`atomic_write_text`).
* On resume the outputs are cut back to the restart step (:func:`truncate_outputs`):
  ``friction.csv`` keeps its title and the numeric rows up to that step; lines
  that are not numbers (the ``#`` header ``fix print`` writes whenever it
  re-opens a file, a row cut by a kill) are dropped; ``traj.lammpstrj`` keeps
  complete frames up to that step.  :func:`finalize_outputs` removes the rows
  and frames a ``run`` command writes twice (its first step) or off the dump
  interval (the first frame of a re-opened dump).
* A folder that holds no simulated work (no restart file and no finished
  ``rates.json``: a run that failed before its first restart) is discarded and
  recomputed (:func:`discard_run_files`).  A folder that holds work of another
  run (a different ``meta.json``) or that is not being resumed is never
  discarded silently: :func:`check_folder` refuses it with one line naming the
  fields that differ, unless the caller asks to overwrite it or to move it
  aside (:func:`archive_run_files`), so that hours of simulation are never
  lost to a changed parameter or a forgotten ``--resume``.

:func:`run_mca_resuming` is the entry point of the chain's nanoscale stage: it
resumes whatever an earlier, interrupted run left in the stage's folder.
"""

from __future__ import annotations

import json
import os
import re
import tempfile
from pathlib import Path
from typing import Any

__all__ = [
    "RUN_FILES",
    "archive_run_files",
    "atomic_write_json",
    "check_folder",
    "atomic_write_text",
    "discard_run_files",
    "finalize_outputs",
    "prune_restarts",
    "restart_files",
    "run_mca_resuming",
    "truncate_outputs",
    "write_restart",
]

_RESTART = re.compile(r"^restart\.(\d+)\.bin$")
#: Files the driver writes into an output folder (removed when a folder is discarded).
RUN_FILES = (
    "meta.json",
    "system.data",
    "friction.csv",
    "traj.lammpstrj",
    "run.log",
    "counters.json",
    "rates.json",
    "profile.npz",
)
CSV_TITLE = "time_s,friction_N,normal_N,top_x_m"


def atomic_write_text(path: Path, text: str) -> None:
    """Write ``text`` to ``path`` through a temporary file and a rename (never half-written)."""
    path = Path(path)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "w") as fh:
            fh.write(text)
            fh.flush()
            os.fsync(fh.fileno())
        os.chmod(tmp, 0o644)  # mkstemp makes 0600; results are for colleagues too
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def atomic_write_json(path: Path, data: Any) -> None:
    """:func:`atomic_write_text` of ``json.dumps(data, indent=1)``."""
    atomic_write_text(path, json.dumps(data, indent=1))


def restart_files(out: Path) -> list[tuple[int, Path]]:
    """Complete restart files in ``out`` as (step, path), oldest first."""
    found = []
    for p in Path(out).glob("restart.*.bin"):
        m = _RESTART.match(p.name)
        if m and p.stat().st_size > 0:
            found.append((int(m.group(1)), p))
    return sorted(found)


def write_restart(lmp, out: Path, step: int, *, is_root: bool) -> Path:
    """``write_restart`` to a temporary name, then rename to ``restart.<step>.bin`` (rank 0).

    The rename is atomic, so a kill at any moment leaves either no file of
    that step or a complete one.
    """
    tmp = Path(out) / f".restart.{step}.bin.tmp"
    final = Path(out) / f"restart.{step}.bin"
    lmp.command(f"write_restart {tmp}")
    if is_root:
        with open(tmp, "rb") as fh:
            os.fsync(fh.fileno())
        os.chmod(tmp, 0o644)
        os.replace(tmp, final)
    return final


def prune_restarts(out: Path, keep: int = 2) -> None:
    """Keep the newest ``keep`` restart files; remove older ones and stale temporaries."""
    for _step, p in restart_files(out)[:-keep]:
        p.unlink(missing_ok=True)
    for p in Path(out).glob(".restart.*.bin.tmp"):
        p.unlink(missing_ok=True)


def _flat(d: Any, prefix: str = "") -> dict[str, Any]:
    """Nested dicts as {dotted key: value} (lists and scalars are leaves)."""
    if not isinstance(d, dict):
        return {prefix: d}
    out: dict[str, Any] = {}
    for k, v in d.items():
        out.update(_flat(v, f"{prefix}.{k}" if prefix else str(k)))
    return out


def run_differences(meta: dict[str, Any], expected: dict[str, Any]) -> list[str]:
    """Where the run described by ``meta`` differs from ``expected``, as ``key: folder != asked``.

    Only the keys of ``expected`` are compared (``params``, ``seed``,
    ``overrides``); a key the folder's ``meta.json`` lacks (a run written by
    an older version) is reported as ``missing``.
    """
    have = _flat({k: meta.get(k, "<missing>") for k in expected})
    want = _flat(expected)
    diffs = []
    for key in sorted(set(have) | set(want)):
        a, b = have.get(key, "<missing>"), want.get(key, "<missing>")
        if a != b:
            diffs.append(f"{key}: folder {a!r} != asked {b!r}")
    return diffs


def held_work(out: Path) -> str | None:
    """Describe the simulated work ``out`` holds, or None if it holds none worth keeping.

    Work is a restart file (a run that can be continued) or a finished run's
    ``rates.json``.  A run that failed before its first restart holds nothing
    that a rerun would not recompute within one restart interval.
    """
    out = Path(out)
    restarts = restart_files(out) if out.is_dir() else []
    if restarts:
        return f"{len(restarts)} restart file(s), the newest at step {restarts[-1][0]}"
    if (out / "rates.json").is_file():
        return "a finished run (rates.json)"
    return None


def check_folder(
    out: Path, expected: dict[str, Any], *, resume: bool, on_conflict: str
) -> tuple[dict[str, Any] | None, Path | None]:
    """Decide what to do with an output folder before a run; refuse rather than lose work.

    Parameters
    ----------
    out : Path
        The run's output folder.
    expected : dict
        What ``meta.json`` must hold for the folder to be this run (``params``,
        ``seed``, ``overrides``).
    resume : bool
        The caller asks to continue the run the folder holds.
    on_conflict : {"refuse", "overwrite", "archive"}
        What to do when the folder holds work that this call would destroy
        (work of another run, or any work when not resuming): raise, discard
        it, or move it into ``out/superseded/<n>/``.

    Returns
    -------
    meta : dict or None
        The folder's ``meta.json`` when it is this run and ``resume`` is set
        (continue from its restart files), else None (start from the beginning;
        the folder's run files have been discarded or archived by then).
    archived : Path or None
        Where the work of another run was moved (``on_conflict="archive"``).

    Raises
    ------
    SetupError
        One line: the folder, what it holds, the fields that differ and what
        to do, when ``on_conflict`` is ``"refuse"`` and work would be lost.
    """
    from ...errors import SetupError

    if on_conflict not in ("refuse", "overwrite", "archive"):
        raise ValueError(f"on_conflict: expected refuse|overwrite|archive, got {on_conflict!r}")
    out = Path(out)
    if not out.is_dir():
        return None, None
    try:
        folder_meta = json.loads((out / "meta.json").read_text())
    except (OSError, ValueError):
        folder_meta = None
    if not isinstance(folder_meta, dict):
        folder_meta = None
    same = folder_meta is not None and not run_differences(folder_meta, expected)
    if resume and same and (out / "system.data").is_file():
        return folder_meta, None
    work = held_work(out)
    if work is None or on_conflict == "overwrite":
        discard_run_files(out)
        return None, None
    if on_conflict == "archive":
        return None, archive_run_files(out)
    if not resume:
        what = "resume it (--resume / resume=True), choose an empty folder, or overwrite it"
        raise SetupError(f"out_dir: {out} holds an earlier run ({work}); {what} (--overwrite)")
    if folder_meta is None:
        why = "no readable meta.json"
    else:
        diffs = run_differences(folder_meta, expected)
        why = "; ".join(diffs[:3]) + (f"; and {len(diffs) - 3} more" if len(diffs) > 3 else "")
        why = why or "no system.data"
    raise SetupError(
        f"out_dir: {out} holds a different run ({work}): {why}; resume needs the same "
        "parameters, seed and overrides: pass those, choose another folder, or overwrite it "
        "(--overwrite)"
    )


def archive_run_files(out: Path) -> Path:
    """Move the run files of ``out`` into ``out/superseded/<n>/`` (never deletes; returns it)."""
    out = Path(out)
    base = out / "superseded"
    n = 1
    while (base / str(n)).exists():
        n += 1
    dest = base / str(n)
    dest.mkdir(parents=True)
    names = [out / name for name in RUN_FILES] + [p for _s, p in restart_files(out)]
    for p in names:
        if p.exists():
            os.replace(p, dest / p.name)
    return dest


def discard_run_files(out: Path) -> None:
    """Remove everything a previous run left in ``out`` (only the files the driver writes)."""
    out = Path(out)
    for name in RUN_FILES:
        (out / name).unlink(missing_ok=True)
    for _step, p in restart_files(out):
        p.unlink(missing_ok=True)
    for pattern in ("restart.*.bin", ".restart.*.bin.tmp", ".*.tmp"):
        for p in out.glob(pattern):
            p.unlink(missing_ok=True)


def _csv_title(text: str) -> str:
    """Return the file's own title line (a law may print more columns than the four SI ones)."""
    for ln in text.splitlines():
        if ln.startswith("time_s,"):
            return ln.strip()
    return CSV_TITLE


def _csv_rows(text: str) -> list[tuple[float, str]]:
    """Numeric rows of friction.csv as (time, line); anything else (titles, cut lines) dropped."""
    ncols = len(_csv_title(text).split(","))
    rows = []
    for ln in text.splitlines():
        parts = ln.split(",")
        if len(parts) != ncols:
            continue
        try:
            t = float(parts[0])
            [float(x) for x in parts[1:]]
        except ValueError:
            continue
        rows.append((t, ln))
    return rows


def _frames(text: str) -> list[tuple[int, str]]:
    """Complete dump frames as (step, text); a frame cut by a kill is dropped."""
    frames = []
    for chunk in text.split("ITEM: TIMESTEP\n")[1:]:
        lines = chunk.split("\n")
        try:
            step = int(lines[0])
            n = int(lines[lines.index("ITEM: NUMBER OF ATOMS") + 1])
            start = next(i for i, ln in enumerate(lines) if ln.startswith("ITEM: ATOMS")) + 1
        except (ValueError, StopIteration, IndexError):
            continue
        body = lines[start : start + n]
        if len(body) != n or any(len(b.split()) != len(lines[start - 1].split()) - 2 for b in body):
            continue
        frames.append((step, "ITEM: TIMESTEP\n" + "\n".join(lines[: start + n]) + "\n"))
    return frames


def _first_rows(rows: list[tuple[float, str]]) -> list[str]:
    """Keep the first row of each time (a ``run`` command repeats the row of its first step)."""
    seen: set[str] = set()
    kept = []
    for _t, ln in rows:
        key = ln.split(",", 1)[0]
        if key not in seen:
            seen.add(key)
            kept.append(ln)
    return kept


def truncate_outputs(out: Path, step: int, dt_s: float) -> None:
    """Cut ``friction.csv`` and ``traj.lammpstrj`` back to ``step``.

    The resumed run writes the rest.
    """
    out = Path(out)
    csv = out / "friction.csv"
    if csv.exists():
        t_max = step * dt_s * (1 + 1e-9)
        text = csv.read_text()
        rows = _first_rows([(t, ln) for t, ln in _csv_rows(text) if t <= t_max])
        atomic_write_text(csv, "\n".join([_csv_title(text), *rows]) + "\n")
    traj = out / "traj.lammpstrj"
    if traj.exists():
        kept = [fr for st, fr in _frames(traj.read_text()) if st <= step]
        atomic_write_text(traj, "".join(kept))


def finalize_outputs(out: Path, dump_every: int) -> None:
    """Drop repeated rows/frames (keep the first) and frames off the dump interval.

    LAMMPS's ``fix print`` and ``dump`` also write on the first step of every
    ``run`` command, and a re-opened dump writes its first frame whatever the
    step, so chunk ends and restart steps appear twice; the first copy is the
    one of the uninterrupted run.
    """
    out = Path(out)
    csv = out / "friction.csv"
    if csv.exists():
        text = csv.read_text()
        kept = _first_rows(_csv_rows(text))
        atomic_write_text(csv, "\n".join([_csv_title(text), *kept]) + "\n")
    traj = out / "traj.lammpstrj"
    if traj.exists():
        seen_steps: set[int] = set()
        frames = []
        for st, fr in _frames(traj.read_text()):
            if st % dump_every == 0 and st not in seen_steps:
                seen_steps.add(st)
                frames.append(fr)
        atomic_write_text(traj, "".join(frames))


def run_mca_resuming(
    params: Any, out: Path, *, seed: int, ranks: int = 1
) -> tuple[Any, dict[str, Any]]:
    """Run :func:`tribolmp.lammps.mca.run_mca` into ``out``, resuming what a kill left there.

    A folder that already holds files is resumed (``run_mca(..., resume=True)``):
    ``run_mca`` continues from the newest readable restart file of the same
    run and drops restart files LAMMPS cannot read.  The work of another run
    (a stage folder written by another package version, say) is moved into
    ``out/superseded/<n>/``, never deleted.  An empty or missing folder starts
    a fresh run.

    Parameters
    ----------
    params : MCAParams
        The run's parameters (SI).
    out : Path
        Output folder (kept across interrupts).
    seed : int
        Seed of the geometry and of LAMMPS.
    ranks : int
        MPI ranks.

    Returns
    -------
    result : Result
        What ``run_mca`` returned.
    info : dict
        ``resumed`` (bool: the folder held files, so a resume was attempted)
        and ``discarded_restarts`` (names of the unreadable restart files
        dropped).
    """
    from .driver import run_mca  # the driver imports this module

    out = Path(out)
    resume = out.is_dir() and any(out.iterdir())
    res = run_mca(params, out, seed=seed, resume=resume, np=ranks, on_conflict="archive")
    info = {"resumed": resume, "discarded_restarts": list(res.get("discarded_restarts", []))}
    if res.get("superseded_run"):
        info["superseded_run"] = res["superseded_run"]
    return res, info
