"""Stage ``tribospectroscopy``: F^2(a) of the oscillating two-contact probe with the chain's mu."""

from __future__ import annotations

import numpy as np

from ...models.friction import friction_coefficient
from ..stage import Decision, Demand, Figure, Handoff, Stage, StageContext, StageOutput
from ._rates import mu_binding, nanoscale_rates


def _draw_f2(ax, result, run) -> None:
    d = np.load(result.file("f2"))
    ax.plot(d["amplitude"] * 1e9, d["f2"], "o", ms=3, label="simulated")
    ax.set_xlabel("amplitude a (nm)")
    ax.set_ylabel("F^2 (N^2)")
    ax.legend()


class Tribospectroscopy(Stage):
    """The probe's squared friction force against oscillation amplitude, and the length fitted to it."""

    name = "tribospectroscopy"
    produces = (Handoff("f2", units={"amplitude": "m", "f2": "N^2"}, doc="f2.npz: F^2 against amplitude"),)
    consumes = ("rates",)
    outputs = ("tribospectroscopy",)
    sections = ("tribospectroscopy", "load", "geometry", "material", "counter_material", "contact", "rates")
    figures = (
        Figure("f2", "f2", _draw_f2, "tribospectroscopy F^2(a) (cf. Fig. 8)",
               "Tribospectroscopy: squared friction force against oscillation amplitude (cf. Fig. 8)"),
    )

    def plan(self, scene, demand: Demand) -> Decision:
        """Run for ``tribospectroscopy`` with a ``[tribospectroscopy]`` section."""
        if not demand.requested("tribospectroscopy"):
            return self.skip("'tribospectroscopy' not requested")
        if scene.tribospectroscopy is None:
            return self.skip("'tribospectroscopy' requested but the scene has no [tribospectroscopy] section")
        ts = scene.tribospectroscopy
        return self.go(f"outputs request 'tribospectroscopy': F^2(a), {ts.model} model, {ts.convention} amplitudes, {{mu}}",
                       sections=("tribospectroscopy", "load", "geometry", "material", "counter_material", "contact"),
                       options={"model": ts.model}, wants=("rates",))

    def bind(self, scene, decision: Decision, supplied) -> Decision:
        """Say where mu comes from; hash ``[rates]`` (or ``[load]``) when that is the source."""
        return mu_binding(scene, decision, supplied)

    def run(self, ctx: StageContext) -> StageOutput:
        """F^2(a) of the oscillating two-contact probe with the chain's mu, and the fitted length."""
        from ...models import tribospectroscopy as ts

        choice = friction_coefficient(ctx.scene, nanoscale_rates(ctx))
        mu, mu_src = choice.mu, choice.source
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


STAGE = Tribospectroscopy()
