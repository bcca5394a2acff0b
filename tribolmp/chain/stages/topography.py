"""Stage ``topography``.

The stochastic surface equation (Eq. 23) with the chain's rates -> height map.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from ...jsonio import scalars
from ..stage import Decision, Demand, Figure, Handoff, Stage, StageContext, StageOutput, fmt
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


def _runin(result):
    return np.load(result.file("runin"))


def _draw_runin_rq(ax, result, run) -> None:
    d = _runin(result)
    s = d["sliding_distance_m"] * 1e3
    ax.plot(s, d["rq_m"] * 1e9, "o-", ms=3, label="Rq")
    ax.set_xlabel("sliding distance (mm)")
    ax.set_ylabel("Rq (nm)")
    ax.set_yscale("log")
    ax2 = ax.twinx()
    ra = d["real_area_fraction"]
    if np.any(np.isfinite(ra)):
        ax2.plot(s, ra, "s-", color="tab:red", ms=3, label="real-contact fraction (BEM)")
    ax2.plot(s, d["phi"], "--", color="tab:red", lw=0.8, label="phi used by the rates")
    ax2.set_ylabel("real-contact fraction", color="tab:red")
    ax2.legend(fontsize=6, loc="center right")


def _draw_runin_psd(ax, result, run) -> None:
    d = _runin(result)
    k = d["k"]
    n = d["psd"].shape[0]
    for i in sorted({0, n // 2, n - 1}):
        (line,) = ax.loglog(
            k,
            d["psd"][i],
            ".",
            ms=2,
            label=f"checkpoint {i}: {d['sliding_distance_m'][i] * 1e3:.3g} mm",
        )
        ax.loglog(k, d["psd_theory"][i], "-", lw=0.8, color=line.get_color())
    ax.set_xlabel("k (1/m)")
    ax.set_ylabel("radial PSD (m^4)")
    ax.legend(fontsize=6, title="dots: surface, lines: Eq. 23 expectation", title_fontsize=6)


def _draw_runin_stiffness(ax, result, run) -> None:
    d = _runin(result)
    s = d["sliding_distance_m"] * 1e3
    ax.semilogy(
        s,
        d["normal_stiffness_N_m"],
        "o-",
        ms=3,
        label="apparent contact (interface + punch in series)",
    )
    ax.axhline(
        float(d["bound_N_m"]), color="k", ls="--", lw=0.8, label="bonded punch 2E*sqrt(A/pi)"
    )
    ax.set_xlabel("sliding distance (mm)")
    ax.set_ylabel("normal stiffness (N/m)")
    ax.legend(fontsize=6)


def _draw_runin_mu(ax, result, run) -> None:
    d = _runin(result)
    ax.plot(
        d["sliding_distance_m"] * 1e3,
        d["mu"],
        "o-",
        ms=3,
        label="mu_k at the matched MCA condition",
    )
    fr = result.values.get("friction") or {}
    if fr.get("mu_static") is not None:
        ax.axhline(float(fr["mu_static"]), color="k", ls="--", lw=0.8, label="mu_s (stated)")
    ax.set_xlabel("sliding distance (mm)")
    ax.set_ylabel("friction coefficient")
    ax.legend(fontsize=6)


def running_in_mode(scene) -> bool:
    """Say whether the topography stage evolves the part's own surface (rough, with [roughness])."""
    return (
        scene.topography is not None
        and scene.roughness is not None
        and scene.geometry.profile == "rough"
    )


_RUNIN_SECTIONS = (
    "roughness",
    "running_in",
    "load",
    "geometry",
    "material",
    "counter_material",
    "contact",
)


