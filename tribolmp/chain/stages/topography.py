"""Stage ``topography``: the stochastic surface equation (Eq. 23) with the chain's rates -> height map."""

from __future__ import annotations

import numpy as np

from ...jsonio import scalars
from ..stage import Decision, Demand, Figure, Handoff, Stage, StageContext, StageOutput
from ._rates import upstream_rates


def _draw_psd(ax, result, run) -> None:
    d = np.load(result.file("psd"))
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
    dim = int(result.values.get("dim", 1))
    ax.set_ylabel(f"PSD (m^{dim + 2})")
    ax.legend(fontsize=7)


class Topography(Stage):
    """Eq. 23 surface evolution with the nanoscale rates (or ``[rates]``, or ``[topography]`` values)."""

    name = "topography"
    produces = (
        Handoff("surface", units={"heights": "m", "pixel_size": "m"}, doc="surface.npy (+ surface.json sidecar): evolved height map"),
        Handoff("psd", units={"k": "1/m", "psd": "m^(d+2)", "psd_theory": "m^(d+2)"}, doc="psd.npz: PSD against Eq. 23 theory"),
    )
    consumes = ("rates",)
    outputs = ("topography",)
    sections = ("topography", "kinematics", "rates")
    figures = (
        Figure("psd", "psd", _draw_psd, "topography PSD (cf. Fig. 10)",
               "Power spectral density of the evolved topography against the Eq. 23 theory (cf. Fig. 10)"),
    )

    def plan(self, scene, demand: Demand) -> Decision:
        """Evolve only with a ``[topography]`` section, when requested or when contact wants the surface."""
        if scene.topography is None:
            r = scene.roughness
            given = (
                f"the height map {r.surface_file}" if r is not None and r.surface_file
                else "a random surface from [roughness]" if r is not None
                else f"the [geometry] profile '{scene.geometry.profile}'"
            )
            return self.skip(f"no [topography] section: contact uses {given}")
        if not (demand.requested("topography") or demand.wants("surface")):
            return self.skip("no requested output needs the evolved surface")
        why = "outputs request 'topography'" if demand.requested("topography") else "the evolved surface feeds contact"
        return self.go(why, sections=("topography", "kinematics"), wants=("rates",))

    def bind(self, scene, decision: Decision, supplied) -> Decision:
        """Name the rates' source; ``[rates]`` joins the hashed sections when it is the source."""
        from dataclasses import replace

        if "rates" in supplied:
            rsrc, src, secs = "measured by nanoscale", "nanoscale", decision.sections
        elif scene.rates is not None:
            rsrc, src, secs = "given in [rates]", "scene", decision.sections + ("rates",)
        else:
            rsrc, src, secs = "[topography] values (no rates in the scene)", "topography", decision.sections
        return replace(decision, reason=f"Eq. 23 with rates {rsrc}; {decision.reason}", sections=secs,
                       options={**decision.options, "rates_source": src})

    def preflight(self, scene, decision: Decision) -> list[str]:
        """Check the Eq. 23 grid against this machine's memory; note the evolution's cost."""
        from ...resources import check_memory

        t = scene.topography
        points = float(t.grid_points) ** t.dim
        # The exact scheme keeps ~5 grid arrays of float64 (benchmarks/topography_speed_vs_error.py:
        # 5.0 grid arrays at 1024^2), plus the saved map and its PSD.
        check_memory(7 * 8 * points, "[topography].grid_points", t.grid_points, f"a {t.dim}D Eq. 23 grid",
                     scene.source)
        # ~90 ns per point-step measured from 2^10 to 2^20 points (same benchmark).
        seconds = 90e-9 * points * t.steps
        return [f"Eq. 23 on {t.grid_points}^{t.dim} points x {t.steps} steps: ~{seconds:.2g} s"] if seconds > 10 else []

    def run(self, ctx: StageContext) -> StageOutput:
        """Eq. 23 with the upstream rates -> final height map (``surface.npy`` + sidecar JSON) and its PSD."""
        from ...models import topography as topo

        rates, rates_src = upstream_rates(ctx)
        params = topo.params_from_scene(ctx.scene, rates=rates)
        res = topo.evolve(params, rng=ctx.rng, scheme=ctx.scene.topography.scheme, progress=ctx.progress)
        topo.save_height_map(ctx.workdir / "surface.npy", res.h, params.dx)
        np.savez(ctx.workdir / "psd.npz", k=res.k, psd=res.psd, psd_theory=res.psd_theory)
        files = {"surface": "surface.npy", "psd": "psd.npz"}
        if (ctx.workdir / "surface.json").exists():
            files["surface_meta"] = "surface.json"
        if (ctx.workdir / "rates.json").exists():
            files["rates"] = "rates.json"
        # Bookkeeping fields (method, message, wall time, counters) go to the record, not the numbers.
        values = {k: v for k, v in scalars(res).items() if k not in ("status", "method", "message", "time_s", "nit", "history")}
        values["rates_source"] = rates_src or "[topography]"
        values["params"] = scalars(dict(vars(params)))
        return StageOutput(
            values=values,
            units={k: v for k, v in res.units.items() if k in values},
            files=files,
            method=res.method,
            message=res.message,
            nit=int(res.nit),
        )


STAGE = Topography()
