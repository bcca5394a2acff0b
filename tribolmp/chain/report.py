"""``report.json`` (every number with its provenance) and ``report.md`` with PNG figures.

The figures are drawn from the hand-off files the stages saved (rates,
friction time series, trajectory, PSD, stiffness table, F^2(a)); nothing is
recomputed here.  matplotlib is imported only inside :func:`draw_figures`.
"""

from __future__ import annotations

import os
import time
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..environment import versions
from ..jsonio import atomic_write_json, atomic_write_text, hash_inputs
from .stage import fmt

if TYPE_CHECKING:  # pragma: no cover
    from .runner import ChainRun

__all__ = ["write_json", "write_report", "report_dict", "draw_figures", "versions"]


def _rel(path: Path, base: Path) -> str:
    try:
        return os.path.relpath(path, base)
    except ValueError:  # different drive (Windows)
        return str(path)


def report_dict(
    run: ChainRun, *, partial: bool = False, figures: dict[str, str] | None = None
) -> dict[str, Any]:
    """Assemble the report as a plain dict.

    Parameters
    ----------
    run : ChainRun
        The (possibly unfinished) run.
    partial : bool
        True while stages are still running.
    figures : dict, optional
        Figure name -> path relative to the output folder.
    """
    scene = run.scene
    scene_dict = scene.to_dict()
    rows, details, results, handoffs = [], {}, {}, {}
    for name in run.plan.registry.names:
        e = run.entries.get(name)
        if e is None:
            sp = run.plan[name]
            rows.append(
                {
                    "name": name,
                    "ran": False,
                    "reason": "pending" if sp.run else sp.reason,
                    "time_s": 0.0,
                }
            )
            continue
        rows.append(e.row())
        d: dict[str, Any] = {
            "status": e.status,
            "key": e.key,
            "plan_reason": run.plan[name].reason,
            "options": run.plan[name].options,
        }
        if e.cached is not None:
            rec = e.cached.record
            d.update(
                cache_dir=_rel(e.cached.path, run.out_dir),
                seed=rec.get("seed"),
                method=rec.get("method"),
                message=rec.get("message"),
                nit=rec.get("nit"),
                compute_time_s=rec.get("time_s"),
                inputs_hash=rec.get("inputs_hash"),
                upstream=rec.get("inputs", {}).get("upstream"),
                created_utc=rec.get("created_utc"),
                provenance=rec.get("provenance"),
            )
            results[name] = {"values": rec.get("values", {}), "units": rec.get("units", {})}
            handoffs[name] = {
                k: _rel(e.cached.path / v, run.out_dir) for k, v in rec.get("files", {}).items()
            }
        details[name] = d
    report = {
        "tribolmp_version": versions()["tribolmp"],
        "complete": not partial and run.complete,
        "created_utc": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
        "wall_time_s": run.wall_time_s,
        "scene": {
            "name": scene.scene.name,
            "source": scene.source,
            "seed": scene.scene.seed,
            "input_hash": hash_inputs(scene_dict),
            "sections": scene_dict,
        },
        "versions": versions(),
        "stages": rows,
        "stage_details": details,
        "plan": run.plan.to_json_dict(),
        "results": results,
        "handoffs": handoffs,
        "figures": figures or {},
    }
    # Top-level fields the stages publish (e.g. the topography stage's "running_in", the
    # issue 15 contract), in registry order; None for a stage without results.
    for stage in run.plan.registry:
        values = results.get(stage.name, {}).get("values", {}) or {}
        report.update(stage.report_fields(values))
    return report


def write_json(
    run: ChainRun, *, partial: bool = False, figures: dict[str, str] | None = None
) -> Path:
    """Write ``report.json`` atomically and return its path."""
    return atomic_write_json(
        run.out_dir / "report.json", report_dict(run, partial=partial, figures=figures)
    )


def write_report(run: ChainRun, *, figures: bool = True) -> Path:
    """Write figures, the final ``report.json`` and ``report.md``; return the markdown path."""
    figs: dict[str, str] = {}
    fig_errors: dict[str, str] = {}
    if figures:
        try:
            figs, fig_errors = draw_figures(run)
        except Exception as exc:  # noqa: BLE001 - e.g. no matplotlib backend: keep the numbers
            fig_errors = {"all": " ".join(f"{type(exc).__name__}: {exc}".split())}
    data = report_dict(run, figures=figs)
    data["figure_captions"] = {
        f.name: f.caption or f.name for _s, f in _figures(run) if f.name in figs
    }
    if fig_errors:
        data["figure_errors"] = fig_errors
    atomic_write_json(run.out_dir / "report.json", data)
    return atomic_write_text(run.out_dir / "report.md", _markdown(data, run.plan.registry))


