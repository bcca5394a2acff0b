"""Stage ``macroscale``: stick-slip of the rigid body pulled through a spring, on the chain's contact and mu."""

from __future__ import annotations

from typing import Any

import numpy as np

from ...models.friction import friction_coefficient
from ..stage import Decision, Demand, Figure, Handoff, Stage, StageContext, StageOutput
from ._rates import mu_binding, nanoscale_rates


def _draw_stick_slip(ax, result, run) -> None:
    d = np.load(result.file("trajectory"))
    ax.plot(d["t"], d["friction"], lw=0.8, label="drive-spring force (N)")
    ax.set_xlabel("t (s)")
    ax.set_ylabel("F (N)")
    if "velocity" in d:
        ax2 = ax.twinx()
        ax2.plot(d["t"], d["velocity"], "r", lw=0.5)
        ax2.set_ylabel("slider velocity (m/s)", color="r")


_SECTIONS = ("kinematics", "load", "geometry", "material", "counter_material", "contact")


class Macroscale(Stage):
    """The rigid body on the contact (MDR springs or the rough contact's stiffness), with the squeeze film when wet."""

    name = "macroscale"
    produces = (
        Handoff("trajectory", units={"t": "s", "x": "m", "velocity": "m/s", "friction": "N"},
                doc="trajectory.npz: the body's motion and the drive force"),
        Handoff("squeeze", units={"t": "s", "gap": "m", "film_force": "N", "contact_force": "N"},
                doc="squeeze.npz: approach through the film (lubricated scenes)"),
    )
    consumes = ("stiffness", "rates")
    outputs = ("stick_slip",)
    sections = _SECTIONS + ("rates", "lubricant", "roughness")
    figures = (
        Figure("stick_slip", "trajectory", _draw_stick_slip, "stick-slip of the rigid body",
               "Rigid body on the contact: friction force and slider velocity (stick-slip)"),
    )

    def plan(self, scene, demand: Demand) -> Decision:
        """Run for ``stick_slip``; a ``[lubricant]`` makes the squeeze film share the normal load."""
        if not demand.requested("stick_slip"):
            return self.skip("'stick_slip' not requested")
        rough = scene.geometry.profile == "rough"
        how = "the rough contact's tangential stiffness" if rough else "MDR contact springs of the axisymmetric profile"
        sections = _SECTIONS
        options: dict[str, Any] = {"contact_law": "stiffness" if rough else "mdr"}
        film = ""
        if scene.lubricant is not None:
            # The body first approaches through the squeeze film; the rupture gap comes from
            # [roughness] (or the film thickness).  Only lubricated scenes hash these, so a dry
            # scene's key does not depend on them.
            sections += ("lubricant", "roughness")
            options["squeeze_film"] = True
            film = "; normal load shared with the [lubricant] squeeze film"
        return self.go(f"outputs request 'stick_slip': rigid body on {how}, {{mu}}{film}", sections=sections,
                       options=options, wants=("stiffness", "rates"))

    def bind(self, scene, decision: Decision, supplied) -> Decision:
        """Say where mu comes from (and hash its section)."""
        return mu_binding(scene, decision, supplied)

    def run(self, ctx: StageContext) -> StageOutput:
        """Stick-slip of the rigid body pulled through a spring, on the contact, with the chain's mu."""
        from ...models import macro

        choice = friction_coefficient(ctx.scene, nanoscale_rates(ctx))
        mu, mu_src = choice.mu, choice.source
        # the rough MDR profile (if the scene has one) is drawn from the chain's stream, never silently a sphere
        kw: dict[str, Any] = {"mu": mu, "rng": ctx.rng}
        stiff = ctx.handoff("stiffness")
        if ctx.plan.options.get("contact_law") == "stiffness" and stiff is not None:
            from ...models.macro.stiffness import tangential_stiffness_from_table

            v, geo = stiff.values, ctx.scene.geometry
            kc, kc_src = tangential_stiffness_from_table(
                v["pressure"], v["stiffness"], v["force"], normal_force=ctx.scene.load.normal_force,
                apparent_area=geo.apparent_length * geo.apparent_width,
                shear_to_normal=ctx.scene.effective_shear_modulus / ctx.scene.effective_modulus)
            kw["contact_stiffness"] = kc
        else:
            kw["contact_law"] = "mdr"
            kc, kc_src = None, "MDR springs of the [geometry] profile (load dependent)"
        film = bool(ctx.plan.options.get("squeeze_film")) and ctx.scene.lubricant is not None
        if film:
            from ...models.lubrication.rupture import film_rupture_gap

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


STAGE = Macroscale()
