"""Gather the speed-against-error tables of every model into one report.

Each model ships ``benchmarks/<name>.py`` with ``main(argv=None)`` that prints
a table and writes CSV files into ``benchmarks/results/``.  :func:`gather`
optionally runs each script's ``--quick`` variant (each in a fresh Python
process, so one crashing benchmark cannot take the others down) and then
collects the newest CSVs into ``bench.md`` and a long-format ``bench.csv``
(``benchmark, file, row, column, value``).
"""

from __future__ import annotations

import csv
import io
import json
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

from .cache import atomic_write_text

__all__ = ["find_benchmarks_dir", "run_benchmark", "gather"]


def find_benchmarks_dir(start: str | Path | None = None) -> Path | None:
    """Find the repository's ``benchmarks/`` folder.

    Under ``start`` (default cwd) or next to the package.
    """
    candidates = []
    if start is not None:
        candidates.append(Path(start))
    candidates += [Path.cwd() / "benchmarks", Path(__file__).resolve().parents[2] / "benchmarks"]
    for c in candidates:
        if c.is_dir() and any(c.glob("*.py")):
            return c
    return None


def run_benchmark(script: Path, *, quick: bool = True, timeout: float = 900.0) -> dict[str, Any]:
    """Run ``script``'s ``main(["--quick"])`` in a subprocess.

    Return status, wall time and output tail.
    """
    argv = ["--quick"] if quick else []
    code = (
        "import importlib.util, sys\n"
        f"spec = importlib.util.spec_from_file_location('bench_mod', {str(script)!r})\n"
        "mod = importlib.util.module_from_spec(spec); spec.loader.exec_module(mod)\n"
        f"rc = mod.main({argv!r})\n"
        "sys.exit(int(rc or 0))\n"
    )
    t0 = time.perf_counter()
    try:
        proc = subprocess.run(
            [sys.executable, "-c", code],
            cwd=script.parent.parent,
            capture_output=True,
            text=True,
            timeout=timeout,
        )
        rc, out, err = proc.returncode, proc.stdout, proc.stderr
    except subprocess.TimeoutExpired:
        rc, out, err = -1, "", f"timed out after {timeout:g} s"
    tail = " ".join((err.strip().splitlines() or [""])[-1].split())
    return {
        "script": script.name,
        "returncode": rc,
        "time_s": time.perf_counter() - t0,
        "stdout": out,
        "error": tail if rc else "",
    }


def _owners(scripts: list[Path], results_dir: Path | None) -> dict[str, list[Path]]:
    """CSV files of each benchmark.

    Named after its stem, else after its model (the stem's first word).

    ``contact_speed_vs_error.py`` owns ``contact_speed_vs_error*.csv`` and also
    ``contact_rough_speed_vs_error.csv`` (model ``contact``) when no other script's
    stem is a prefix of that file.
    """
    out: dict[str, list[Path]] = {s.stem: [] for s in scripts}
    if not results_dir or not results_dir.is_dir():
        return out
    for p in results_dir.glob("*.csv"):
        exact = [s.stem for s in scripts if p.stem == s.stem or p.stem.startswith(s.stem + "_")]
        model = [s.stem for s in scripts if p.stem.split("_")[0] == s.stem.split("_")[0]]
        owner = max(exact, key=len) if exact else (model[0] if len(model) == 1 else None)
        if owner is not None:
            out[owner].append(p)
    return out


def _short(cell: str) -> str:
    """4 significant digits for numbers in the markdown table (the CSV keeps full precision)."""
    try:
        v = float(cell)
    except ValueError:
        return cell
    return cell if cell.strip().lstrip("-").isdigit() else f"{v:.4g}"


def _read_csv(path: Path) -> tuple[list[str], list[list[str]]]:
    with open(path, newline="", encoding="utf-8") as fh:
        rows = list(csv.reader(fh))
    rows = [r for r in rows if r and not r[0].startswith("#")]
    return (rows[0], rows[1:]) if rows else ([], [])


