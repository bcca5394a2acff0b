"""``tribolmp analysis``: measurements on MCA outputs.

``tribolmp analysis eq23-fit PROFILE.npz [--start S] [--min-relaxations R] [--json]`` fits the Eq.
23 coefficients on a surface profile h(x, t) (``profile.npz``: ``x`` [m], ``t`` [s], ``h`` [m] of
shape (nt, nx); written by every MCA run next to ``rates.json``).  JSON fields (SI): ``mu_per_s``,
``d0_m2_s``, ``dz``, ``dx_l2``, their ``*_err``, ``valid`` (per coefficient), ``reasons``,
``modes_used`` (indices of the modes used), ``stationary``, ``units`` and the per-mode table
``modes``.
"""

from __future__ import annotations

HELP = "measurements on MCA outputs (Eq. 23 fit of a surface profile)"


def configure(parser) -> None:
    """Add the ``eq23-fit`` subcommand."""
    sub = parser.add_subparsers(
        dest="action", metavar="ACTION", parser_class=type(parser), required=True
    )
    p = sub.add_parser(
        "eq23-fit",
        help="fit gamma = mu + D0 k^2 and S gamma = Dz + Dx l^2 k^2 on profile.npz",
        description="Fit the Eq. 23 coefficients on a surface profile h(x, t).",
    )
    p.add_argument("profile", help="profile.npz with x [m], t [s], h [m] (nt, nx)")
    p.add_argument("--start", type=float, default=None, help="analyse frames with t >= START (s)")
    p.add_argument(
        "--min-relaxations",
        type=float,
        default=10.0,
        help="relaxation times a mode must span at the "
             "2-sigma lower bound of its rate (default 10)",
    )
    p.add_argument("--max-gamma-dt", type=float, default=0.6,
                   help="largest gamma*dt of a usable mode (time resolution; default 0.6)")
    p.add_argument("--blocks", type=int, default=20, help="jackknife blocks (default 20)")
    p.add_argument("--json", action="store_true", help="print the result as JSON")


def run(args) -> int:
    """Read the profile, fit, print."""
    import math

    from ..analysis.eq23 import COEFFICIENTS, fit_eq23, read_profile
    from ..errors import ParameterError

    if not (math.isfinite(args.min_relaxations) and args.min_relaxations > 0):
        raise ParameterError("--min-relaxations", "a number > 0", args.min_relaxations)
    if not (math.isfinite(args.max_gamma_dt) and args.max_gamma_dt > 0):
        raise ParameterError("--max-gamma-dt", "a number > 0", args.max_gamma_dt)
    prof = read_profile(args.profile)
    res = fit_eq23(
        prof["x"],
        prof["t"],
        prof["h"],
        start_s=args.start,
        min_relaxations=args.min_relaxations,
        max_gamma_dt=args.max_gamma_dt,
        n_blocks=args.blocks,
    )
    res["profile"] = str(args.profile)
    if args.json:
        from . import emit_json

        emit_json(res)
        return 0
    print(
        f"profile: {args.profile}  ({res['n_frames']} frames, "
        f"dt {res['dt_s']:.3g} s, L {res['length_m']:.3g} m)"
    )
    print(f"modes used: {res['n_modes_used']} {res['modes_used']}  stationary: {res['stationary']} "
          f"(p = {res['stationarity_p']:.2g})")
    for c in COEFFICIENTS:
        unit = res["units"][c]
        if res["valid"][c]:
            print(f"{c:10s} = {res[c]:.4g} +- {res[f'{c}_err']:.2g} {unit}")
        else:
            print(f"{c:10s} = null (invalid: {res['reasons'][c]})")
    return 0
