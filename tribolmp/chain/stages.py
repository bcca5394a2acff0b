"""The six stages of the chain: thin adapters from scene + upstream hand-off files to model calls.

Each stage function takes a :class:`StageContext` and returns a
:class:`StageOutput` (numbers in SI with their units, plus the hand-off files
it wrote into ``ctx.workdir``).  No physics lives here: every number comes from
a model package, imported (plainly) inside the stage function so that a scene
imports only the models it needs.
"""

from __future__ import annotations

import json
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..scene import Scene
from ..jsonio import atomic_write_json, scalars
from .cache import CachedStage
from .planner import StagePlan

__all__ = ["StageContext", "StageOutput", "STAGE_FUNCS"]


@dataclass
class StageContext:
    """Everything a stage may use: the scene, its plan, a working folder, upstream results, an RNG."""

    scene: Scene
    plan: StagePlan
    workdir: Path
    upstream: dict[str, CachedStage]
    rng: np.random.Generator
    seed: list[int]
    progress: Callable[..., None] = lambda frac, what="": None


@dataclass
class StageOutput:
    """What a stage hands on: SI numbers with units and files (names relative to the workdir)."""

    values: dict[str, Any]
    units: dict[str, str] = field(default_factory=dict)
    files: dict[str, str] = field(default_factory=dict)
    method: str = ""
    message: str = ""
    nit: int = 0
    provenance: dict[str, Any] = field(default_factory=dict)


def _rates_from_upstream(ctx: StageContext) -> tuple[dict[str, Any] | None, str]:
    """The rates dict and where it came from: nanoscale's rates.json, the scene's [rates], or none."""
    if "nanoscale" in ctx.upstream:
        up = ctx.upstream["nanoscale"]
        return json.loads(up.file("rates").read_text()), f"nanoscale stage {up.key} (rates.json)"
    if ctx.scene.rates is not None:
        # The shared record (tribolmp.records.Rates); the hand-off is a file even when the scene
        # gives the rates, so every stage reads rates the same way.
        rates = {k: v for k, v in ctx.scene.rates.to_record().to_dict().items() if v is not None}
        atomic_write_json(ctx.workdir / "rates.json", rates)
        return rates, "[rates]"
    return None, ""


def _friction_coefficient(ctx: StageContext) -> tuple[float, str]:
    """mu from nanoscale / [rates] when present, else [load].friction_coefficient."""
    rates, src = _rates_from_upstream(ctx)
    if rates is not None and rates.get("mu") is not None:
        return float(rates["mu"]), src
    return ctx.scene.load.friction_coefficient, "[load].friction_coefficient"


STAGE_FUNCS: dict[str, Callable[[StageContext], StageOutput]] = {}


def _stage(name: str):
    def deco(func):
        STAGE_FUNCS[name] = func
        return func

    return deco


# ---------------------------------------------------------------- nanoscale


class _watch_progress:
    """Report a LAMMPS run's progress from the simulated time in the last line of ``friction.csv``.

    A daemon thread reads only the file's tail every ``interval`` s, so it costs
    nothing measurable and never touches the LAMMPS session.
    """

    def __init__(self, path: Path, duration: float, report: Callable[..., None], interval: float = 2.0):
        import threading

        self.path, self.duration, self.report, self.interval = path, duration, report, interval
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)

    def _last_time(self) -> float | None:
        try:
            with open(self.path, "rb") as fh:
                fh.seek(0, 2)
                fh.seek(max(0, fh.tell() - 256))
                line = fh.read().decode(errors="ignore").strip().splitlines()[-1]
            return float(line.split(",")[0])
        except (OSError, ValueError, IndexError):
            return None

    def _run(self) -> None:
        while not self._stop.wait(self.interval):
            t = self._last_time()
            if t is not None and self.duration > 0:
                self.report(t / self.duration, f"simulated {t * 1e9:.2f} of {self.duration * 1e9:.2f} ns")

    def __enter__(self):
        self._thread.start()
        return self

    def __exit__(self, *exc):
        self._stop.set()
        self._thread.join(timeout=5)