def gather(
    out_dir: str | Path,
    *,
    benchmarks_dir: str | Path | None = None,
    run: bool = False,
    quick: bool = True,
    only: list[str] | None = None,
    timeout: float = 900.0,
    log=None,
) -> dict[str, Any]:
    """Collect (and optionally run) every benchmark; write ``bench.md`` and ``bench.csv``.

    Parameters
    ----------
    out_dir : str or Path
        Where the combined report goes.
    benchmarks_dir : str or Path, optional
        The ``benchmarks/`` folder (default: found from the cwd or the source tree).
    run : bool
        Run each benchmark first (``--quick`` when ``quick``); otherwise read existing CSVs.
    quick : bool
        Pass ``--quick`` to the benchmarks.
    only : list of str, optional
        Benchmark names (script stems) to include.
    timeout : float
        Per-benchmark time limit in s.
    log : file, optional
        Progress stream (default stderr).

    Returns
    -------
    dict
        ``{"benchmarks": [...], "markdown": path, "csv": path}``.
    """
    log = log or sys.stderr
    bdir = find_benchmarks_dir(benchmarks_dir)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    scripts = sorted(p for p in (bdir.glob("*.py") if bdir else []) if not p.name.startswith("_"))
    if only:
        scripts = [s for s in scripts if s.stem in only]
    results_dir = bdir / "results" if bdir else None
    entries = []
    for i, script in enumerate(scripts, 1):
        entry: dict[str, Any] = {
            "name": script.stem,
            "ran": False,
            "returncode": None,
            "time_s": None,
            "error": "",
        }
        if run:
            print(
                f"[{i}/{len(scripts)}] running {script.name} {'--quick' if quick else ''}",
                file=log,
                flush=True,
            )
            r = run_benchmark(script, quick=quick, timeout=timeout)
            entry.update(ran=True, returncode=r["returncode"], time_s=r["time_s"], error=r["error"])
        owned = _owners(scripts, results_dir)
        csvs = sorted(owned.get(script.stem, []), key=lambda p: p.stat().st_mtime, reverse=True)
        entry["csv"] = [str(p) for p in csvs]
        entry["tables"] = []
        for p in csvs:
            header, rows = _read_csv(p)
            entry["tables"].append(
                {"file": p.name, "header": header, "rows": rows, "mtime": p.stat().st_mtime}
            )
        entries.append(entry)

    md = ["# tribolmp benchmarks: speed against error", ""]
    if bdir is None:
        md.append(
            "No `benchmarks/` folder found (run from the repository root or pass --benchmarks)."
        )
    md.append(
        f"Source: `{bdir}`; mode: "
        f"{'ran --quick' if run and quick else 'ran full' if run else 'collected existing CSVs'}."
    )
    md.append("")
    long = io.StringIO()
    w = csv.writer(long)
    w.writerow(["benchmark", "file", "row", "column", "value"])
    for e in entries:
        md.append(f"## {e['name']}")
        md.append("")
        if e["ran"]:
            status = (
                "ok" if e["returncode"] == 0 else f"FAILED (exit {e['returncode']}): {e['error']}"
            )
            md.append(f"Run: {status}, {e['time_s']:.1f} s.")
        if not e["tables"]:
            md.append("No CSV results in benchmarks/results/.")
        for t in e["tables"]:
            md += [
                "",
                f"`{t['file']}` ({time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime(t['mtime']))})",
                "",
            ]
            if t["header"]:
                md.append("| " + " | ".join(t["header"]) + " |")
                md.append("|" + "---|" * len(t["header"]))
                for j, r in enumerate(t["rows"]):
                    md.append("| " + " | ".join(_short(c) for c in r) + " |")
                    for col, val in zip(t["header"], r):
                        w.writerow([e["name"], t["file"], j, col, val])
        md.append("")
    md_path = atomic_write_text(out / "bench.md", "\n".join(md) + "\n")
    csv_path = atomic_write_text(out / "bench.csv", long.getvalue())
    for e in entries:
        for t in e["tables"]:
            t.pop("mtime", None)
    return {
        "benchmarks_dir": str(bdir) if bdir else None,
        "benchmarks": entries,
        "markdown": str(md_path),
        "csv": str(csv_path),
    }


