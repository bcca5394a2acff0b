"""``tribolmp macro stick-slip|oscillate|squeeze``: the rigid body on MDR contact springs."""

from __future__ import annotations

HELP = "rigid body on contact springs: stick-slip and oscillation"


def configure(parser) -> None:
    """Add the ``stick-slip``, ``oscillate`` and ``squeeze`` subcommands."""
    sub = parser.add_subparsers(
        dest="action", metavar="ACTION", parser_class=type(parser), required=True
    )
    ss = sub.add_parser("stick-slip", help="body pulled through a spring at constant velocity")
    ss.add_argument("scene", nargs="?", help="TOML scene file (default: the embedded scene)")
    ss.add_argument(
        "--law", choices=("constant", "velocity-weakening"), default="constant", help="friction law"
    )
    ss.add_argument("--mu-s", type=float, help="static coefficient (default: the scene's mu)")
    ss.add_argument(
        "--mu-k",
        type=float,
        help="kinetic coefficient (constant) or high-speed "
             "limit (velocity-weakening; default 0.75 mu_s)",
    )
    ss.add_argument(
        "--v-c", type=float, default=1e-3, help="velocity-weakening: characteristic speed in m/s"
    )
    ss.add_argument(
        "--friction-file", help="rates.json (mu) or mu(v) table (CSV/JSON: velocity_m_s, mu)"
    )
    ss.add_argument(
        "--contact", choices=("rigid", "mdr"), default="rigid", help="contact during stick"
    )
    ss.add_argument("--contact-stiffness", type=float, help="constant contact stiffness in N/m")
    ss.add_argument(
        "--unload-time",
        type=float,
        default=0.0,
        help="normal load falls linearly to 0 at this time (s)",
    )
    ss.add_argument("--duration", type=float, help="simulated time in s")
    ss.add_argument("--velocity", type=float, help="drive velocity in m/s")
    ss.add_argument(
        "--method", default="auto", help="auto, analytic, rk45, radau, radau-rk45, bdf, lsoda"
    )
    ss.add_argument(
        "--contact-gap",
        type=float,
        help="with [lubricant]: gap in m where the asperities touch; "
             "the load reaches the contact through the squeeze film",
    )
    ss.add_argument(
        "--series", action="store_true", help="include the (downsampled) time series in the JSON"
    )
    ss.add_argument("--json", action="store_true", help="print JSON")
    osc = sub.add_parser("oscillate", help="prescribed tangential oscillation with micro-slip")
    osc.add_argument("scene", nargs="?", help="TOML scene file (default: the embedded scene)")
    osc.add_argument("--amplitude", type=float, required=True, help="tangential amplitude in m")
    osc.add_argument(
        "--frequency", type=float, help="Hz (default: the scene's tribospectroscopy frequency)"
    )
    osc.add_argument("--cycles", type=int, default=3)
    osc.add_argument("--steps-per-cycle", type=int, default=200)
    osc.add_argument("--mu", type=float, help="friction coefficient (default: the scene's)")
    osc.add_argument("--json", action="store_true", help="print JSON")
    sq = sub.add_parser(
        "squeeze", help="normal approach of the body through the squeeze film ([lubricant])"
    )
    sq.add_argument(
        "scene",
        nargs="?",
        help="TOML scene file with a [lubricant] section (default: the embedded scene)",
    )
    sq.add_argument(
        "--normal-force",
        "--load",
        dest="load",
        type=float,
        help="normal load in N (default [load].normal_force); --load is the old spelling",
    )
    sq.add_argument(
        "--gap", type=float, help="initial film thickness in m (default [lubricant].film_thickness)"
    )
    sq.add_argument(
        "--duration", type=float, help="simulated time in s (default [kinematics].duration)"
    )
    sq.add_argument(
        "--mass", type=float, help="body mass in kg, 0 = overdamped (default [kinematics].mass)"
    )
    sq.add_argument(
        "--contact-gap",
        type=float,
        default=0.0,
        help="gap in m where the MDR contact engages (0 = never)",
    )
    sq.add_argument("--json", action="store_true", help="print JSON")


def run(args) -> int:
    """Dispatch to the drives and the normal approach."""
    from ..scene import default_scene, load_scene

    scene = load_scene(args.scene) if args.scene else default_scene()
    out = {"stick-slip": _stick_slip, "oscillate": _oscillate, "squeeze": _squeeze}[args.action](
        args, scene
    )
    if args.json:
        from . import emit_json

        emit_json(out)
    else:
        for k, v in out.items():
            if not isinstance(v, (list, dict)):
                print(f"{k}: {v}")
    return 0


def _profile_rng(scene):
    """Return the random generator of a rough scene's MDR profile.

    Drawn from ``[scene].seed`` (explicit, reproducible).
    """
    import numpy as np

    return np.random.default_rng(scene.scene.seed)