@_stage("nanoscale")
def nanoscale(ctx: StageContext) -> StageOutput:
    """LAMMPS MCA friction run -> ``rates.json`` (plus friction.csv, trajectory, meta.json)."""
    from ..errors import LammpsError
    from ..rng import lammps_seed

    from ..lammps import mca
    params = mca.params_from_scene(ctx.scene)
    out = ctx.workdir / "mca"
    # An interrupted run left restart files in the (kept) partial folder: continue from them.
    resume = out.is_dir() and any(out.iterdir())
    seed = lammps_seed(ctx.rng)
    discarded: list[str] = []
    with _watch_progress(out / "friction.csv", params.duration, ctx.progress):
        while True:
            try:
                res = mca.run_mca(params, out, seed=seed, resume=resume, np=ctx.scene.nanoscale.ranks)
                break
            except LammpsError as exc:
                restarts = mca.restart_files(out) if resume and hasattr(mca, "restart_files") else []
                if not restarts or "restart" not in str(exc).lower():
                    raise
                # A kill while LAMMPS was writing a restart file leaves it truncated: drop that
                # file and continue from the previous one (or from the start when none is left).
                newest = max(restarts)[1]
                discarded.append(newest.name)
                newest.unlink()
                resume = bool(mca.restart_files(out))
    rates_path = out / "rates.json"
    if not rates_path.exists():
        raise RuntimeError(f"run_mca finished without writing {rates_path.name}")
    rates = json.loads(rates_path.read_text())
    meta = json.loads((out / "meta.json").read_text()) if (out / "meta.json").exists() else {}
    values = {k: v for k, v in scalars(rates).items()}
    values["meta"] = scalars(meta)
    files = {"rates": "mca/rates.json"}
    for key, name in (("friction", "friction.csv"), ("traj", "traj.lammpstrj"), ("meta", "meta.json"), ("log", "run.log")):
        if (out / name).exists():
            files[key] = f"mca/{name}"
    units = dict(rates.get("units", {}))
    return StageOutput(
        values=values,
        units=units,
        files=files,
        method=str(res.get("method", "mca")),
        message=str(res.get("message", "")),
        nit=int(res.get("nit", 0) or 0),
        provenance={"lammps_seed_from": ctx.seed, "resumed": resume, "discarded_restarts": discarded, "params": scalars(dict(vars(params))),
                    "rates_provenance": rates.get("provenance", {}), "warnings": rates.get("warnings", [])},
    )


# --------------------------------------------------------------- topography


@_stage("topography")
def topography(ctx: StageContext) -> StageOutput:
    """Eq. 23 with the upstream rates -> final height map (``surface.npy`` + sidecar JSON) and its PSD."""
    from ..models import topography as topo
    rates, rates_src = _rates_from_upstream(ctx)
    params = topo.params_from_scene(ctx.scene, rates=rates)
    res = topo.evolve(params, rng=ctx.rng, scheme=ctx.scene.topography.scheme)
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


# -------------------------------------------------------------- lubrication


