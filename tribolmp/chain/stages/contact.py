"""Stage ``contact``.

Normal stiffness against load (MDR or BEM) of the rough or axisymmetric contact.
"""

from __future__ import annotations

import json
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np

from ...environment import data_path
from ...errors import SceneError
from ..stage import Decision, Demand, Figure, Handoff, Stage, StageContext, StageOutput

__all__ = ["STAGE", "speed_error_table", "choose_contact_method"]


def speed_error_table() -> dict[str, Any] | None:
    """Return the shipped measured speed-vs-error table of the contact solvers.

    None if the table is not shipped.
    """
    try:
        return json.loads(data_path("contact_speed_error.json").read_text())
    except (OSError, ValueError):
        return None


def choose_contact_method(tolerance: float, table: dict[str, Any] | None, *,
                          reduced_pressures: list[float] | None = None) -> dict[str, Any]:
    """Pick the cheapest measured (method, mesh) whose error is within ``tolerance``.

    The choice itself is physics (which solver is valid where) and lives in
    :func:`tribolmp.models.contact.choice.choose_method`; see there for the
    table format.  ``reduced_pressures`` (``p / (E* h'_rms)``) selects the
    table rows of the pressure range the scene asks for.
    """
    from ...models.contact.choice import choose_method

    return choose_method(tolerance, table, reduced_pressures=reduced_pressures)


def _draw_stiffness(ax, result, run) -> None:
    d = np.load(result.file("stiffness"))
    p, med = d["pressure"], d["stiffness"]
    ax.loglog(p, med, "o-", label="median")
    if "q10" in d and "q90" in d:
        ax.fill_between(p, d["q10"], d["q90"], alpha=0.3, label="q10-q90")
    ax.set_xlabel("nominal pressure (Pa)")
    ax.set_ylabel("normal stiffness (N/m)")
    ax.legend()


_SECTIONS = ("geometry", "material", "counter_material", "load", "contact")