class Topography(Stage):
    """Eq. 23 surface evolution with the nanoscale rates.

    Without them, with ``[rates]`` or the ``[topography]`` values.
    """

    name = "topography"
    produces = (
        Handoff(
            "surface",
            units={"heights": "m", "pixel_size": "m"},
            doc="surface.npy (+ surface.json sidecar): evolved height map",
        ),
        Handoff(
            "psd",
            units={"k": "1/m", "psd": "m^(d+2)", "psd_theory": "m^(d+2)"},
            doc="psd.npz: PSD against Eq. 23 theory",
        ),
        Handoff(
            "running_in",
            file="running_in",
            units={
                "sliding_distance_m": "m",
                "time_s": "s",
                "rq_m": "m",
                "normal_stiffness_N_m": "N/m",
                "real_area_fraction": "1",
                "mu": "1",
            },
            doc="running_in.json + runin.npz: the part's surface, "
                "contact and friction over the sliding distance",
        ),
    )
    consumes = ("rates",)
    outputs = ("topography",)
    # The running-in reads the shipped nanoscale table: a rebuilt table invalidates cached results.
    data = ("data/nanoscale_table.json",)
    sections = ("topography", "kinematics", "rates") + _RUNIN_SECTIONS
    # Issue 15 contract: the running-in series of the part, at the top level of report.json.
    report_keys = ("running_in",)
    figures = (
        Figure(
            "psd",
            "psd",
            _draw_psd,
            "topography PSD (cf. Fig. 10)",
            "Power spectral density of the evolved topography "
            "against the Eq. 23 theory (cf. Fig. 10)",
        ),
        Figure(
            "runin_rq",
            "runin",
            _draw_runin_rq,
            "running-in: Rq and real-contact fraction",
            "Running-in of the part's surface: Rq and the "
            "real-contact fraction (BEM; dashed: phi used by the "
            "rates) against sliding distance",
        ),
        Figure(
            "runin_psd",
            "runin",
            _draw_runin_psd,
            "running-in: PSD at checkpoints vs Eq. 23",
            "Radial PSD of the part's surface at checkpoints "
            "(dots) against the Eq. 23 expectation for the same "
            "coefficients (lines)",
        ),
        Figure(
            "runin_stiffness",
            "runin",
            _draw_runin_stiffness,
            "running-in: apparent-contact stiffness",
            "Normal stiffness of the apparent contact against "
            "sliding distance, below the bonded-punch bound",
        ),
        Figure(
            "runin_mu",
            "runin",
            _draw_runin_mu,
            "running-in: friction coefficient",
            "Friction coefficient at the MCA condition "
            "matched to the part, against sliding distance",
        ),
    )

    def plan(self, scene, demand: Demand) -> Decision:
        """Evolve only with a ``[topography]`` section.

        When requested or when contact wants the surface.
        """
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
        why = (
            "outputs request 'topography'"
            if demand.requested("topography")
            else "the evolved surface feeds contact"
        )
        if running_in_mode(scene):
            # Issue 15: the part's own [roughness] surface runs in, coupled
            # to the contact at every checkpoint.
            c = scene.contact
            if c.method == "auto":
                import json

                from ...environment import data_path
                from ...models.contact.choice import choose_method, reduced_pressures_of_scene

                # The same measured table and rule as the contact stage (no stage imports another).
                table = demand.overrides.get("contact_table")
                if table is None:
                    try:
                        table = json.loads(data_path("contact_speed_error.json").read_text())
                    except (OSError, ValueError):
                        table = None
                choice = choose_method(
                    c.tolerance, table, reduced_pressures=reduced_pressures_of_scene(scene)
                )
                method, mwhy = choice["method"], "auto: " + choice["why"]
            else:
                method, mwhy = c.method, f"method '{c.method}' set in [contact]"
            return self.go(
                "the part's [roughness] surface runs in over "
                f"[kinematics].duration, {method.upper()} contact "
                f"at every checkpoint; {why}",
                sections=("topography", "kinematics") + _RUNIN_SECTIONS,
                options={
                    "running_in": True,
                    "contact_method": method,
                    "contact_method_reason": mwhy,
                },
                wants=("rates",),
            )
        return self.go(why, sections=("topography", "kinematics"), wants=("rates",))

    def bind(self, scene, decision: Decision, supplied) -> Decision:
        """Name the rates' source; ``[rates]`` joins the hashed sections when it is the source."""
        from dataclasses import replace

        if "rates" in supplied:
            rsrc, src, secs = "measured by nanoscale", "nanoscale", decision.sections
        elif scene.rates is not None:
            rsrc, src, secs = "given in [rates]", "scene", decision.sections + ("rates",)
        else:
            rsrc, src, secs = (
                "[topography] values (no rates in the scene)",
                "topography",
                decision.sections,
            )
        return replace(
            decision,
            reason=f"Eq. 23 with rates {rsrc}; {decision.reason}",
            sections=secs,
            options={**decision.options, "rates_source": src},
        )

    def preflight(self, scene, decision: Decision) -> list[str]:
        """Check the Eq. 23 grid against this machine's memory; note the evolution's cost."""
        if decision.options.get("running_in"):
            # Running-in evolves the part's own [roughness] map (2D), with a
            # contact solve per checkpoint.
            n, dim, field = scene.roughness.grid_points, 2, "[roughness].grid_points"
            what = "the running-in surface (Eq. 23 + contact per checkpoint)"
            method = decision.options.get("contact_method")
            note = f"running-in of the {n}^2 [roughness] map, {method} contact"
            return self._memory(scene, n, dim, field, what) or [note]
        t = scene.topography
        self._memory(
            scene, t.grid_points, t.dim, "[topography].grid_points", f"a {t.dim}D Eq. 23 grid"
        )
        # ~90 ns per point-step measured from 2^10 to 2^20 points (same benchmark).
        seconds = 90e-9 * float(t.grid_points) ** t.dim * t.steps
        return (
            [f"Eq. 23 on {t.grid_points}^{t.dim} points x {t.steps} steps: ~{seconds:.2g} s"]
            if seconds > 10
            else []
        )

    @staticmethod
    def _memory(scene, n: int, dim: int, field: str, what: str) -> list[str]:
        from ...resources import check_memory

        # The exact scheme keeps ~5 grid arrays of float64 (benchmarks/topography_speed_vs_error.py:
        # 5.0 grid arrays at 1024^2), plus the saved map and its PSD.
        check_memory(7 * 8 * float(n) ** dim, field, n, what, scene.source)
        return []

    def summary(self, values) -> list[str]:
        """Say where the running-in rates, surface, contact and friction came from (issue 15)."""
        if "running_in" not in values:
            return []
        ri = values["running_in"]
        fr = values.get("friction") or {}
        eq = values.get("eq23_mca") or {}
        warn = " ".join(values.get("eq23_warnings") or [])
        k_n = ri["normal_stiffness_N_m"]
        factor = ri["rate_factor"]
        extra = f"; **extrapolated**: {fr.get('extrapolation')}" if fr.get("extrapolated") else ""
        out = [
            f"- **Rates** from {values.get('rates_source')}: Eq. 23 coefficients "
            f"{values.get('eq23_source')} at the MCA's V = {fmt(eq.get('velocity_m_s'))} m/s, "
            f"P = {fmt(eq.get('pressure_Pa'))} Pa (k1 = {fmt(eq.get('k1'))}, "
            f"k2 = {fmt(eq.get('k2'))} 1/m). {warn}".rstrip(),
            "- **At the part** every rate is multiplied by phi V_part / V_MCA (processes scale "
            f"with the distance slid in contact; factor {fmt(factor[0])} at the start, "
            f"{fmt(factor[-1])} at the end) and the noise intensities by the slab thickness "
            f"w = {fmt(values.get('slab_thickness_m'))} m ({values.get('slab_thickness_source')}) "
            "to go from the MCA's 1D profile to the 2D surface.",
            f"- **Surface**: {values.get('surface_source')}, "
            f"side {fmt(values.get('domain_size_m'))} m; "
            f"Rq {fmt(values.get('rq_initial_m'))} -> {fmt(values.get('rq_final_m'))} m over "
            f"{fmt(values.get('sliding_distance_m'))} m of sliding in {ri.get('checkpoints')} "
            f"checkpoints ({ri.get('substeps')} Eq. 23 sub-steps, phi changing by at most the "
            "stated tolerance per sub-step).",
            f"- **Contact** at every checkpoint: {ri.get('contact_method')} "
            f"({values.get('contact_method_reason')}); "
            f"real-contact fraction: {ri.get('phi_source')}.",
            "- **Stiffness** of the apparent contact: interfacial stiffness per area x A in series "
            f"with the bonded punch 2E*sqrt(A/pi) = {fmt(ri.get('bound_N_m'))} N/m (the bound); "
            f"{fmt(k_n[0])} -> {fmt(k_n[-1])} N/m.",
            f"- **Friction**: mu_k = {fmt(fr.get('mu_kinetic'))}, "
            f"mu_s = {fmt(fr.get('mu_static'))} "
            f"({fr.get('source')}); matched at the {fr.get('pressure_source')} pressure "
            f"{fmt(fr.get('pressure_Pa'))} Pa{extra}.",
        ]
        conv = ri.get("convergence")
        if conv:
            n0, n1 = conv["checkpoints"]
            out.append(
                f"- **Convergence**: halving the checkpoint spacing ({n0} -> {n1}) changes "
                f"the final Rq by {fmt(conv['rq_final_rel_change'])} and the stiffness by "
                f"{fmt(conv['stiffness_final_rel_change'])} (relative)."
            )
        return out

    def run(self, ctx: StageContext) -> StageOutput:
        """Eq. 23 with the upstream rates -> final height map and its PSD.

        The height map is ``surface.npy`` with a sidecar JSON.
        """
        if ctx.plan.options.get("running_in"):
            return _running_in(ctx)
        from ...models import topography as topo

        rates, rates_src = upstream_rates(ctx)
        params = topo.params_from_scene(ctx.scene, rates=rates)
        res = topo.evolve(
            params, rng=ctx.rng, scheme=ctx.scene.topography.scheme, progress=ctx.progress
        )
        topo.save_height_map(ctx.workdir / "surface.npy", res.h, params.pixel_size)
        np.savez(ctx.workdir / "psd.npz", k=res.k, psd=res.psd, psd_theory=res.psd_theory)
        files = {"surface": "surface.npy", "psd": "psd.npz"}
        if (ctx.workdir / "surface.json").exists():
            files["surface_meta"] = "surface.json"
        if (ctx.workdir / "rates.json").exists():
            files["rates"] = "rates.json"
        # Bookkeeping fields (method, message, wall time, counters) go to
        # the record, not the numbers.
        values = {
            k: v
            for k, v in scalars(res).items()
            if k not in ("status", "method", "message", "time_s", "nit", "history")
        }
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