@_stage("lubrication")
def lubrication(ctx: StageContext) -> StageOutput:
    """Squeeze-force summary of the film (reduced damper vs Reynolds/Brenner) and, with [polishing], polishing."""
    from ..models.lubrication import summary as summ
    res = summ.lubrication_summary(ctx.scene)
    gap = np.asarray(res.gap)
    film = ctx.scene.lubricant.film_thickness
    i = int(np.argmin(np.abs(gap - film)))  # the summary includes the scene's film thickness
    curves: dict[str, Any] = {"x": gap, "x_label": "gap h (m)", "damper": res.force_damper, "Reynolds": res.force_reynolds}
    if "force_brenner" in res:
        curves["Brenner (exact)"] = res.force_brenner
    np.savez(ctx.workdir / "curves.npz", **curves)
    values: dict[str, Any] = {
        "alpha_N_s": res.alpha,
        "radius_m": res.radius,
        "approach_velocity_m_s": res.velocity,
        "power_law_index": res.power_law_index,
        "film_thickness_m": float(gap[i]),
        "force_damper_N": float(res.force_damper[i]),
        "force_reynolds_N": float(res.force_reynolds[i]),
        "error_damper_vs_reynolds": float(res.error_damper_vs_reynolds[i]),
    }
    units = {"alpha_N_s": "N s", "radius_m": "m", "approach_velocity_m_s": "m/s", "power_law_index": "1",
             "film_thickness_m": "m", "force_damper_N": "N", "force_reynolds_N": "N", "error_damper_vs_reynolds": "1"}
    if "force_brenner" in res:
        values["force_brenner_N"] = float(res.force_brenner[i])
        values["error_damper_vs_stokes"] = float(res.error_damper_vs_stokes[i])
        units.update(force_brenner_N="N", error_damper_vs_stokes="1")
    files = {"curves": "curves.npz"}
    method, message = res.method, res.message
    if ctx.scene.polishing is not None:
        from ..models.lubrication import polishing as pol

        pres = pol.polish(pol.params_from_scene(ctx.scene), rng=ctx.rng)
        np.savez(ctx.workdir / "polishing.npz", t=pres.t, sq=pres.sq, sa=pres.sa, removed_volume=pres.removed_volume)
        np.save(ctx.workdir / "polished.npy", pres.h)
        files.update(polishing="polishing.npz", polished_surface="polished.npy")
        for key in ("removal_rate", "preston_rate", "contact_fraction", "mass_balance_error", "load_error", "pixel_size"):
            values[f"polishing_{key}"] = float(pres[key])
            units[f"polishing_{key}"] = pres.units.get(key, "1")
        values.update(polishing_sq_initial_m=float(pres.sq[0]), polishing_sq_final_m=float(pres.sq[-1]))
        units.update(polishing_sq_initial_m="m", polishing_sq_final_m="m")
        method += f"; polishing {pres.method}"
        message += f"; polishing: {pres.message}"
    return StageOutput(values=values, units=units, files=files, method=method, message=message, nit=int(res.nit))


# ------------------------------------------------------------------ contact


