"""Stage ``macroscale``.

Stick-slip of the rigid body pulled through a spring, on the chain's contact and mu.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ...models.friction import friction_coefficient
from ..stage import Decision, Demand, Figure, Handoff, Stage, StageContext, StageOutput, fmt
from ._rates import mu_binding, nanoscale_rates


def _draw_stick_slip(ax, result, run) -> None:
    d = np.load(result.file("trajectory"))
    ax.plot(d["t"], d["friction"], lw=0.8, label="drive-spring force")
    if "contact_force" in d:
        ax.plot(d["t"], d["contact_force"], lw=1.4, zorder=3, color="tab:orange",
                label="contact friction force (drive - m dv/dt)")
    if "mu_s_N" in d:
        ax.axhline(float(d["mu_s_N"]), color="k", ls="--", lw=0.8, label="mu_s N")
        ax.axhline(float(d["mu_k_N"]), color="k", ls=":", lw=0.8, label="mu_k N")
    ax.set_xlabel("t (s)")
    ax.set_ylabel("F (N)")
    ax.legend(fontsize=6, loc="lower right")
    if "velocity" in d:
        ax2 = ax.twinx()
        ax2.plot(d["t"], d["velocity"], "r", lw=0.5)
        ax2.set_ylabel("slider velocity (m/s)", color="r")


_SECTIONS = ("kinematics", "load", "geometry", "material", "counter_material", "contact")



def _restick_words(v_min) -> str:
    """Say what the lowest velocity after the first slip means (it re-sticks at <= 0)."""
    if v_min is None:
        return "no slip"
    return "the body sticks again after its slips" if v_min <= 0 else "no re-stick: steady sliding"

class Macroscale(Stage):
    """The rigid body on the contact, with the squeeze film when wet.

    The contact is MDR springs or the rough contact's stiffness.
    """

    name = "macroscale"
    produces = (
        Handoff("trajectory", units={"t": "s", "x": "m", "velocity": "m/s", "friction": "N"},
                doc="trajectory.npz: the body's motion and the drive force"),
        Handoff("squeeze", units={"t": "s", "gap": "m", "film_force": "N", "contact_force": "N"},
                doc="squeeze.npz: approach through the film (lubricated scenes)"),
    )
    consumes = ("stiffness", "rates", "running_in")
    outputs = ("stick_slip",)
    sections = _SECTIONS + ("rates", "lubricant", "roughness", "running_in")
    figures = (
        Figure("stick_slip", "trajectory", _draw_stick_slip, "stick-slip of the rigid body",
               "Rigid body on the contact: friction force and slider velocity (stick-slip)"),
    )

    def plan(self, scene, demand: Demand) -> Decision:
        """Run for ``stick_slip``.

        A ``[lubricant]`` makes the squeeze film share the normal load.
        """
        if not demand.requested("stick_slip"):
            return self.skip("'stick_slip' not requested")
        rough = scene.geometry.profile == "rough"
        how = (
            "the rough contact's tangential stiffness"
            if rough
            else "MDR contact springs of the axisymmetric profile"
        )
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
        return self.go(
            f"outputs request 'stick_slip': rigid body on {how}, {{mu}}{film}",
            sections=sections,
            options=options,
            wants=("stiffness", "rates", "running_in"),
        )

    def bind(self, scene, decision: Decision, supplied) -> Decision:
        """Say where mu comes from (and hash its section)."""
        return mu_binding(scene, decision, supplied)

    def summary(self, values) -> list[str]:
        """Say which contact stiffness and friction the rigid body slid with, and what it did."""
        return [
            f"- **Rigid body**: contact stiffness {fmt(values.get('contact_stiffness_N_m'))} N/m "
            f"({values.get('contact_stiffness_source')}), bound "
            f"{fmt(values.get('contact_stiffness_bound_N_m'))} N/m; "
            f"{values.get('n_slip_events')} slip events with "
            f"mu_s = {fmt(values.get('mu_static'))}, "
            f"mu_k = {fmt(values.get('mu_kinetic'))}; lowest velocity after the first slip "
            f"{fmt(values.get('min_velocity_after_first_slip_m_s'))} m/s "
            f"({_restick_words(values.get('min_velocity_after_first_slip_m_s'))})."
        ]

    def run(self, ctx: StageContext) -> StageOutput:
        """Stick-slip of the spring-pulled rigid body on the contact, with the chain's mu."""
        from ...models import macro
        from ...models.bridges import punch_bound

        choice = friction_coefficient(ctx.scene, nanoscale_rates(ctx))
        mu, mu_src = choice.mu, choice.source
        # the rough MDR profile (if the scene has one) is drawn from the
        # chain's stream, never silently a sphere
        kw: dict[str, Any] = {"mu": mu, "rng": ctx.rng}
        runin = ctx.handoff("running_in")
        fr = runin.values.get("friction") if runin is not None else None
        if fr:
            # Static and kinetic coefficients at the part (the running-in
            # stage states rule and sources).
            kw["law"] = macro.ConstantFriction(
                mu_s=float(fr["mu_static"]), mu_k=float(fr["mu_kinetic"])
            )
            mu, mu_src = float(fr["mu_kinetic"]), "running-in: " + str(fr["source"])
        elif choice.mu_static != choice.mu_kinetic:
            kw["law"] = macro.ConstantFriction(mu_s=choice.mu_static, mu_k=choice.mu_kinetic)
        scene = ctx.scene
        stiff = ctx.handoff("stiffness")
        extra: dict[str, Any] = {}
        bound = None
        if ctx.plan.options.get("contact_law") == "stiffness" and stiff is not None:
            from ...models.macro.stiffness import apparent_tangential_stiffness

            v, geo = stiff.values, scene.geometry
            kc, kc_src, extra = apparent_tangential_stiffness(
                v["pressure"],
                v["stiffness"],
                v["force"],
                normal_force=scene.load.normal_force,
                apparent_area=geo.apparent_length * geo.apparent_width,
                E_star=scene.effective_modulus,
                shear_to_normal=scene.effective_shear_modulus / scene.effective_modulus,
            )
            kw["contact_stiffness"] = kc
            bound = extra["bound"]
        else:
            kw["contact_law"] = "mdr"
            kc, kc_src = None, "MDR springs of the [geometry] profile (load dependent)"
            if scene.geometry.profile == "sphere" and scene.load.normal_force > 0:
                # Apparent area of a sphere: the Hertz circle at the load;
                # its bonded-punch bound is 2E*a.
                a = (
                    3.0
                    * scene.load.normal_force
                    * scene.geometry.radius
                    / (4.0 * scene.effective_modulus)
                ) ** (1 / 3)
                bound = punch_bound(np.pi * a * a, scene.effective_modulus)
        film = bool(ctx.plan.options.get("squeeze_film")) and ctx.scene.lubricant is not None
        if film:
            from ...models.lubrication.rupture import film_rupture_gap

            kw["contact_gap"], hc_src = film_rupture_gap(ctx.scene)
        res = macro.stick_slip_from_scene(ctx.scene, **kw)
        t = np.asarray(res.t)
        law = kw.get("law")
        mu_s = float(law.mu_s) if law is not None else mu
        mu_k = float(law.kinetic(0.0)) if law is not None else mu
        # Newton on the body: the contact's friction force is the drive force minus m dv/dt
        # (event times repeat in the trajectory: differentiate across distinct times only).
        v_arr = np.asarray(res.v, float)
        acc = np.zeros_like(v_arr)
        step = np.diff(t)
        ok = step > 0
        if np.count_nonzero(ok) >= 2:
            acc = np.interp(t, 0.5 * (t[1:] + t[:-1])[ok], np.diff(v_arr)[ok] / step[ok])
        f_contact = np.asarray(res.drive_force, float) - scene.kinematics.mass * acc
        np.savez(
            ctx.workdir / "trajectory.npz",
            t=t,
            x=res.x,
            velocity=res.v,
            friction=res.drive_force,
            drive_force=res.drive_force,
            contact_force=f_contact,
            phase=res.phase,
            mu_s_N=mu_s * scene.load.normal_force,
            mu_k_N=mu_k * scene.load.normal_force,
        )
        slips = [e for e in res.events if str(e.get("to_phase", "")).startswith("slip")]
        resticks = [e for e in res.events if e.get("to_phase") == "stick"]
        from ...models.macro.reference import restick_criterion

        # Whether the data allow repeated stick-slip (analytic, constant mu_s/mu_k, contact spring
        # kc or rigid): stated next to what the integration gave.
        crit = (
            restick_criterion(
                scene.kinematics.mass,
                scene.kinematics.drive_stiffness,
                scene.kinematics.sliding_velocity,
                scene.load.normal_force,
                mu_s,
                mu_k,
                kc or 0.0,
            )
            if kc is not None or kw.get("contact_law") != "mdr"
            else None
        )
        values = {
            "mu": mu,
            "mu_source": mu_src,
            "contact_stiffness_N_m": kc,
            "contact_stiffness_source": kc_src,
            "contact_stiffness_bound_N_m": bound,
            "contact_stiffness_bound_source": "bonded punch 2E*sqrt(A/pi) of the apparent area"
            if bound
            else None,
            "contact_normal_stiffness_N_m": extra.get("normal"),
            "interfacial_stiffness_per_area_N_m3": extra.get("k_int_per_area"),
            "interface_compliance_share": extra.get("interface_share"),
            "mu_static": mu_s,
            "mu_kinetic": mu_k,
            "n_transitions": int(res.n_transitions),
            "n_slip_events": len(slips),
            # stick phases: the initial one (the body starts at rest) plus
            # every re-stick after a slip
            "n_stick_phases": 1 + len(resticks),
            "restick_criterion": crit,
            "max_drive_force_N": float(np.max(res.drive_force)),
            "mean_drive_force_N": float(np.mean(res.drive_force)),
            "max_velocity_m_s": float(np.max(res.v)),
            "duration_s": float(t[-1]) if t.size else 0.0,
            "first_slip_time_s": float(slips[0]["t"]) if slips else None,
            # Below zero the body re-sticks; a positive minimum after the first slip means steady
            # sliding with an oscillating velocity (e.g. the contact spring's pre-slip creep).
            "min_velocity_after_first_slip_m_s": (
                float(np.min(v_arr[t > slips[0]["t"]]))
                if slips and np.any(t > slips[0]["t"])
                else None
            ),
        }
        units = {
            "mu": "1",
            "contact_stiffness_N_m": "N/m",
            "contact_stiffness_bound_N_m": "N/m",
            "contact_normal_stiffness_N_m": "N/m",
            "interfacial_stiffness_per_area_N_m3": "N/m^3",
            "interface_compliance_share": "1",
            "mu_static": "1",
            "mu_kinetic": "1",
            "max_drive_force_N": "N",
            "mean_drive_force_N": "N",
            "max_velocity_m_s": "m/s",
            "min_velocity_after_first_slip_m_s": "m/s",
            "duration_s": "s",
            "first_slip_time_s": "s",
        }
        files = {"trajectory": "trajectory.npz"}
        message = str(res.message)
        if film:
            sq = res.squeeze
            W = ctx.scene.load.normal_force
            fc = np.asarray(sq.contact_force)
            touched = np.flatnonzero(fc > 0.0)
            np.savez(
                ctx.workdir / "squeeze.npz",
                t=sq.t,
                gap=sq.gap,
                log_gap=sq.log_gap,
                film_force=sq.film_force,
                contact_force=fc,
            )
            files["squeeze"] = "squeeze.npz"
            values.update(
                {
                    "film_rupture_gap_m": kw["contact_gap"],
                    "film_rupture_gap_source": hc_src,
                    "time_to_solid_contact_s": float(np.asarray(sq.t)[touched[0]])
                    if touched.size
                    else None,
                    "final_load_share": float(fc[-1] / W),
                    "final_gap_m": float(np.asarray(sq.gap)[-1]),
                    "squeeze_status": int(sq.status),
                    "squeeze_message": str(sq.message),
                }
            )
            units.update(
                {
                    "film_rupture_gap_m": "m",
                    "time_to_solid_contact_s": "s",
                    "final_load_share": "1",
                    "final_gap_m": "m",
                }
            )
            if sq.status != 0:
                # Not a failure of the chain: the model says the film has
                # not been squeezed out yet (h_c below the indentation the
                # load needs, or too short a run).  Say so, invent nothing.
                message += f"; squeeze film: {sq.message}"
        return StageOutput(
            values=values,
            units=units,
            files=files,
            method=str(res.method),
            message=message,
            nit=int(res.nit),
        )


STAGE = Macroscale()