def _fallback_from_topography(scene, slab: float) -> dict:
    """Return the scene's ``[topography]`` Eq. 23 values in the 1D C1 names.

    These are not measured by the MCA.
    """
    from ...models.topography.rates import topography_fallback
    from ...scene.schema import Topography as TopoSection

    return topography_fallback(scene.topography or TopoSection(), slab)


def _eq23_from_table(table, pressure: float, velocity: float, v_ref) -> tuple[dict | None, dict]:
    """Return the table's Eq. 23 coefficients at the part's condition, in C1 units at ``v_ref``.

    Each coefficient is interpolated by :func:`tribolmp.models.bridges.table_at_part` (rows that
    measured it validly, nearest velocity, log p and log value) and moved from its row's velocity to
    ``v_ref`` (the velocity of the rates they complete) per sliding distance, the same assumption as
    ``rates_at_part``.  Returns ``(mapping for eq23_from_rates or None, {coefficient: lookup}})``.
    """
    from ...models import bridges

    if not table:
        return None, {}
    out, hits = {}, {}
    for key in ("mu_per_s", "d0_m2_s", "dz", "dx_l2"):
        t = bridges.table_at_part(
            table, key, pressure_Pa=pressure, velocity_m_s=velocity, log_values=True
        )
        if t is None:
            continue
        scale = float(v_ref) / t.velocity_m_s if v_ref else 1.0
        out[key] = t.value * scale
        hits[key] = {"value_at_table_velocity": t.value, "table_velocity_m_s": t.velocity_m_s,
                     "extrapolated": t.extrapolated, "extrapolation": t.extrapolation}
    if not out:
        return None, {}
    out["source"] = "nanoscale table (tribolmp/data/nanoscale_table.json)"
    return out, hits


