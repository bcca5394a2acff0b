"""``tribolmp tribospec simulate|fit``: friction force against oscillation amplitude."""

from __future__ import annotations

from . import seed_type

HELP = "tribospectroscopy: simulate and fit F(amplitude)"


def configure(parser) -> None:
    """Add the ``simulate`` and ``fit`` subcommands."""
    from . import float_list

    sub = parser.add_subparsers(
        dest="action", metavar="ACTION", parser_class=type(parser), required=True
    )
    sim = sub.add_parser("simulate", help="F and F^2 against amplitude from a model")
    sim.add_argument("scene", nargs="?", help="TOML scene file (default: the embedded scene)")
    sim.add_argument(
        "--amplitudes", type=float_list, help="comma-separated amplitudes in m (in --convention)"
    )
    sim.add_argument(
        "--model", choices=("stiffness", "potential"), help="friction model (default: the scene's)"
    )
    sim.add_argument(
        "--law", choices=("linear", "microslip"), default="linear", help="stiffness model variant"
    )
    sim.add_argument(
        "--convention",
        choices=("per-contact", "probe"),
        help="amplitude convention (default: the scene's)",
    )
    sim.add_argument(
        "--correlation-length", type=float, help="pinning correlation length lambda in m"
    )
    sim.add_argument(
        "--contact-stiffness",
        type=float,
        help="tangential stiffness of one contact in N/m (default: MDR)",
    )
    sim.add_argument("--json", action="store_true", help="print JSON")
    fit = sub.add_parser("fit", help="fit the characteristic length to measured F(amplitude)")
    fit.add_argument("data", help="CSV with amplitude_m and force_N or force_sq_N2")
    fit.add_argument("--model", choices=("stiffness", "potential", "auto"), default="auto")
    fit.add_argument("--convention", choices=("per-contact", "probe"), default="per-contact",
                     help="convention of amplitude_m in the file")
    fit.add_argument(
        "--no-background", action="store_true", help="fit without a constant background"
    )
    fit.add_argument(
        "--noise",
        choices=("additive", "proportional"),
        help="noise model: additive (constant sd, default) or proportional to the signal; "
        "the sd is estimated from the residuals in both",
    )
    fit.add_argument("--weighting", choices=("none", "relative"), default=None,
                     help="older spelling: relative = --noise proportional")
    fit.add_argument(
        "--interval",
        choices=("auto", "profile", "calibrated"),
        default="auto",
        help="interval threshold: F form (profile), bootstrap-calibrated, or auto (calibrated only "
        "where the F form undercovers: stiffness model, proportional noise)",
    )
    fit.add_argument(
        "--bootstrap",
        type=int,
        default=0,
        help="wild-bootstrap refits that widen the 68 %% interval (coverage then not tested)",
    )
    fit.add_argument(
        "--plot", default="tribospec_fit.png", help="PNG to write (default tribospec_fit.png)"
    )
    fit.add_argument("--no-plot", action="store_true", help="do not write a figure")
    fit.add_argument("--seed", type=seed_type, default=0, help="seed of the bootstrap")
    fit.add_argument("--json", action="store_true", help="print JSON")


def run(args) -> int:
    """Dispatch to simulate or fit."""
    return _simulate(args) if args.action == "simulate" else _fit(args)