def build_contact_table(results_dir: str | Path) -> dict[str, Any]:
    """Build the planner's contact speed-error table from the contact benchmark's CSVs.

    Rows per grid ``n`` of ``contact_rough_mdr_vs_bem[_quick].csv`` (the rough
    surface of that benchmark, ``n x n`` pixels, MDR ensemble of 16):

    * ``mdr``: ``rel_error`` = max over pressures of ``|k_MDR / k_BEM,punch - 1|``
      (the non-periodic BEM is the 3D reference), ``time_s`` = MDR wall time per pressure;
    * ``bem``: ``rel_error`` = the non-periodic BEM's own discretization error at
      grid ``n`` on the Hertz case of ``contact_speed_vs_error[_quick].csv``
      (indentation vs the analytic solution; a smooth-contact proxy: the rough
      surface has no exact solution), ``time_s`` = max BEM punch wall time per pressure.

    The full-size CSVs are preferred over ``_quick`` ones for the same grid.

    When the repository's resolved rough-contact references
    (``tests/data/contact_references.json``, issue 17) are found next to the
    benchmarks, the table is the one their summary wrote into the package,
    ``tribolmp/data/contact_speed_error.json``
    (``tests/data/generate_reference_data.py contact-summary``).
    """
    rdir = Path(results_dir)
    refs = rdir.resolve().parent.parent / "tests" / "data" / "contact_references.json"
    if refs.exists():
        # The summary of the references is what
        # tests/data/generate_reference_data.py contact-summary ships as the package
        # table; the chain does not import test code, so it reads that table.
        shipped = Path(__file__).resolve().parents[1] / "data" / "contact_speed_error.json"
        table = json.loads(shipped.read_text())
        table["provenance"] = f"{table.get('provenance', '')} (read by build_contact_table)"
        return table
    rough_rows: dict[int, list[dict[str, str]]] = {}
    hertz: dict[int, float] = {}
    sources = []
    for suffix in ("_quick", ""):  # full-size files last, so they win
        rp = rdir / f"contact_rough_mdr_vs_bem{suffix}.csv"
        if rp.exists():
            header, rows = _read_csv(rp)
            by_grid: dict[int, list[dict[str, str]]] = {}
            for r in rows:
                d = dict(zip(header, r))
                by_grid.setdefault(int(float(d["grid"])), []).append(d)
            rough_rows.update(by_grid)
            sources.append(rp.name)
        hp = rdir / f"contact_speed_vs_error{suffix}.csv"
        if hp.exists():
            header, rows = _read_csv(hp)
            for r in rows:
                d = dict(zip(header, r))
                if d["case"] == "hertz" and d["method"] == "bem":
                    hertz[int(float(d["resolution"]))] = float(d["error"])
            sources.append(hp.name)
    out_rows = []
    for n, rows in sorted(rough_rows.items()):
        out_rows.append({
            "method": "mdr",
            "mesh": n,
            "rel_error": max(abs(float(d["ratio_mdr_punch"]) - 1.0) for d in rows),
            "time_s": max(float(d["mdr_time_s"]) for d in rows),
        })
        if n in hertz:
            out_rows.append({
                "method": "bem",
                "mesh": n,
                "rel_error": hertz[n],
                "time_s": max(float(d["bem_punch_time_s"]) for d in rows),
            })
    return {
        "provenance": (
            "built by tribolmp.chain.bench.build_contact_table from benchmarks/results/"
            + ", ".join(sources)
            + " (written by benchmarks/contact_speed_vs_error.py). mdr rows: max over pressures of "
            "|k_MDR/k_BEM,punch - 1| on that benchmark's rough "
            "surface at grid n (16 profiles), time = MDR wall "
            "time per pressure. bem rows: the non-periodic "
            "BEM's discretization error at grid n on Hertz "
            "(indentation vs analytic; a proxy, the rough "
            "surface has no exact solution), time = BEM punch "
            "wall time per pressure on the rough surface."
        ),
        "quantity": "relative error of the normal contact stiffness "
                    "(MDR vs non-periodic BEM; BEM vs Hertz)",
        "mesh_unit": "grid points per side of the height map (MDR: spring rows of that length)",
        "created_utc": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
        "rows": out_rows,
    }
