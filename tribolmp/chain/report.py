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

import numpy as np

from ..environment import versions
from ..jsonio import atomic_write_json, atomic_write_text, hash_inputs

if TYPE_CHECKING:  # pragma: no cover
    from .runner import ChainRun

__all__ = ["write_json", "write_report", "report_dict", "draw_figures", "versions"]


def _rel(path: Path, base: Path) -> str:
    try:
        return os.path.relpath(path, base)
    except ValueError:  # different drive (Windows)
        return str(path)


def report_dict(run: ChainRun, *, partial: bool = False, figures: dict[str, str] | None = None) -> dict[str, Any]:
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
    from .planner import STAGES

    scene = run.scene
    scene_dict = scene.to_dict()
    rows, details, results, handoffs = [], {}, {}, {}
    for name in STAGES:
        e = run.entries.get(name)
        if e is None:
            sp = run.plan[name]
            rows.append({"name": name, "ran": False, "reason": "pending" if sp.run else sp.reason, "time_s": 0.0})
            continue
        rows.append(e.row())
        d: dict[str, Any] = {"status": e.status, "key": e.key, "plan_reason": run.plan[name].reason, "options": run.plan[name].options}
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
            handoffs[name] = {k: _rel(e.cached.path / v, run.out_dir) for k, v in rec.get("files", {}).items()}
        details[name] = d
    return {
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


def write_json(run: ChainRun, *, partial: bool = False, figures: dict[str, str] | None = None) -> Path:
    """Write ``report.json`` atomically and return its path."""
    return atomic_write_json(run.out_dir / "report.json", report_dict(run, partial=partial, figures=figures))


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
    if fig_errors:
        data["figure_errors"] = fig_errors
    atomic_write_json(run.out_dir / "report.json", data)
    return atomic_write_text(run.out_dir / "report.md", _markdown(data))


# ------------------------------------------------------------------ markdown


def _fmt(v: Any) -> str:
    if isinstance(v, float):
        return f"{v:.4g}"
    if isinstance(v, list) and len(v) > 8:
        return f"[{len(v)} values: {_fmt(v[0])} ... {_fmt(v[-1])}]"
    if isinstance(v, list):
        return "[" + ", ".join(_fmt(x) for x in v) + "]"
    return str(v)


_CAPTIONS = {
    "mca_snapshot": "MCA snapshot at the end of the nanoscale run (cf. Fig. 9): automata coloured by body",
    "mu_t": "Friction coefficient mu(t) = F_friction / F_normal of the nanoscale run",
    "psd": "Power spectral density of the evolved topography against the Eq. 23 theory (cf. Fig. 10)",
    "stiffness": "Normal contact stiffness against nominal pressure (median and q10-q90 of the ensemble)",
    "stick_slip": "Rigid body on the contact: friction force and slider velocity (stick-slip)",
    "f2": "Tribospectroscopy: squared friction force against oscillation amplitude (cf. Fig. 8)",
    "lubrication": "Squeeze-film force against gap: reduced damper, Reynolds and Brenner's exact series",
    "polishing": "Lubricated polishing: rms (Sq) and mean absolute (Sa) roughness of the workpiece against time",
}


def _markdown(data: dict[str, Any]) -> str:
    sc = data["scene"]
    lines = [
        f"# tribolmp run: {sc['name']}",
        "",
        f"- scene: `{sc['source']}` (input hash `{sc['input_hash'][:16]}`), master seed {sc['seed']}",
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
        lines.append(f"| {r['name']} | {'yes' if r['ran'] else 'no'} ({status}) | {r['time_s']:.2f} | {r['reason']} |")
    lines += ["", "## Results (SI units)", ""]
    for name, res in data["results"].items():
        lines += [f"### {name}", "", "| quantity | value | unit |", "|---|---|---|"]
        units = res.get("units", {})
        for k, v in res.get("values", {}).items():
            if isinstance(v, dict):
                continue
            lines.append(f"| {k} | {_fmt(v)} | {units.get(k, '')} |")
        files = data["handoffs"].get(name, {})
        if files:
            lines += ["", "Hand-off files: " + ", ".join(f"`{p}`" for p in files.values())]
        lines.append("")
    if data["figures"]:
        lines += ["## Figures", ""]
        for name, path in data["figures"].items():
            lines += [f"![{name}]({path})", "", f"*{_CAPTIONS.get(name, name)}*", ""]
    if data.get("figure_errors"):
        lines += ["Figures not drawn: " + "; ".join(f"{k}: {v}" for k, v in data["figure_errors"].items()), ""]
    return "\n".join(lines)


# ------------------------------------------------------------------- figures


def _fig_mca(ax, run: ChainRun) -> None:
    from ..analysis.plots import plot_snapshot

    # true-size discs coloured by body, like the seed's Fig. 9
    plot_snapshot(run.result("nanoscale").file("traj").parent, ax=ax)


def _fig_mu(ax, run: ChainRun) -> None:
    from ..analysis.plots import plot_friction

    # marks the averaging window and says "not steady" when no steady state was detected
    plot_friction(run.result("nanoscale").file("friction").parent, ax=ax)


def _fig_psd(ax, run: ChainRun) -> None:
    d = np.load(run.result("topography").file("psd"))
    k, s = d["k"], d["psd"]
    m = k > 0
    ax.loglog(k[m], s[m], ".", ms=1.5, color="0.7", label="periodogram")
    # Log-binned mean: a single periodogram scatters by ~100 %, the bin mean shows the shape.
    edges = np.geomspace(k[m].min(), k[m].max() * 1.0001, 25)
    idx = np.digitize(k[m], edges)
    kb = [k[m][idx == i].mean() for i in range(1, len(edges)) if np.any(idx == i)]
    sb = [s[m][idx == i].mean() for i in range(1, len(edges)) if np.any(idx == i)]
    ax.loglog(kb, sb, "o", ms=3, label="log-binned mean")
    if "psd_theory" in d:
        ax.loglog(k[m], d["psd_theory"][m], "k-", lw=1, label="Eq. 23 theory")
    ax.set_xlabel("k (1/m)")
    dim = int(run.result("topography").values.get("dim", 1))
    ax.set_ylabel(f"PSD (m^{dim + 2})")
    ax.legend(fontsize=7)


def _fig_stiffness(ax, run: ChainRun) -> None:
    d = np.load(run.result("contact").file("stiffness"))
    p, med = d["pressure"], d["stiffness"]
    ax.loglog(p, med, "o-", label="median")
    if "q10" in d and "q90" in d:
        ax.fill_between(p, d["q10"], d["q90"], alpha=0.3, label="q10-q90")
    ax.set_xlabel("nominal pressure (Pa)")
    ax.set_ylabel("normal stiffness (N/m)")
    ax.legend()


def _fig_stick_slip(ax, run: ChainRun) -> None:
    d = np.load(run.result("macroscale").file("trajectory"))
    ax.plot(d["t"], d["friction"], lw=0.8, label="drive-spring force (N)")
    ax.set_xlabel("t (s)")
    ax.set_ylabel("F (N)")
    if "velocity" in d:
        ax2 = ax.twinx()
        ax2.plot(d["t"], d["velocity"], "r", lw=0.5)
        ax2.set_ylabel("slider velocity (m/s)", color="r")


def _fig_f2(ax, run: ChainRun) -> None:
    d = np.load(run.result("tribospectroscopy").file("f2"))
    ax.plot(d["amplitude"] * 1e9, d["f2"], "o", ms=3, label="simulated")
    if "f2_fit" in d:
        ax.plot(d["amplitude"] * 1e9, d["f2_fit"], "k-", lw=1, label="fit")
    ax.set_xlabel("amplitude a (nm)")
    ax.set_ylabel("F^2 (N^2)")
    ax.legend()


def _fig_lubrication(ax, run: ChainRun) -> None:
    d = np.load(run.result("lubrication").file("curves"))
    for key in d.files:
        if key != "x" and d[key].shape == d["x"].shape:
            ax.loglog(d["x"], np.abs(d[key]), label=key)
    ax.set_xlabel(str(d["x_label"]) if "x_label" in d.files else "x")
    ax.set_ylabel("|F| (N)")
    ax.legend(fontsize=7)


def _fig_polishing(ax, run: ChainRun) -> None:
    d = np.load(run.result("lubrication").file("polishing"))
    ax.plot(d["t"], d["sq"] * 1e9, label="Sq")
    ax.plot(d["t"], d["sa"] * 1e9, label="Sa")
    ax.set_xlabel("t (s)")
    ax.set_ylabel("roughness (nm)")
    ax.legend(fontsize=7)


_TITLES = {
    "polishing": "polishing: roughness against time",
    "mca_snapshot": "MCA snapshot (cf. Fig. 9)",
    "mu_t": "friction coefficient mu(t), nanoscale",
    "psd": "topography PSD (cf. Fig. 10)",
    "stiffness": "normal stiffness vs load",
    "lubrication": "lubrication forces",
    "stick_slip": "stick-slip of the rigid body",
    "f2": "tribospectroscopy F^2(a) (cf. Fig. 8)",
}

_FIGURES = {
    "mca_snapshot": ("nanoscale", "traj", _fig_mca),
    "mu_t": ("nanoscale", "friction", _fig_mu),
    "psd": ("topography", "psd", _fig_psd),
    "stiffness": ("contact", "stiffness", _fig_stiffness),
    "lubrication": ("lubrication", "curves", _fig_lubrication),
    "polishing": ("lubrication", "polishing", _fig_polishing),
    "stick_slip": ("macroscale", "trajectory", _fig_stick_slip),
    "f2": ("tribospectroscopy", "f2", _fig_f2),
}


def draw_figures(run: ChainRun) -> tuple[dict[str, str], dict[str, str]]:
    """Draw every figure whose stage ran; return (name -> relative path, name -> error)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    folder = run.out_dir / "figures"
    folder.mkdir(parents=True, exist_ok=True)
    done, errors = {}, {}
    for name, (stage, filekey, func) in _FIGURES.items():
        res = run.result(stage)
        if res is None or filekey not in res.record.get("files", {}):
            continue
        fig, ax = plt.subplots(figsize=(5.5, 3.6), constrained_layout=True)
        try:
            func(ax, run)
            ax.set_title(_TITLES[name], fontsize=9)
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
