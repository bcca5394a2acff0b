"""Stage ``lubrication``.

Squeeze and shear forces of the ``[lubricant]`` film and, with ``[polishing]``, polishing.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..stage import Decision, Demand, Figure, Handoff, Stage, StageContext, StageOutput


def _draw_lubrication(ax, result, run) -> None:
    d = np.load(result.file("curves"))
    for key in d.files:
        if key != "x" and d[key].shape == d["x"].shape:
            ax.loglog(d["x"], np.abs(d[key]), label=key)
    ax.set_xlabel(str(d["x_label"]) if "x_label" in d.files else "x")
    ax.set_ylabel("|F| (N)")
    ax.legend(fontsize=7)


def _draw_polishing(ax, result, run) -> None:
    d = np.load(result.file("polishing"))
    ax.plot(d["t"], d["sq"] * 1e9, label="Sq")
    ax.plot(d["t"], d["sa"] * 1e9, label="Sa")
    ax.set_xlabel("t (s)")
    ax.set_ylabel("roughness (nm)")
    ax.legend(fontsize=7)


class Lubrication(Stage):
    """The film's squeeze force and lubricated polishing.

    The reduced damper against Reynolds and Brenner.
    """

    name = "lubrication"
    produces = (
        Handoff(
            "lubrication_curves",
            file="curves",
            units={"x": "m", "damper": "N", "Reynolds": "N"},
            doc="curves.npz: squeeze force against gap",
        ),
        Handoff(
            "polishing",
            units={"t": "s", "sq": "m", "sa": "m", "removed_volume": "m^3"},
            doc="polishing.npz: roughness of the workpiece against time",
        ),
    )
    outputs = ("lubrication", "polishing")
    sections = (
        "lubricant",
        "polishing",
        "geometry",
        "load",
        "kinematics",
        "material",
        "counter_material",
    )
    figures = (
        Figure(
            "lubrication",
            "curves",
            _draw_lubrication,
            "lubrication forces",
            "Squeeze-film force against gap: reduced damper, Reynolds and Brenner's exact series",
        ),
        Figure(
            "polishing",
            "polishing",
            _draw_polishing,
            "polishing: roughness against time",
            "Lubricated polishing: rms (Sq) and mean absolute "
            "(Sa) roughness of the workpiece against time",
        ),
    )

    def plan(self, scene, demand: Demand) -> Decision:
        """Run whenever the scene has a ``[lubricant]``."""
        if scene.lubricant is None:
            return self.skip("dry scene: no [lubricant] section")
        what = "polishing" if scene.polishing is not None else "squeeze and shear forces"
        return self.go(f"scene has [lubricant]: {what}", sections=self.sections,
                       options={"polishing": scene.polishing is not None})

    def run(self, ctx: StageContext) -> StageOutput:
        """Squeeze-force summary of the film and, with [polishing], polishing.

        The reduced damper against Reynolds and Brenner.
        """
        from ...models.lubrication import summary as summ
        res = summ.lubrication_summary(ctx.scene)
        gap = np.asarray(res.gap)
        film = ctx.scene.lubricant.film_thickness
        i = int(np.argmin(np.abs(gap - film)))  # the summary includes the scene's film thickness
        curves: dict[str, Any] = {
            "x": gap,
            "x_label": "gap h (m)",
            "damper": res.force_damper,
            "Reynolds": res.force_reynolds,
        }
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
        units = {
            "alpha_N_s": "N s",
            "radius_m": "m",
            "approach_velocity_m_s": "m/s",
            "power_law_index": "1",
            "film_thickness_m": "m",
            "force_damper_N": "N",
            "force_reynolds_N": "N",
            "error_damper_vs_reynolds": "1",
        }
        if "force_brenner" in res:
            values["force_brenner_N"] = float(res.force_brenner[i])
            values["error_damper_vs_stokes"] = float(res.error_damper_vs_stokes[i])
            units.update(force_brenner_N="N", error_damper_vs_stokes="1")
        files = {"curves": "curves.npz"}
        method, message = res.method, res.message
        if ctx.scene.polishing is not None:
            from ...models.lubrication import polishing as pol

            pres = pol.polish(pol.params_from_scene(ctx.scene), rng=ctx.rng)
            np.savez(
                ctx.workdir / "polishing.npz",
                t=pres.t,
                sq=pres.sq,
                sa=pres.sa,
                removed_volume=pres.removed_volume,
            )
            np.save(ctx.workdir / "polished.npy", pres.h)
            files.update(polishing="polishing.npz", polished_surface="polished.npy")
            for key in (
                "removal_rate",
                "preston_rate",
                "contact_fraction",
                "mass_balance_error",
                "load_error",
                "pixel_size",
            ):
                values[f"polishing_{key}"] = float(pres[key])
                units[f"polishing_{key}"] = pres.units.get(key, "1")
            values.update(
                polishing_sq_initial_m=float(pres.sq[0]), polishing_sq_final_m=float(pres.sq[-1])
            )
            units.update(polishing_sq_initial_m="m", polishing_sq_final_m="m")
            method += f"; polishing {pres.method}"
            message += f"; polishing: {pres.message}"
        return StageOutput(
            values=values,
            units=units,
            files=files,
            method=method,
            message=message,
            nit=int(res.nit),
        )


STAGE = Lubrication()
