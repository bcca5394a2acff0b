"""``tribolmp contact``: quick MDR / BEM contact calculations with JSON output.

Only composes library calls from :mod:`tribolmp.models.contact`; no physics here.
"""

from __future__ import annotations

import argparse
import sys

from . import emit_json, float_list, seed_type

HELP = "contact mechanics: MDR and half-space BEM"


def configure(parser: argparse.ArgumentParser) -> None:
    """Add the ``axisymmetric`` and ``rough`` subcommands."""
    sub = parser.add_subparsers(
        dest="contact_command", metavar="SUBCOMMAND", parser_class=type(parser), required=True
    )

    a = sub.add_parser(
        "axisymmetric",
        help="sphere, cone or flat punch on a half-space",
        description="Force and contact radius of an axisymmetric rigid indenter (SI units).",
    )
    a.add_argument(
        "--profile",
        choices=("sphere", "cone", "flat", "power"),
        default="sphere",
        help="indenter shape",
    )
    a.add_argument("--radius", type=float, help="sphere radius or flat-punch radius (m)")
    a.add_argument(
        "--half-angle",
        type=float,
        dest="half_angle",
        help="cone half-angle from the axis (deg); f(r) = r/tan(angle)",
    )
    a.add_argument("--exponent", type=float, help="power law f = c r^n: n")
    a.add_argument("--coefficient", type=float, help="power law f = c r^n: c (m^(1-n))")
    a.add_argument(
        "--E-star",
        "--modulus",
        dest="modulus",
        type=float,
        required=True,
        help="effective modulus E* (Pa); --modulus is the old spelling",
    )
    a.add_argument(
        "--indentation",
        type=float,
        required=True,
        help="rigid indentation d (m); negative only with adhesion",
    )
    a.add_argument(
        "--work-of-adhesion",
        type=float,
        default=0.0,
        dest="work_of_adhesion",
        help="Dupre work of adhesion (J/m^2), JKR via Hess's rule",
    )
    a.add_argument("--method", choices=("mdr", "bem"), default="mdr", help="solver (default mdr)")
    a.add_argument("--springs", type=int, default=2001, help="MDR springs (default 2001)")
    a.add_argument("--grid", type=int, default=128, help="BEM grid points per side (default 128)")
    a.add_argument("--json", action="store_true", help="print JSON")

    r = sub.add_parser(
        "rough",
        help="rough surface: stiffness, force and approach vs pressure",
        description="Rough-surface normal contact against nominal pressure (SI units).",
    )
    r.add_argument(
        "--surface",
        required=True,
        help="height map: .npy (2D, m; pixel size from its sidecar JSON), .asc/.xyz, "
        "or any instrument file SurfaceTopography reads (x3p, "
        "sur, opd, datx, gwy, plu, nc, ...; units from the file)",
    )
    r.add_argument(
        "--unit",
        default=None,
        help="length unit of a surface file that states none (m, mm, um, nm)",
    )
    r.add_argument(
        "--detrend",
        default="none",
        choices=("none", "mean", "plane", "curvature"),
        help="detrend the surface first",
    )
    r.add_argument(
        "--fill-missing",
        action="store_true",
        help="fill missing data points (harmonic interpolation) instead of refusing the file",
    )
    r.add_argument(
        "--pixel-size",
        type=float,
        dest="pixel_size",
        help="grid spacing (m); default from the sidecar JSON 'pixel_size_m'",
    )
    r.add_argument(
        "--E-star",
        "--modulus",
        dest="modulus",
        type=float,
        required=True,
        help="effective modulus E* (Pa); --modulus is the old spelling",
    )
    r.add_argument(
        "--pressures", type=float_list, required=True, help="nominal pressures p1,p2,... (Pa)"
    )
    r.add_argument(
        "--method",
        choices=("mdr", "bem"),
        default="mdr",
        help="MDR ensemble or 3D BEM (default mdr)",
    )
    r.add_argument(
        "--periodic",
        action="store_true",
        help="BEM: periodic cell (default: rigid rough square punch of side N*DX)",
    )
    r.add_argument("--realizations", type=int, default=16, help="MDR ensemble size (default 16)")
    r.add_argument("--seed", type=seed_type, default=0, help="seed of the MDR ensemble (default 0)")
    r.add_argument(
        "--json", action="store_true", help="print JSON (a list with one object per pressure)"
    )


