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
        # Issue 15 contract: the running-in series of the part (topography stage), top level.
        "running_in": (results.get("topography", {}).get("values", {}) or {}).get("running_in"),
    }


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


def _narrative(data: dict[str, Any]) -> list[str]:
    """Tell what ran, from which inputs, under which assumptions (issue 15)."""
    res = data["results"]
    out: list[str] = []
    topo = res.get("topography", {}).get("values", {})
    if "running_in" in topo:
        ri = topo["running_in"]
        fr = topo.get("friction") or {}
        eq = topo.get("eq23_mca") or {}
        warn = " ".join(topo.get("eq23_warnings") or [])
        k_n = ri["normal_stiffness_N_m"]
        factor = ri["rate_factor"]
        extra = f"; **extrapolated**: {fr.get('extrapolation')}" if fr.get("extrapolated") else ""
        out += [
            f"- **Rates** from {topo.get('rates_source')}: Eq. 23 coefficients "
            f"{topo.get('eq23_source')} at the MCA's V = {_fmt(eq.get('velocity_m_s'))} m/s, "
            f"P = {_fmt(eq.get('pressure_Pa'))} Pa (k1 = {_fmt(eq.get('k1'))}, "
            f"k2 = {_fmt(eq.get('k2'))} 1/m). {warn}".rstrip(),
            "- **At the part** every rate is multiplied by phi V_part / V_MCA (processes scale "
            f"with the distance slid in contact; factor {_fmt(factor[0])} at the start, "
            f"{_fmt(factor[-1])} at the end) and the noise intensities by the slab thickness "
            f"w = {_fmt(topo.get('slab_thickness_m'))} m ({topo.get('slab_thickness_source')}) "
            "to go from the MCA's 1D profile to the 2D surface.",
            f"- **Surface**: {topo.get('surface_source')}, "
            f"side {_fmt(topo.get('domain_size_m'))} m; "
            f"Rq {_fmt(topo.get('rq_initial_m'))} -> {_fmt(topo.get('rq_final_m'))} m over "
            f"{_fmt(topo.get('sliding_distance_m'))} m of sliding in {ri.get('checkpoints')} "
            f"checkpoints ({ri.get('substeps')} Eq. 23 sub-steps, phi changing by at most the "
            "stated tolerance per sub-step).",
            f"- **Contact** at every checkpoint: {ri.get('contact_method')} "
            f"({topo.get('contact_method_reason')}); "
            f"real-contact fraction: {ri.get('phi_source')}.",
            "- **Stiffness** of the apparent contact: interfacial stiffness per area x A in series "
            f"with the bonded punch 2E*sqrt(A/pi) = {_fmt(ri.get('bound_N_m'))} N/m (the bound); "
            f"{_fmt(k_n[0])} -> {_fmt(k_n[-1])} N/m.",
            f"- **Friction**: mu_k = {_fmt(fr.get('mu_kinetic'))}, "
            f"mu_s = {_fmt(fr.get('mu_static'))} "
            f"({fr.get('source')}); matched at the {fr.get('pressure_source')} pressure "
            f"{_fmt(fr.get('pressure_Pa'))} Pa{extra}.",
        ]
        conv = ri.get("convergence")
        if conv:
            n0, n1 = conv["checkpoints"]
            out.append(
                f"- **Convergence**: halving the checkpoint spacing ({n0} -> {n1}) changes "
                f"the final Rq by {_fmt(conv['rq_final_rel_change'])} and the stiffness by "
                f"{_fmt(conv['stiffness_final_rel_change'])} (relative)."
            )
    mac = res.get("macroscale", {}).get("values", {})
    if mac:
        out.append(
            f"- **Rigid body**: contact stiffness {_fmt(mac.get('contact_stiffness_N_m'))} N/m "
            f"({mac.get('contact_stiffness_source')}), bound "
            f"{_fmt(mac.get('contact_stiffness_bound_N_m'))} N/m; {mac.get('n_slip_events')} slip "
            f"events with mu_s = {_fmt(mac.get('mu_static'))}, "
            f"mu_k = {_fmt(mac.get('mu_kinetic'))}; lowest velocity after the first slip "
            f"{_fmt(mac.get('min_velocity_after_first_slip_m_s'))} m/s (above 0: no re-stick)."
        )
    tri = res.get("tribospectroscopy", {}).get("values", {})
    if tri:
        out.append(
            f"- **Tribospectroscopy**: length {_fmt(tri.get('length_m'))} m from "
            f"{tri.get('length_source')}; fitted on a simulated measurement with "
            f"{_fmt(tri.get('measurement_noise_rel'))} relative noise: "
            f"{_fmt(tri.get('fitted_length_m'))} m, 68 % interval "
            f"{tri.get('fitted_length_interval_m')} ({tri.get('fit_message')})."
        )
    if not out:
        return []
    return ["", "## What ran, from which inputs, under which assumptions", "", *out]


def _markdown(data: dict[str, Any]) -> str:
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
    lines += _narrative(data)
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