@_stage("contact")
def contact(ctx: StageContext) -> StageOutput:
    """Normal stiffness against load: rough surface (evolved, given or generated) or axisymmetric profile."""
    from ..models.contact.solve import load_surface, rough_params_from_scene, rough_surface, solve_rough

    scene, opts = ctx.scene, ctx.plan.options
    method = opts["method"]
    if scene.geometry.profile != "rough":
        return _contact_axisymmetric(ctx, method)
    import dataclasses

    params = rough_params_from_scene(scene)
    surf_rng, ens_rng = ctx.rng.spawn(2)
    mesh_note = ""
    if "topography" in ctx.upstream:
        h, dx = load_surface(ctx.upstream["topography"].file("surface"))
        source = "evolved surface (topography stage)"
        if opts.get("mesh") is not None:
            mesh_note = f"mesh fixed by the evolved surface ({h.shape[0]} points), not the table's {opts['mesh']}"
    else:
        if opts.get("mesh") is not None and not params.surface_file and method == "bem":
            # The measured table gives the BEM grid for this tolerance: same physical size L, new pixel.
            L = params.grid_points * params.pixel_size
            params = dataclasses.replace(params, grid_points=int(opts["mesh"]), pixel_size=L / int(opts["mesh"]))
            mesh_note = f"BEM grid {opts['mesh']} from the speed-error table (L = {L:g} m)"
        h, dx = rough_surface(params, surf_rng)
        source = f"height map {params.surface_file}" if params.surface_file else "random surface from [roughness]"
    res = solve_rough(
        h, dx, params.modulus, params.pressures, method=method, periodic=params.periodic,
        realizations=params.realizations, rng=ens_rng,
    )
    arrays = {k: np.asarray(res[k]) for k in ("pressure", "force", "stiffness", "approach", "stiffness_q10", "stiffness_q90", "area_fraction") if k in res}
    np.savez(ctx.workdir / "stiffness.npz", q10=arrays.get("stiffness_q10", arrays["stiffness"]),
             q90=arrays.get("stiffness_q90", arrays["stiffness"]), **arrays)
    values: dict[str, Any] = {k: v.tolist() for k, v in arrays.items()}
    values.update(surface=source, grid=int(h.shape[0]), pixel_size_m=float(dx), surface_rms_m=float(np.std(h)),
                  E_star_Pa=float(params.modulus), realizations=int(params.realizations) if method == "mdr" else None,
                  periodic=bool(params.periodic) if method == "bem" else None)
    if mesh_note:
        values["mesh_note"] = mesh_note
    if opts.get("expected_error") is not None:
        values["expected_rel_error"] = opts["expected_error"]
    units = {"pressure": "Pa", "force": "N", "stiffness": "N/m", "approach": "m", "stiffness_q10": "N/m",
             "stiffness_q90": "N/m", "area_fraction": "1", "pixel_size_m": "m", "surface_rms_m": "m", "E_star_Pa": "Pa",
             "expected_rel_error": "1"}
    return StageOutput(values=values, units=units, files={"stiffness": "stiffness.npz"}, method=method,
                       message=f"{method} on {source}, {h.shape[0]}x{h.shape[1]} grid", nit=int(res.get("nit", 0) or 0))


def _contact_axisymmetric(ctx: StageContext, method: str) -> StageOutput:
    """Axisymmetric indenter: force, contact radius and (MDR) stiffness at fractions of the scene's load."""
    import dataclasses

    from ..models.contact.solve import params_from_scene, solve

    base = params_from_scene(ctx.scene)
    if base.normal_force is None:
        raise ValueError("[load].normal_force must be > 0 for a stiffness-vs-load curve of an axisymmetric contact")
    loads = base.normal_force * np.geomspace(0.01, 1.0, 9)
    rows = [solve(dataclasses.replace(base, normal_force=float(F)), method=method) for F in loads]
    arrays = {"force": np.array([r.force for r in rows]), "contact_radius": np.array([r.contact_radius for r in rows]),
              "indentation": np.array([r.indentation for r in rows])}
    if all("stiffness" in r for r in rows):
        arrays["stiffness"] = np.array([r.stiffness for r in rows])
    # The figure's x axis is the nominal (mean contact) pressure F / (pi a^2).
    arrays["pressure"] = arrays["force"] / (np.pi * arrays["contact_radius"] ** 2)
    np.savez(ctx.workdir / "stiffness.npz", **arrays)
    values: dict[str, Any] = {k: v.tolist() for k, v in arrays.items()}
    values.update(profile=ctx.scene.geometry.profile, E_star_Pa=float(base.modulus), springs=int(rows[-1].get("springs", 0)) or None)
    units = {"force": "N", "contact_radius": "m", "indentation": "m", "stiffness": "N/m", "pressure": "Pa", "E_star_Pa": "Pa"}
    files = {"stiffness": "stiffness.npz"} if "stiffness" in arrays else {"contact_curve": "stiffness.npz"}
    return StageOutput(values=values, units=units, files=files, method=method,
                       message=f"{method} {ctx.scene.geometry.profile}, {len(loads)} loads up to {base.normal_force:g} N")


# --------------------------------------------------------------- macroscale