def _stick_slip(args, scene) -> dict:
    import numpy as np

    from ..models.friction import friction_coefficient
    from ..models.macro import load_friction_law, make_friction_law, stick_slip_from_scene

    mu0 = friction_coefficient(scene).mu
    if args.friction_file:
        law = load_friction_law(args.friction_file, mu_s=args.mu_s)
    elif args.law == "constant":
        law = make_friction_law(
            "constant", mu_s=mu0 if args.mu_s is None else args.mu_s, mu_k=args.mu_k
        )
    else:
        mu_s = mu0 if args.mu_s is None else args.mu_s
        law = make_friction_law("velocity-weakening", mu_s=mu_s, mu_k=args.mu_k, v_c=args.v_c)
    over = {"unload_time": args.unload_time}
    if args.duration is not None:
        over["duration"] = args.duration
    if args.velocity is not None:
        over["drive_velocity"] = args.velocity
    res = stick_slip_from_scene(
        scene,
        contact_law=args.contact,
        law=law,
        contact_stiffness=args.contact_stiffness,
        method=args.method,
        contact_gap=args.contact_gap,
        rng=_profile_rng(scene),
        **over,
    )
    f = res.drive_force
    out = {
        "method": res.method,
        "friction_law": type(law).__name__,
        "mu_s": law.mu_s,
        "contact": args.contact if args.contact_stiffness is None else "constant stiffness",
        "n_transitions": res.n_transitions,
        "n_stick": sum(e["to_phase"] == "stick" for e in res.events),
        "force_max_N": float(f.max()),
        "force_min_N": float(f.min()),
        "final_position_m": float(res.x[-1]),
        "final_velocity_m_s": float(res.v[-1]),
        "nfev": res.nfev,
        "time_s": res.time_s,
        "message": res.message,
        "events": res.events[:1000],
        "units": {
            "force_max_N": "N",
            "final_position_m": "m",
            "final_velocity_m_s": "m/s",
            "time_s": "s",
        },
    }
    if "squeeze" in res:
        out["squeeze_final_gap_m"] = float(res.squeeze.gap[-1])
        out["squeeze_final_contact_force_N"] = float(res.squeeze.contact_force[-1])
    if args.series:
        idx = np.unique(np.linspace(0, res.t.size - 1, min(res.t.size, 2000)).astype(int))
        out["series"] = {k: res[k][idx] for k in ("t", "x", "v", "drive_force", "phase")}
    return out


def _oscillate(args, scene) -> dict:
    from ..models.macro import oscillation_from_scene
    from ..progress import Progress

    res = oscillation_from_scene(
        scene,
        args.amplitude,
        frequency=args.frequency,
        cycles=args.cycles,
        steps_per_cycle=args.steps_per_cycle,
        mu=args.mu,
        rng=_profile_rng(scene),
        progress=Progress("macro oscillate", "steps", args.cycles * args.steps_per_cycle),
    )
    spc = args.steps_per_cycle
    last = slice(res.force_x.size - spc - 1, res.force_x.size)
    return {
        "amplitude_m": args.amplitude,
        "normal_force_N": float(res.force_n[-1]),
        "indentation_m": res.indentation_m,
        "force_amplitude_N": float(abs(res.force_x[last]).max()),
        "dissipation_per_cycle_J": res.dissipation_per_cycle_J,
        "stiffness_x_N_m": res.stiffness_x,
        "time_s": res.time_s,
        "units": {
            "amplitude_m": "m",
            "force_amplitude_N": "N",
            "dissipation_per_cycle_J": "J",
            "stiffness_x_N_m": "N/m",
        },
    }


def _squeeze(args, scene) -> dict:
    from ..models.macro import contact_from_scene, squeeze_approach, squeeze_params_from_scene

    over = {
        k: v
        for k, v in (
            ("normal_force", args.load),
            ("gap", args.gap),
            ("duration", args.duration),
            ("mass", args.mass),
        )
        if v is not None
    }
    p = squeeze_params_from_scene(scene, contact_gap=args.contact_gap, **over)
    res = squeeze_approach(
        p, contact_from_scene(scene, rng=_profile_rng(scene)) if p.contact_gap > 0 else None
    )
    return {
        "load_N": p.normal_force,
        "normal_force_N": p.normal_force,
        "initial_gap_m": p.gap,
        "final_gap_m": float(res.gap[-1]),
        "final_film_force_N": float(res.film_force[-1]),
        "final_contact_force_N": float(res.contact_force[-1]),
        "alpha_N_s": float(res.alpha),
        "mass_kg": p.mass,
        "nfev": res.nfev,
        "time_s": res.time_s,
        "message": res.message,
        "units": {
            "load_N": "N",
            "initial_gap_m": "m",
            "final_gap_m": "m",
            "final_film_force_N": "N",
            "final_contact_force_N": "N",
            "alpha_N_s": "N s",
            "time_s": "s",
        },
    }