def _coefficient_provenance(
    eq, rates_tier: str, table_hits: dict, fr, mu_tier: str, ri, rates
) -> dict:
    """Say, per coefficient, which tier of the precedence gave it (report.json provenance)."""
    out = {}
    for key, short in (("mu_per_s", "mu"), ("d0_m2_s", "d0"), ("dz", "dz"), ("dx_l2", "dx_l2")):
        src = eq.sources[short]
        tier = ("nanoscale table" if src.startswith("nanoscale table")
                else "[topography] fallback" if src.startswith("[topography]") else rates_tier)
        row = {"tier": tier, "source": src, "value": eq[short]}
        if tier == "nanoscale table":
            row.update(table_hits.get(key, {}))
        out[key] = row
    src_k, _, src_s = str(fr["source"]).partition("; mu_s: ")
    k_tier = ("scene [running_in].mu_kinetic" if ri.mu_kinetic is not None
              else rates_tier + " (mu_kinetic)" if rates.mu_kinetic is not None else mu_tier)
    out["mu_kinetic"] = {
        "tier": k_tier,
        "source": src_k.removeprefix("mu_k: "),
        "value": fr["mu_kinetic"],
        "extrapolated": fr["extrapolated"],
        "extrapolation": fr["extrapolation"],
    }
    s_tier = ("scene [running_in].mu_static" if ri.mu_static is not None
              else rates_tier + " (mu_static)" if rates.mu_static is not None
              else "nanoscale table (mu_s/mu_k)" if "nanoscale table" in src_s
              else "scene [running_in].static_ratio (stated assumption)")
    out["mu_static"] = {"tier": s_tier, "source": src_s, "value": fr["mu_static"]}
    return out