def tangential_stiffness_from_contact(result: CachedStage, scene: Scene) -> tuple[float, str]:
    """Tangential stiffness (N/m) of the scene's apparent contact from the contact stage's table.

    Hand-off conversion only, no new physics: the contact stage gives the normal
    stiffness ``k_n(p)`` of a patch of area ``A_patch`` (``force / pressure``) at
    nominal pressures ``p``.  The interface stiffness per unit area ``k_n / A``
    is intensive, so it is interpolated (log-log) at the macroscale pressure
    ``p = N / A_apparent`` and multiplied by ``A_apparent``; the MDR rule
    ``dk_x / dk_z = G* / E*`` of sticking springs (PHYSICS.md section 2) turns it
    into the tangential stiffness.  Pressures outside the computed range are refused.
    """
    v = result.values
    p = np.asarray(v["pressure"], float)
    k = np.asarray(v["stiffness"], float)
    area_patch = np.asarray(v["force"], float) / p
    geo = scene.geometry
    area = geo.apparent_length * geo.apparent_width
    p_macro = scene.load.normal_force / area
    if not (p.min() <= p_macro <= p.max()):
        from ..errors import ParameterError

        raise ParameterError(
            "[load].normal_force",
            f"a nominal pressure N/(apparent_length*apparent_width) within [load].pressures [{p.min():g}, {p.max():g}] Pa",
            f"{p_macro:g} Pa",
        )
    order = np.argsort(p)
    k_per_area = np.exp(np.interp(np.log(p_macro), np.log(p[order]), np.log((k / area_patch)[order])))
    k_t = float(k_per_area * area * scene.effective_shear_modulus / scene.effective_modulus)
    return k_t, f"contact stage at p = {p_macro:g} Pa over {area:g} m^2, times G*/E*"


@_stage("macroscale")
def macroscale(ctx: StageContext) -> StageOutput:
    """Stick-slip of the rigid body pulled through a spring, on the contact, with the chain's mu."""
    from ..models import macro

    mu, mu_src = _friction_coefficient(ctx)
    # the rough MDR profile (if the scene has one) is drawn from the chain's stream, never silently a sphere
    kw: dict[str, Any] = {"mu": mu, "rng": ctx.rng}
    if ctx.plan.options.get("contact_law") == "stiffness" and "contact" in ctx.upstream:
        kc, kc_src = tangential_stiffness_from_contact(ctx.upstream["contact"], ctx.scene)
        kw["contact_stiffness"] = kc
    else:
        kw["contact_law"] = "mdr"
        kc, kc_src = None, "MDR springs of the [geometry] profile (load dependent)"
    film = bool(ctx.plan.options.get("squeeze_film")) and ctx.scene.lubricant is not None
    if film:
        kw["contact_gap"], hc_src = film_rupture_gap(ctx.scene)
    res = macro.stick_slip_from_scene(ctx.scene, **kw)
    t = np.asarray(res.t)
    np.savez(ctx.workdir / "trajectory.npz", t=t, x=res.x, velocity=res.v, friction=res.drive_force, phase=res.phase)
    slips = [e for e in res.events if str(e.get("to_phase", "")).startswith("slip")]
    values = {
        "mu": mu,
        "mu_source": mu_src,
        "contact_stiffness_N_m": kc,
        "contact_stiffness_source": kc_src,
        "n_transitions": int(res.n_transitions),
        "n_slip_events": len(slips),
        "max_drive_force_N": float(np.max(res.drive_force)),
        "mean_drive_force_N": float(np.mean(res.drive_force)),
        "max_velocity_m_s": float(np.max(res.v)),
        "duration_s": float(t[-1]) if t.size else 0.0,
        "first_slip_time_s": float(slips[0]["t"]) if slips else None,
    }
    units = {"mu": "1", "contact_stiffness_N_m": "N/m", "max_drive_force_N": "N", "mean_drive_force_N": "N",
             "max_velocity_m_s": "m/s", "duration_s": "s", "first_slip_time_s": "s"}
    files = {"trajectory": "trajectory.npz"}
    message = str(res.message)
    if film:
        sq = res.squeeze
        W = ctx.scene.load.normal_force
        fc = np.asarray(sq.contact_force)
        touched = np.flatnonzero(fc > 0.0)
        np.savez(ctx.workdir / "squeeze.npz", t=sq.t, gap=sq.gap, log_gap=sq.log_gap, film_force=sq.film_force,
                 contact_force=fc)
        files["squeeze"] = "squeeze.npz"
        values.update({
            "film_rupture_gap_m": kw["contact_gap"],
            "film_rupture_gap_source": hc_src,
            "time_to_solid_contact_s": float(np.asarray(sq.t)[touched[0]]) if touched.size else None,
            "final_load_share": float(fc[-1] / W),
            "final_gap_m": float(np.asarray(sq.gap)[-1]),
            "squeeze_status": int(sq.status),
            "squeeze_message": str(sq.message),
        })
        units.update({"film_rupture_gap_m": "m", "time_to_solid_contact_s": "s", "final_load_share": "1",
                      "final_gap_m": "m"})
        if sq.status != 0:
            # Not a failure of the chain: the model says the film has not been squeezed out yet
            # (h_c below the indentation the load needs, or too short a run).  Say so, invent nothing.
            message += f"; squeeze film: {sq.message}"
    return StageOutput(values=values, units=units, files=files, method=str(res.method), message=message,
                       nit=int(res.nit))