# ------------------------------------------------------------------ markdown


def _narrative(data: dict[str, Any], registry) -> list[str]:
    """Tell what ran, from which inputs, under which assumptions: each stage's own summary."""
    out: list[str] = []
    for stage in registry:
        values = data["results"].get(stage.name, {}).get("values", {})
        if values:
            out += stage.summary(values)
    if not out:
        return []
    return ["", "## What ran, from which inputs, under which assumptions", "", *out]


def _markdown(data: dict[str, Any], registry) -> str:
    sc = data["scene"]
    lines = [
        f"# tribolmp run: {sc['name']}",
        "",
        f"- scene: `{sc['source']}` (input hash `{sc['input_hash'][:16]}`), "
        f"master seed {sc['seed']}",
        f"- tribolmp {data['tribolmp_version']}; "
        + ", ".join(f"{k} {v}" for k, v in data["versions"].items() if k != "tribolmp"),
        f"- wall time {data['wall_time_s']:.1f} s; finished {data['created_utc']}",
        "",
        "## Stages",
        "",
        "| stage | ran | time (s) | reason |",
        "|---|---|---|---|",
    ]
    for r in data["stages"]:
        status = data["stage_details"].get(r["name"], {}).get("status", "")
        lines.append(
            f"| {r['name']} | {'yes' if r['ran'] else 'no'} ({status}) | {r['time_s']:.2f} "
            f"| {r['reason']} |"
        )
    lines += _narrative(data, registry)
    lines += ["", "## Results (SI units)", ""]
    for name, res in data["results"].items():
        lines += [f"### {name}", "", "| quantity | value | unit |", "|---|---|---|"]
        units = res.get("units", {})
        for k, v in res.get("values", {}).items():
            if isinstance(v, dict):
                continue
            lines.append(f"| {k} | {fmt(v)} | {units.get(k, '')} |")
        files = data["handoffs"].get(name, {})
        if files:
            lines += ["", "Hand-off files: " + ", ".join(f"`{p}`" for p in files.values())]
        lines.append("")
    if data["figures"]:
        lines += ["## Figures", ""]
        for name, path in data["figures"].items():
            lines += [
                f"![{name}]({path})",
                "",
                f"*{data.get('figure_captions', {}).get(name, name)}*",
                "",
            ]
    if data.get("figure_errors"):
        lines += [
            "Figures not drawn: "
            + "; ".join(f"{k}: {v}" for k, v in data["figure_errors"].items()),
            "",
        ]
    return "\n".join(lines)


# ------------------------------------------------------------------- figures


def _figures(run: ChainRun):
    """(stage, Figure) pairs of the registry, in stage order."""
    for stage in run.plan.registry:
        for fig in stage.figures:
            yield stage, fig


def draw_figures(run: ChainRun) -> tuple[dict[str, str], dict[str, str]]:
    """Draw every figure whose stage ran; return (name -> relative path, name -> error)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    folder = run.out_dir / "figures"
    folder.mkdir(parents=True, exist_ok=True)
    done, errors = {}, {}
    for stage, fig_decl in _figures(run):
        name = fig_decl.name
        res = run.result(stage.name)
        if res is None or fig_decl.file not in res.record.get("files", {}):
            continue
        fig, ax = plt.subplots(figsize=(5.5, 3.6), constrained_layout=True)
        try:
            fig_decl.draw(ax, res, run)
            ax.set_title(fig_decl.title or name, fontsize=9)
            path = folder / f"{name}.png"
            tmp = folder / f".{name}.tmp.png"
            fig.savefig(tmp, dpi=110)
            os.replace(tmp, path)
            done[name] = _rel(path, run.out_dir)
        except Exception as exc:  # noqa: BLE001 - a broken plot must not lose the numbers
            errors[name] = " ".join(f"{type(exc).__name__}: {exc}".split())
        finally:
            plt.close(fig)
    return done, errors