#: Fields of a Rates record that feed Eq. 23 (the C1 coefficients and the legacy rates the
#: block picture maps to them); all are measurements on the MCA's own profile.
_MCA_EQ23_FIELDS = ("mu_per_s", "d0_m2_s", "dz", "dx_l2", "wear_rate", "diffusion_m2_s",
                    "transfer_rate", "detachment_rate", "reattachment_rate")


def part_coefficients(scene, rates, rates_src: str, table, h0, dx: float, params, slab: float,
                      *, run_length: float | None = None, table_length: float | None = None):
    """Choose every coefficient of the running-in at the part, by the precedence of issue 15.

    Per coefficient: the scene's ``[rates]`` (``rates_src == "[rates]"``) > this run's valid
    measurement (the nanoscale ``rates.json``; a C1 coefficient marked not valid or null is not one)
    > the shipped nanoscale ``table`` at the part's condition (nominal pressure, or the mean
    real-contact pressure ``p/phi`` with ``phi`` estimated on ``h0``, as ``[running_in]`` says) >
    the ``[topography]`` values.  mu_k: ``[running_in].mu_kinetic`` > the rates' mu > the table >
    ``[load]``; mu_s: ``[running_in].mu_static`` > the rates' > the table's measured mu_s/mu_k x
    mu_k > the stated ``static_ratio``.

    The Eq. 23 coefficients measured on an MCA profile (this run's, of length ``run_length``;
    the table's, of length ``table_length``, both in m) are used only when the part's map
    resolves a wavelength the MCA measured (:func:`tribolmp.models.bridges.mca_band_applies`);
    otherwise that tier is skipped, and ``eq.warnings`` and the provenance say why.  The scene's
    ``[rates]`` are the user's statement for the part and are always used.

    Returns
    -------
    eq : Result
        The Eq. 23 coefficients (:func:`~tribolmp.models.bridges.eq23_from_rates`).
    friction : callable
        ``phi -> Result``: the friction at the part for a real-contact fraction ``phi``.
    provenance : callable
        ``friction Result -> {coefficient: {tier, source, value, ...}}``.
    fr_src : str
        Source of the friction coefficient (the rates, the shipped table or ``[load]``).
    """
    from ...models import bridges
    from ...scene.schema import RunningIn

    ri = scene.running_in or RunningIn()
    rates_tier = (
        "scene [rates]" if rates_src == "[rates]" else "measured by this run (nanoscale rates.json)"
    )
    v_part = max(params.sliding_velocity, 1e-300)
    # The part's matching pressure: nominal, or the mean real-contact pressure p/phi with phi
    # estimated from the initial surface (the Eq. 23 coefficients are taken once, before the loop).
    phi0 = bridges.contact_fraction_estimate(
        params.pressure, params.E_star, bridges.rms_gradient(h0, dx)
    )
    p_match = (
        params.pressure
        if ri.friction_pressure == "nominal"
        else params.pressure / max(phi0, 1e-300)
    )
    not_used: dict[str, str] = {}
    rates_eq = rates
    if rates_src != "[rates]":
        band = bridges.mca_band_applies(dx, run_length)
        if not band.applies and any(getattr(rates, f) is not None for f in _MCA_EQ23_FIELDS):
            rates_eq = dataclasses.replace(rates, **dict.fromkeys(_MCA_EQ23_FIELDS))
            not_used[rates_tier] = band.reason
    table_eq = table
    if table:
        band = bridges.mca_band_applies(dx, table_length)
        if not band.applies:
            table_eq = None
            not_used["nanoscale table"] = band.reason
    eq23_table, table_hits = _eq23_from_table(
        table_eq, p_match, v_part, rates.sliding_velocity_m_s
    )
    eq = bridges.eq23_from_rates(
        rates_eq, table=eq23_table, fallback=_fallback_from_topography(scene, slab)
    )
    for tier, why in not_used.items():
        eq.warnings.append(f"Eq. 23 coefficients of the {tier} not used at the part: {why}")
    rates_mu = rates.mu if rates.mu is not None and "mu" not in rates.flagged else None
    if rates_mu is not None:
        rows = [
            {
                "pressure_Pa": eq.pressure_Pa or params.pressure,
                "sliding_velocity_m_s": eq.velocity_m_s,
                "mu": float(rates_mu),
            }
        ]
        fr_src, mu_tier = rates_src, rates_tier
    elif table is not None:
        rows, fr_src, mu_tier = table, "tribolmp/data/nanoscale_table.json", "nanoscale table"
    else:
        rows = [
            {
                "pressure_Pa": eq.pressure_Pa or params.pressure,
                "sliding_velocity_m_s": eq.velocity_m_s or v_part,
                "mu": float(scene.load.friction_coefficient),
            }
        ]
        fr_src, mu_tier = (
            "[load].friction_coefficient (no measured mu)",
            "[load].friction_coefficient",
        )
    mu_s_given = ri.mu_static if ri.mu_static is not None else rates.mu_static
    mu_k_given = ri.mu_kinetic if ri.mu_kinetic is not None else rates.mu_kinetic

    def friction(phi: float):
        p = (
            params.pressure
            if ri.friction_pressure == "nominal"
            else params.pressure / max(phi, 1e-300)
        )
        return bridges.friction_at_part(
            rows,
            pressure_Pa=p,
            velocity_m_s=v_part,
            mu_static=mu_s_given,
            mu_kinetic=mu_k_given,
            static_ratio=ri.static_ratio,
            pressure_source=ri.friction_pressure,
            table=table,
        )

    def provenance(fr) -> dict:
        out = _coefficient_provenance(eq, rates_tier, table_hits, fr, mu_tier, ri, rates)
        for key in bridges.C1_FIELDS:
            if not_used:
                out[key]["not_used"] = dict(not_used)
        return out

    return eq, friction, provenance, fr_src


