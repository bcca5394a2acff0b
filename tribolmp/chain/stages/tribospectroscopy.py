"""Stage ``tribospectroscopy``: F^2(a) of the oscillating two-contact probe with the chain's mu."""

from __future__ import annotations

import numpy as np

from ...models.friction import friction_coefficient
from ..stage import Decision, Demand, Figure, Handoff, Stage, StageContext, StageOutput, fmt
from ._rates import mu_binding, nanoscale_rates


def _draw_f2(ax, result, run) -> None:
    d = np.load(result.file("f2"))
    if "f2_measured" in d:
        ax.plot(
            d["amplitude"] * 1e9,
            d["f2_measured"],
            "o",
            ms=3,
            label="simulated measurement (with noise)",
        )
        ax.plot(d["amplitude"] * 1e9, d["f2"], "-", color="0.6", lw=1,
                label=f"model, length {float(d['length_m']) * 1e9:.3g} nm (upstream)")
        lo, hi = d["interval"]
        ax.plot(
            d["amplitude"] * 1e9,
            d["f2_fit"],
            "k-",
            lw=1,
            label=f"fit: {float(d['fitted_length_m']) * 1e9:.3g} "
                  f"nm, 68 % [{lo * 1e9:.3g}, {hi * 1e9:.3g}] nm",
        )
    else:
        ax.plot(d["amplitude"] * 1e9, d["f2"], "o", ms=3, label="simulated")
    ax.set_xlabel("amplitude a (nm)")
    ax.set_ylabel("F^2 (N^2)")
    ax.legend()