def _simulate(args) -> int:
    import numpy as np

    from ..errors import ParameterError
    from ..models.tribospectroscopy import CONVENTION_TEXT, params_from_scene, solve, to_per_contact
    from ..scene import default_scene, load_scene

    scene = load_scene(args.scene) if args.scene else default_scene()
    over = {"law": args.law}
    ts = scene.tribospectroscopy
    convention = args.convention or (ts.convention if ts else "per-contact")
    if args.model:
        over["model"] = args.model
    if args.correlation_length is not None:
        over["correlation_length"] = args.correlation_length
    if args.contact_stiffness is not None:
        # 0 used to mean "not given" inside the model, so --contact-stiffness 0 silently took MDR.
        if not args.contact_stiffness > 0:
            raise ParameterError(
                "--contact-stiffness",
                "a stiffness > 0 N/m (omit it to use the MDR stiffness)",
                args.contact_stiffness,
            )
        over["contact_stiffness"] = args.contact_stiffness
    if args.amplitudes is not None:
        if any(a < 0 for a in args.amplitudes):
            raise ParameterError("--amplitudes", "amplitudes >= 0 m", args.amplitudes)
        given = np.asarray(args.amplitudes, dtype=float)
    else:
        given = np.asarray(
            ts.amplitudes if ts else params_from_scene(scene).amplitudes, dtype=float
        )
        if not ts:
            convention = "per-contact"
    over["amplitudes"] = tuple(to_per_contact(given, convention).tolist())
    res = solve(params_from_scene(scene, **over))
    rows = [
        {
            "amplitude_m": float(a),
            "amplitude_per_contact_m": float(ap),
            "force_N": float(f),
            "force_sq_N2": float(f2),
            "convention": convention,
        }
        for a, ap, f, f2 in zip(given, res.amplitude_m, res.force_N, res.force_sq_N2)
    ]
    out = {
        "model": res.model,
        "law": res.law,
        "convention": convention,
        "amplitude_convention": CONVENTION_TEXT[convention],
        "length_m": res.length_m,
        "rows": rows,
        "time_s": res.time_s,
    }
    for key in ("contact_stiffness_N_m", "shakedown_limit_m", "force0_N"):
        if key in res:
            out[key] = res[key]
    warnings = []
    if (
        scene.geometry.profile == "rough"
        and args.contact_stiffness is None
        and res.model == "stiffness"
    ):
        # stated, not silent: the probe tip contact is the sphere of [geometry].radius here
        warnings.append(
            "[geometry].profile = 'rough': the contact "
            "stiffness is that of the probe tip, the sphere "
            "of [geometry].radius; pass --contact-stiffness for the rough contact's stiffness"
        )
        import sys

        print(f"tribolmp tribospec: warning: {warnings[-1]}", file=sys.stderr)
    out["warnings"] = warnings
    if args.json:
        from . import emit_json

        emit_json(out)
    else:
        print(f"# {res.model} model; {CONVENTION_TEXT[convention]}; length {res.length_m:.4g} m")
        print("amplitude_m,force_N,force_sq_N2")
        for r in rows:
            print(f"{r['amplitude_m']:.6g},{r['force_N']:.6g},{r['force_sq_N2']:.6g}")
    return 0


def _fit(args) -> int:
    from ..models.tribospectroscopy import fit_length, read_curve_csv

    if not args.no_plot:
        from ..locking import prepare_file

        # Checked before the fit, so a bad --plot never costs the bootstrap and then a traceback.
        prepare_file(args.plot, "--plot")
    curve = read_curve_csv(args.data, args.convention)
    res = fit_length(
        curve,
        args.model,
        background=not args.no_background,
        noise=args.noise,
        weighting=args.weighting,
        n_boot=args.bootstrap,
        interval=args.interval,
        rng=args.seed,
    )
    out = {
        k: res[k]
        for k in (
            "length_m",
            "length_std_m",
            "model",
            "residual",
            "length_interval_m",
            "length_interval_95_m",
            "interval_levels",
            "interval_method",
            "noise_model",
            "coverage_tested",
            "coverage_conditions",
            "bounded",
            "aic",
            "force0_N",
            "background",
            "fitted_quantity",
            "convention",
            "amplitude_convention",
            "weighting",
            "n_points",
            "delta_aic",
            "model_ambiguous",
            "candidates",
            "message",
            "status",
            "time_s",
            "units",
        )
    }
    if not args.no_plot:
        from ..models.tribospectroscopy.plot import plot_fit

        out["plot"] = str(plot_fit(curve, res, args.plot))
    if args.json:
        from . import emit_json

        emit_json(out)
    else:
        print(res.message)
        print(f"residual (rms) {res.residual:.4g} {res.units['residual']}; AIC "
              + ", ".join(f"{m}: {c['aic']:.2f}" for m, c in res.candidates.items()))
        if "plot" in out:
            print(f"plot: {out['plot']}")
    return 0