def _running_in(ctx: StageContext) -> StageOutput:
    """Run in the part's [roughness] surface by Eq. 23, coupled to the contact (issue 15)."""
    from ...environment import data_path
    from ...jsonio import atomic_write_json, jsonable
    from ...models import bridges, runin
    from ...models.topography import save_height_map
    from ...scene.schema import RunningIn

    scene = ctx.scene
    rates, rates_src = upstream_rates(ctx)
    if rates is None:
        raise ValueError("running-in needs nanoscale rates ([nanoscale] or [rates])")
    ri = scene.running_in or RunningIn()
    # Slab thickness of the 2D MCA: given, else the automaton diameter of
    # the run, else the step length.
    if rates.slab_thickness_m:
        slab, slab_src = rates.slab_thickness_m, "rates slab_thickness_m"
    elif rates.automaton_diameter_m:
        slab, slab_src = (
            rates.automaton_diameter_m,
            "rates automaton_diameter_m (one automaton thick)",
        )
    elif scene.nanoscale is not None:
        slab, slab_src = scene.nanoscale.automaton_diameter, "[nanoscale].automaton_diameter"
    elif rates.step_length_m:
        slab, slab_src = rates.step_length_m, "step_length_m (one automaton)"
    else:
        raise ValueError(
            "rates: slab_thickness_m, automaton_diameter_m "
            "or step_length_m is needed for the 2D surface"
        )
    method = ctx.plan.options.get("contact_method", "mdr")
    rough = scene.roughness
    surf_rng, noise_rng = ctx.rng.spawn(2)
    h0, dx, surf_src = runin.part_surface(
        rms_height=rough.rms_height,
        hurst=rough.hurst,
        rolloff_wavelength=rough.rolloff_wavelength,
        short_cutoff_wavelength=rough.short_cutoff_wavelength,
        grid_points=rough.grid_points,
        pixel_size=rough.pixel_size,
        rng=surf_rng,
        surface_file=rough.surface_file,
        surface_options={
            "pixel_size": rough.surface_pixel_size or None,
            "unit": rough.surface_unit or None,
            "detrend": rough.surface_detrend,
            "missing": rough.surface_missing,
        },
    )
    geo = scene.geometry
    area = geo.apparent_length * geo.apparent_width
    seed = int(ctx.seed[-1]) if ctx.seed else 0
    params = runin.RunInParams(
        duration=scene.kinematics.duration, sliding_velocity=scene.kinematics.sliding_velocity,
        normal_force=scene.load.normal_force, apparent_area=area, E_star=scene.effective_modulus,
        checkpoints=ri.checkpoints, slab_thickness=float(slab), contact_method=method,
        realizations=rough.realizations, contact_seed=seed, phi_tolerance=ri.phi_tolerance)
    table_path = data_path("nanoscale_table.json")
    table = bridges.load_nanoscale_table(table_path) if table_path.is_file() else None
    table_length = bridges.nanoscale_table_profile_length(table_path) if table else None
    # this run's MCA profile spans its periodic box
    run_length = scene.nanoscale.box_length if scene.nanoscale is not None else None
    eq, friction, provenance, fr_src = part_coefficients(
        scene, rates, rates_src, table, h0, dx, params, float(slab),
        run_length=run_length, table_length=table_length,
    )

    res = runin.running_in(
        h0, dx, eq, params, rng=noise_rng, mu_of_phi=lambda phi: friction(phi)["mu_kinetic"]
    )
    ctx.progress(
        0.5, "running-in done; convergence check" if ri.convergence_check else "running-in done"
    )
    fr = friction(res.phi[-1])
    conv = (
        runin.checkpoint_convergence(h0, dx, eq, params, seed=seed, coarse=res)
        if ri.convergence_check
        else None
    )
    w = ctx.workdir
    save_height_map(w / "surface.npy", res.h, dx)
    np.save(w / "initial_surface.npy", h0)
    np.savez(w / "psd.npz", k=res.k, psd=res.psd[-1], psd_theory=res.psd_theory[-1])
    np.savez(
        w / "runin.npz",
        k=res.k,
        psd=res.psd,
        psd_theory=res.psd_theory,
        sliding_distance_m=np.asarray(res.sliding_distance_m),
        rq_m=np.asarray(res.rq_m),
        normal_stiffness_N_m=np.asarray(res.normal_stiffness_N_m),
        phi=np.asarray(res.phi),
        real_area_fraction=np.array([np.nan if a is None else a for a in res.real_area_fraction]),
        mu=np.asarray(res.mu, float),
        bound_N_m=res.bound_N_m,
    )
    running = {
        k: jsonable(list(res[src]))
        for k, src in (
            ("sliding_distance_m", "sliding_distance_m"),
            ("time_s", "sliding_time_s"),
            ("rq_m", "rq_m"),
            ("normal_stiffness_N_m", "normal_stiffness_N_m"),
            ("real_area_fraction", "real_area_fraction"),
            ("mu", "mu"),
        )
    }
    running.update(
        phi_used=[float(x) for x in res.phi],
        phi_source=res.phi_source,
        contact_method=method,
        rate_factor=[float(x) for x in res.rate_factor],
        bound_N_m=float(res.bound_N_m),
        checkpoints=params.checkpoints,
        substeps=int(res.substeps),
    )
    if conv is not None:
        running["convergence"] = {
            "checkpoints": list(conv.checkpoints),
            "rq_final_rel_change": float(conv.rq_delta),
            "stiffness_final_rel_change": float(conv.stiffness_delta),
        }
    atomic_write_json(w / "running_in.json", running)
    corr = bridges.correlation_length(res.h, dx)
    values = {
        "dim": 2,
        "domain_size_m": float(res.domain_size_m),
        "pixel_size_m": float(dx),
        "grid_points": int(res.h.shape[0]),
        "rq_initial_m": float(res.rq_initial_m),
        "rq_final_m": float(res.rq_final_m),
        "rq": float(res.rq_final_m),
        "correlation_length_m": corr if np.isfinite(corr) else None,
        "surface_source": surf_src,
        "sliding_distance_m": params.sliding_velocity * params.duration,
        "duration_s": params.duration,
        "rates_source": rates_src,
        "eq23_source": eq.source,
        "eq23_sources": dict(eq.sources),
        "eq23_warnings": list(eq.warnings),
        "shape_fixed_by_identity": bool(eq.shape_fixed_by_identity),
        "eq23_mca": jsonable(
            {
                k: eq[k]
                for k in ("mu", "d0", "dz", "dx_l2", "k1", "k2", "velocity_m_s", "pressure_Pa")
            }
        ),
        "k1": jsonable(eq.k1),
        "k2": jsonable(eq.k2),
        "slab_thickness_m": float(slab),
        "slab_thickness_source": slab_src,
        "contact_method": method,
        "contact_method_reason": ctx.plan.options.get("contact_method_reason"),
        "phi_source": res.phi_source,
        "running_in_warnings": list(res.warnings),
        "contact_pixels_min": res.contact_pixels_min,
        "friction": jsonable(
            {
                k: fr[k]
                for k in (
                    "mu",
                    "mu_kinetic",
                    "mu_static",
                    "extrapolated",
                    "extrapolation",
                    "pressure_Pa",
                    "pressure_source",
                    "source",
                    "velocity_table",
                )
            }
        ),
        "friction_table_source": fr_src,
        "coefficient_provenance": jsonable(provenance(fr)),
        "running_in": running,
    }
    units = {
        "domain_size_m": "m",
        "pixel_size_m": "m",
        "rq_initial_m": "m",
        "rq_final_m": "m",
        "rq": "m",
        "correlation_length_m": "m",
        "sliding_distance_m": "m",
        "duration_s": "s",
        "slab_thickness_m": "m",
        "k1": "1/m",
        "k2": "1/m",
    }
    files = {
        "surface": "surface.npy",
        "surface_meta": "surface.json",
        "initial_surface": "initial_surface.npy",
        "psd": "psd.npz",
        "runin": "runin.npz",
        "running_in": "running_in.json",
    }
    if (w / "rates.json").exists():
        files["rates"] = "rates.json"
    return StageOutput(
        values=values,
        units=units,
        files=files,
        method=res.method,
        message=res.message,
        nit=int(res.substeps),
        provenance={"coefficients": values["coefficient_provenance"]},
    )


STAGE = Topography()