def film_rupture_gap(scene: Scene) -> tuple[float, str]:
    """Gap ``h_c`` (m) at which the squeeze film ruptures and the solids touch.

    With ``[roughness]``: ``3 * rms_height`` (film-thickness-to-roughness ratio
    Lambda = 3, the usual onset of asperity contact).  Without it the surfaces are
    smooth on the model's scale and the film is taken to rupture at the thickness it
    started with, ``[lubricant].film_thickness`` (solid contact from t = 0, the film
    only shares the load while it is squeezed out).  A choice of the chain, not a model.
    """
    if scene.roughness is not None:
        return 3.0 * scene.roughness.rms_height, "3 x [roughness].rms_height (Lambda = 3)"
    return scene.lubricant.film_thickness, "[lubricant].film_thickness (no [roughness]: film ruptures where it started)"


# -------------------------------------------------------- tribospectroscopy


@_stage("tribospectroscopy")
def tribospectroscopy(ctx: StageContext) -> StageOutput:
    """F^2(a) of the oscillating two-contact probe with the chain's mu, and the fitted length."""
    from ..models import tribospectroscopy as ts

    mu, mu_src = _friction_coefficient(ctx)
    params = ts.params_from_scene(ctx.scene, mu=mu)
    res = ts.solve(params)
    a, f2 = np.asarray(res.amplitude_m), np.asarray(res.force_sq_N2)
    # Fitting the model's own curve must return its input length: a check of the forward/inverse pair.
    fit = ts.fit_length(ts.MeasuredCurve(amplitude=a, value=f2, quantity="force_sq", source="tribospectroscopy stage"),
                        model=params.model)
    np.savez(ctx.workdir / "f2.npz", amplitude=a, f2=f2)
    values = {
        "mu": mu,
        "mu_source": mu_src,
        "model": res.model,
        "amplitude_convention": res.amplitude_convention,
        "length_m": float(res.length_m),
        "fitted_length_m": float(fit.get("length_m", np.nan)),
        "force_at_zero_amplitude_N": float(np.sqrt(f2[0])),
        "amplitude_m": a.tolist(),
        "force_sq_N2": f2.tolist(),
    }
    for k in ("contact_stiffness_N_m", "shakedown_limit_m", "force0_N"):
        if k in res:
            values[k] = float(res[k])
    units = {**{k: u for k, u in res.units.items() if k in values}, "fitted_length_m": "m", "force_at_zero_amplitude_N": "N", "mu": "1"}
    return StageOutput(values=values, units=units, files={"f2": "f2.npz"}, method=str(res.method), message=str(res.message))