class Tribospectroscopy(Stage):
    """The probe's squared friction force against oscillation amplitude, and its fitted length."""

    name = "tribospectroscopy"
    produces = (
        Handoff("f2", units={"amplitude": "m", "f2": "N^2"}, doc="f2.npz: F^2 against amplitude"),
    )
    consumes = ("rates", "running_in")
    outputs = ("tribospectroscopy",)
    sections = (
        "tribospectroscopy",
        "load",
        "geometry",
        "material",
        "counter_material",
        "contact",
        "rates",
        "running_in",
    )
    figures = (
        Figure(
            "f2",
            "f2",
            _draw_f2,
            "tribospectroscopy F^2(a) (cf. Fig. 8)",
            "Tribospectroscopy: squared friction force against oscillation amplitude (cf. Fig. 8)",
        ),
    )

    def plan(self, scene, demand: Demand) -> Decision:
        """Run for ``tribospectroscopy`` with a ``[tribospectroscopy]`` section."""
        if not demand.requested("tribospectroscopy"):
            return self.skip("'tribospectroscopy' not requested")
        if scene.tribospectroscopy is None:
            return self.skip(
                "'tribospectroscopy' requested but the scene has no [tribospectroscopy] section"
            )
        ts = scene.tribospectroscopy
        return self.go(
            "outputs request 'tribospectroscopy': F^2(a), "
            f"{ts.model} model, {ts.convention} amplitudes, {{mu}}",
            sections=(
                "tribospectroscopy",
                "load",
                "geometry",
                "material",
                "counter_material",
                "contact",
            ),
            options={"model": ts.model},
            wants=("rates", "running_in"),
        )

    def bind(self, scene, decision: Decision, supplied) -> Decision:
        """Say where mu comes from; hash ``[rates]`` (or ``[load]``) when that is the source."""
        return mu_binding(scene, decision, supplied)

    def summary(self, values) -> list[str]:
        """Say where the probe's length came from and how well the fit recovers it."""
        return [
            f"- **Tribospectroscopy**: length {fmt(values.get('length_m'))} m from "
            f"{values.get('length_source')}; fitted on a simulated measurement with "
            f"{fmt(values.get('measurement_noise_rel'))} relative noise: "
            f"{fmt(values.get('fitted_length_m'))} m, 68 % interval "
            f"{values.get('fitted_length_interval_m')} ({values.get('fit_message')})."
        ]

    def run(self, ctx: StageContext) -> StageOutput:
        """F^2(a) of the oscillating two-contact probe with the chain's mu; the fitted length."""
        from ...models import tribospectroscopy as ts
        from ...models.tribospectroscopy.fit import model_curve

        choice = friction_coefficient(ctx.scene, nanoscale_rates(ctx))
        mu, mu_src = choice.mu, choice.source
        over = {}
        length_src = "[tribospectroscopy].correlation_length (scene)"
        runin = ctx.handoff("running_in")
        ri = ctx.scene.running_in
        if runin is not None:
            fr = runin.values.get("friction") or {}
            if fr:
                mu, mu_src = float(fr["mu_kinetic"]), "running-in: " + str(fr["source"])
            # The length scale comes from upstream (issue 15): the evolved
            # surface's correlation length, or the quasi-liquid layer depth
            # of the nanoscale rates; [running_in] says which.
            if ri is not None and ri.tribospec_length == "layer_depth":
                from ._rates import upstream_rates

                rates, rsrc = upstream_rates(ctx)
                lam, length_src = (
                    (rates.layer_depth_m if rates is not None else None),
                    f"layer_depth_m of the rates ({rsrc})",
                )
            else:
                lam = runin.values.get("correlation_length_m")
                length_src = "1/e correlation length of the evolved surface (topography stage)"
            if not lam or not np.isfinite(lam) or lam <= 0:
                raise ValueError(
                    "tribospectroscopy length from upstream "
                    f"({length_src}) is not a positive number: {lam}"
                )
            over["correlation_length"] = float(lam)
        params = ts.params_from_scene(ctx.scene, mu=mu, **over)
        res = ts.solve(params)
        a, f2 = np.asarray(res.amplitude_m), np.asarray(res.force_sq_N2)
        # A fit is reported only on data it did not generate: a simulated measurement of the forward
        # curve with stated multiplicative Gaussian noise (drawn from the stage's stream).
        noise = ri.measurement_noise if ri is not None else 0.05
        meas_rng, boot_rng = ctx.rng.spawn(2)
        f2_meas = f2 * (1.0 + noise * meas_rng.standard_normal(f2.shape))
        fit = ts.fit_length(
            ts.MeasuredCurve(
                amplitude=a,
                value=f2_meas,
                quantity="force_sq",
                source=f"simulated measurement, {noise:g} relative noise",
            ),
            model=params.model,
            noise="proportional",
            rng=boot_rng,
        )  # the noise drawn above
        f2_fit = model_curve(
            fit["model"], a, fit["length_m"], fit["force0_N"] ** 2, fit["background"], "force_sq"
        )
        interval = [
            float(x) for x in np.asarray(fit.get("length_interval_m", (np.nan, np.nan)), float)
        ]
        np.savez(
            ctx.workdir / "f2.npz",
            amplitude=a,
            f2=f2,
            f2_measured=f2_meas,
            f2_fit=f2_fit,
            length_m=float(res.length_m),
            fitted_length_m=float(fit["length_m"]),
            interval=np.asarray(interval),
        )
        values = {
            "mu": mu,
            "mu_source": mu_src,
            "model": res.model,
            "amplitude_convention": res.amplitude_convention,
            "length_m": float(res.length_m),
            "length_source": length_src,
            "measurement_noise_rel": float(noise),
            "fitted_length_std_m": float(fit["length_std_m"])
            if np.isfinite(fit["length_std_m"])
            else None,
            "fitted_length_interval_m": [x if np.isfinite(x) else None for x in interval],
            "fit_bounded": bool(fit.get("bounded", False)),
            "fit_noise_model": str(fit.get("noise_model", "")),
            "fit_coverage_tested": bool(fit.get("coverage_tested", False)),
            "fit_message": str(fit.get("message", "")),
            "fitted_length_m": float(fit.get("length_m", np.nan)),
            "force_at_zero_amplitude_N": float(np.sqrt(f2[0])),
            "amplitude_m": a.tolist(),
            "force_sq_N2": f2.tolist(),
        }
        for k in ("contact_stiffness_N_m", "shakedown_limit_m", "force0_N"):
            if k in res:
                values[k] = float(res[k])
        units = {
            **{k: u for k, u in res.units.items() if k in values},
            "fitted_length_m": "m",
            "force_at_zero_amplitude_N": "N",
            "mu": "1",
            "fitted_length_std_m": "m",
            "fitted_length_interval_m": "m",
            "measurement_noise_rel": "1",
        }
        return StageOutput(
            values=values,
            units=units,
            files={"f2": "f2.npz"},
            method=str(res.method),
            message=str(res.message),
        )


STAGE = Tribospectroscopy()