class Contact(Stage):
    """Contact stiffness against nominal pressure.

    The evolved, given or random rough surface, or a profile.
    """

    name = "contact"
    produces = (
        Handoff(
            "stiffness",
            units={
                "pressure": "Pa",
                "force": "N",
                "stiffness": "N/m",
                "approach": "m",
                "stiffness_q10": "N/m",
                "stiffness_q90": "N/m",
                "area_fraction": "1",
            },
            doc="stiffness.npz: normal stiffness against "
                "nominal pressure (table also in the values)",
        ),
    )
    consumes = ("surface",)
    outputs = ("stiffness",)
    sections = _SECTIONS + ("roughness",)
    figures = (
        Figure(
            "stiffness",
            "stiffness",
            _draw_stiffness,
            "normal stiffness vs load",
            "Normal contact stiffness against nominal "
            "pressure (median and q10-q90 of the ensemble)",
        ),
    )

    def plan(self, scene, demand: Demand) -> Decision:
        """Run when stiffness is requested or consumed.

        ``method = "auto"`` picks the solver from measured data.
        """
        wanted = demand.requested("stiffness") or demand.wants("stiffness")
        if not wanted:
            return self.skip("no requested output needs contact stiffness")
        rough = scene.geometry.profile == "rough"
        if rough and scene.topography is None and scene.roughness is None:
            raise SceneError(
                "[roughness]",
                "a [roughness] or [topography] section for geometry.profile = 'rough'",
                "nothing",
                scene.source,
            )
        c = scene.contact
        if c.method == "auto":
            from ...models.contact.choice import choose_method_for_scene

            # rough: the measured table at the scene's reduced pressures;
            # axisymmetric: the exact MDR
            table = demand.overrides.get("contact_table")
            choice = choose_method_for_scene(scene, speed_error_table() if table is None else table)
            method, mesh, why = choice["method"], choice["mesh"], "auto: " + choice["why"]
        else:
            choice = {}
            method, mesh, why = c.method, None, f"method '{c.method}' set in [contact]"
        purpose = (
            "outputs request 'stiffness'"
            if demand.requested("stiffness")
            else "stiffness feeds macroscale"
        )
        options = {
            "method": method,
            "mesh": mesh,
            **{f"expected_{k}": choice.get(f"expected_{k}") for k in ("error", "time_s") if choice},
        }
        return self.go(f"{method.upper()} on the {{surface}}; {why}; {purpose}",
                       sections=_SECTIONS if not rough else _SECTIONS + ("roughness",),
                       options=options, wants=("surface",) if rough else ())

    def bind(self, scene, decision: Decision, supplied) -> Decision:
        """Name the surface.

        Evolved (topography supplies it), given height map, random, or axisymmetric.
        """
        if scene.geometry.profile != "rough":
            surface = f"axisymmetric {scene.geometry.profile}"
        elif "surface" in supplied:
            surface = "evolved surface from topography"
        else:
            surface = (
                "given height map"
                if scene.roughness.surface_file
                else "random surface from [roughness]"
            )
        opts = dict(decision.options)
        # keep the option order of the reports: method, mesh, surface, expected_*
        options = {
            "method": opts.pop("method"),
            "mesh": opts.pop("mesh"),
            "surface": surface,
            **opts,
        }
        return replace(
            decision, reason=decision.reason.replace("{surface}", surface), options=options
        )

    def preflight(self, scene, decision: Decision) -> list[str]:
        """Read the height map the scene names and check the grid's memory.

        A damaged file fails here, before any stage runs.
        """
        from ...resources import check_memory

        if (
            scene.geometry.profile != "rough"
            or scene.roughness is None
            or "surface" in decision.supplied
        ):
            return []
        r = scene.roughness
        notes: list[str] = []
        if r.surface_file:
            from ...errors import SetupError
            from ...models.contact.solve import load_surface

            path = Path(r.surface_file)
            if not path.is_absolute() and scene.source not in ("<default>", "<scene>"):
                path = Path(scene.source).parent / path
            try:
                h, _ = load_surface(path, r.surface_pixel_size or None, unit=r.surface_unit or None,
                                    detrend=r.surface_detrend, missing=r.surface_missing)
            except SetupError as exc:
                raise SceneError(
                    "[roughness].surface_file", "a readable height map", str(exc), scene.source
                ) from None
            n = int(max(h.shape))
            if path.suffix.lower() == ".npy" and not path.with_suffix(".json").exists():
                notes.append(
                    f"{path.name} has no sidecar "
                    f"{path.with_suffix('.json').name}: its pixel size is "
                    f"[roughness].pixel_size = {r.pixel_size:g} "
                    "m (set it there if that is not right)"
                )
        else:
            n = int(r.grid_points)
        method = decision.options.get("method")
        mesh = (decision.options.get("mesh") or n) if method == "bem" else n
        # BEM: FFTs on the zero-padded (2n)^2 grid, ~6 complex/real work
        # arrays; MDR: the map and its line profiles, ~4 float64 copies.
        need = 6 * 16 * (2 * mesh) ** 2 if method == "bem" else 4 * 8 * n**2
        check_memory(
            need,
            "[roughness].grid_points",
            n,
            f"the {method} contact solve on {mesh}^2 points",
            scene.source,
        )
        return notes

    def run(self, ctx: StageContext) -> StageOutput:
        """Compute the normal stiffness against load.

        Rough surface (evolved, given or generated) or axisymmetric profile.
        """
        from ...models.contact.solve import (
            load_surface,
            rough_params_from_scene,
            rough_surface,
            solve_rough,
        )

        scene, opts = ctx.scene, ctx.plan.options
        method = opts["method"]
        if scene.geometry.profile != "rough":
            return _contact_axisymmetric(ctx, method)
        import dataclasses

        params = rough_params_from_scene(scene)
        surf_rng, ens_rng = ctx.rng.spawn(2)
        mesh_note = ""
        if ctx.handoff("surface") is not None:
            h, dx = load_surface(ctx.handoff_file("surface"))
            source = "evolved surface (topography stage)"
            if opts.get("mesh") is not None:
                mesh_note = (
                    f"mesh fixed by the evolved surface ({h.shape[0]} points), "
                    f"not the table's {opts['mesh']}"
                )
        else:
            if opts.get("mesh") is not None and not params.surface_file and method == "bem":
                # The measured table gives the BEM grid for this tolerance:
                # same physical size L, new pixel.
                L = params.grid_points * params.pixel_size
                params = dataclasses.replace(
                    params, grid_points=int(opts["mesh"]), pixel_size=L / int(opts["mesh"])
                )
                mesh_note = f"BEM grid {opts['mesh']} from the speed-error table (L = {L:g} m)"
            h, dx = rough_surface(params, surf_rng)
            if params.surface_file:
                from ...models.topography.measured import surface_provenance

                # Say which units and pixel size were used: the file's
                # metadata or the scene's value.
                source = "height map " + surface_provenance(
                    params.surface_file,
                    params.pixel_size,
                    pixel_size=params.surface_pixel_size or None,
                    unit=params.surface_unit or None,
                    detrend=params.surface_detrend,
                    missing=params.surface_missing,
                )
            else:
                source = "random surface from [roughness]"
        res = solve_rough(
            h, dx, params.E_star, params.pressures, method=method, periodic=params.periodic,
            realizations=params.realizations, rng=ens_rng,
        )
        arrays = {
            k: np.asarray(res[k])
            for k in (
                "pressure",
                "force",
                "stiffness",
                "approach",
                "stiffness_q10",
                "stiffness_q90",
                "area_fraction",
            )
            if k in res
        }
        np.savez(
            ctx.workdir / "stiffness.npz",
            q10=arrays.get("stiffness_q10", arrays["stiffness"]),
            q90=arrays.get("stiffness_q90", arrays["stiffness"]),
            **arrays,
        )
        values: dict[str, Any] = {k: v.tolist() for k, v in arrays.items()}
        values.update(
            surface=source,
            grid=int(h.shape[0]),
            pixel_size_m=float(dx),
            surface_rms_m=float(np.std(h)),
            E_star_Pa=float(params.E_star),
            realizations=int(params.realizations) if method == "mdr" else None,
            periodic=bool(params.periodic) if method == "bem" else None,
        )
        if mesh_note:
            values["mesh_note"] = mesh_note
        if opts.get("expected_error") is not None:
            values["expected_rel_error"] = opts["expected_error"]
        units = {
            "pressure": "Pa",
            "force": "N",
            "stiffness": "N/m",
            "approach": "m",
            "stiffness_q10": "N/m",
            "stiffness_q90": "N/m",
            "area_fraction": "1",
            "pixel_size_m": "m",
            "surface_rms_m": "m",
            "E_star_Pa": "Pa",
            "expected_rel_error": "1",
        }
        return StageOutput(
            values=values,
            units=units,
            files={"stiffness": "stiffness.npz"},
            method=method,
            message=f"{method} on {source}, {h.shape[0]}x{h.shape[1]} grid",
            nit=int(res.get("nit", 0) or 0),
        )