def run(args: argparse.Namespace) -> int:
    """Dispatch to the subcommand."""
    if args.contact_command == "axisymmetric":
        return _axisymmetric(args)
    return _rough(args)


def _axisymmetric(args) -> int:
    from ..errors import ParameterError
    from ..models.contact import AxisymmetricParams, solve
    from ..params import check_positive

    check_positive("--E-star/--modulus", args.modulus, "Pa")
    kw = dict(
        profile=args.profile,
        E_star=args.modulus,
        indentation=args.indentation,
        work_of_adhesion=args.work_of_adhesion,
        springs=args.springs,
        grid=args.grid,
    )
    need = {
        "sphere": ("radius",),
        "flat": ("radius",),
        "cone": ("half_angle",),
        "power": ("exponent", "coefficient"),
    }[args.profile]
    names = {
        "radius": "radius",
        "half_angle": "half_angle_deg",
        "exponent": "exponent",
        "coefficient": "coefficient",
    }
    for opt in need:
        value = getattr(args, opt)
        if value is None:
            raise ParameterError(
                f"--{opt.replace('_', '-')}", f"a value for --profile {args.profile}", None
            )
        kw[names[opt]] = value
    res = solve(AxisymmetricParams(**kw), method=args.method)
    out = {
        "force": res.force,
        "contact_radius": res.contact_radius,
        "time_s": res.time_s,
        "indentation": res.indentation,
        "method": res.method,
    }
    for key in (
        "pull_off_force",
        "pull_off_force_displacement_control",
        "stiffness",
        "springs",
        "grid",
        "nit",
    ):
        if key in res and (key != "nit" or res.method == "bem"):
            out[key] = res[key]
    for line in res.get("warnings", []):
        print(f"warning: {line}", file=sys.stderr)
    if res.get("warnings"):
        out["warnings"] = res["warnings"]
    if args.json:
        emit_json(out)
    else:
        for k, v in out.items():
            print(f"{k:36s} {v:.9g}" if isinstance(v, float) else f"{k:36s} {v}")
    return 0


def _rough(args) -> int:
    import numpy as np

    from ..errors import ParameterError
    from ..models.base import check_positive
    from ..models.contact import solve_rough
    from ..models.contact.solve import load_surface

    check_positive("--E-star/--modulus", args.modulus, "Pa")
    if args.pixel_size is not None:
        check_positive("pixel_size", args.pixel_size, "m")
    h, dx = load_surface(args.surface, args.pixel_size, unit=args.unit, detrend=args.detrend,
                         missing="fill" if args.fill_missing else "refuse")
    if dx is None:
        raise ParameterError(
            "--pixel-size", "a grid spacing in m (no sidecar JSON with pixel_size_m found)", None
        )
    res = solve_rough(
        h, dx, args.modulus, args.pressures, method=args.method, periodic=args.periodic,
        realizations=args.realizations, rng=np.random.default_rng(args.seed),
    )
    rows = res.rows
    closed = [(r["pressure"], r["closed_fraction"]) for r in rows if r.get("warnings")]
    if closed:
        # One line for the whole run; the per-pressure lines are in the JSON rows' "warnings".
        where = ", ".join(f"{p:g} Pa ({c:.0%})" for p, c in closed)
        print(
            "warning: more than 10 % of the MDR lines are fully "
            f"in contact at {where}: the stiffness there is "
            "the punch limit E*L, not a roughness prediction (use --method bem --periodic)",
            file=sys.stderr,
        )
    if args.json:
        emit_json(rows)
    else:
        keys = [k for k in rows[0] if isinstance(rows[0][k], (int, float))]
        print(" ".join(f"{k:>14s}" for k in keys))
        for row in rows:
            print(" ".join(f"{row[k]:14.6g}" for k in keys))
    return 0