def _contact_axisymmetric(ctx: StageContext, method: str) -> StageOutput:
    """Axisymmetric indenter.

    Force, contact radius and (MDR) stiffness at fractions of the scene's load.
    """
    from ...models.contact.solve import params_from_scene
    from ...models.contact.sweep import axisymmetric_load_sweep

    base = params_from_scene(ctx.scene)
    if base.normal_force is None:
        raise ValueError(
            "[load].normal_force must be > 0 for a "
            "stiffness-vs-load curve of an axisymmetric contact"
        )
    sweep = axisymmetric_load_sweep(base, method=method)
    arrays = {
        k: np.asarray(sweep[k])
        for k in ("force", "contact_radius", "indentation", "stiffness", "pressure")
        if k in sweep
    }
    np.savez(ctx.workdir / "stiffness.npz", **arrays)
    values: dict[str, Any] = {k: v.tolist() for k, v in arrays.items()}
    values.update(
        profile=ctx.scene.geometry.profile, E_star_Pa=float(base.E_star), springs=sweep["springs"]
    )
    units = {
        "force": "N",
        "contact_radius": "m",
        "indentation": "m",
        "stiffness": "N/m",
        "pressure": "Pa",
        "E_star_Pa": "Pa",
    }
    files = (
        {"stiffness": "stiffness.npz"}
        if "stiffness" in arrays
        else {"contact_curve": "stiffness.npz"}
    )
    return StageOutput(
        values=values,
        units=units,
        files=files,
        method=method,
        message=f"{method} {ctx.scene.geometry.profile}, {sweep.message.split(': ', 1)[1]}",
    )


STAGE = Contact()
