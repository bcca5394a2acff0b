"""``tribolmp topography``: stochastic surface evolution (Eq. 23).

``tribolmp topography evolve --dim 1|2 --n N --dx DX --d0 D0 --dx-noise DX_NOISE
--dz DZ --mu MU --l L --dt DT --steps S [--replicas R] [--seed SEED]
[--scheme exact|euler] [--out DIR] --json``

prints ``{"k", "psd", "psd_theory", "time_s", "steps_per_s", ...}`` (SI).

``tribolmp topography info FILE [--pixel-size M] [--unit U] [--detrend none|mean|plane|curvature]
[--channel I] [--out DIR] [--json]``

reads a measured topography (any SurfaceTopography format, or tribolmp's own
files) and prints ``{"format", "grid", "size_m", "pixel_size_m", "rms_height_m",
"rms_gradient", "hurst", "unit_source", "psd", "files", ...}`` (SI); writes a
PNG (map or profile and PSD) and the PSD as CSV into ``--out``.
"""

from __future__ import annotations

from . import seed_type

HELP = "stochastic surface evolution (Eq. 23); info on measured topography files"

#: Default noise intensities: 1D in m^3/s; 2D in m^4/s (1D value x 10 nm, see run()).
DEFAULT_DX_NOISE_1D, DEFAULT_DZ_1D = 2.5e-20, 5.6e-20
DEFAULT_DX_NOISE_2D, DEFAULT_DZ_2D = 2.5e-28, 5.6e-28


def configure(parser) -> None:
    """Add the ``evolve`` subcommand."""
    sub = parser.add_subparsers(
        dest="action", metavar="ACTION", parser_class=type(parser), required=True
    )
    p = sub.add_parser(
        "evolve", help="evolve a periodic profile/surface and print its PSD against theory"
    )
    p.add_argument("--dim", type=int, default=1, help="1 (profile) or 2 (surface)")
    p.add_argument("--n", type=int, default=1024, help="grid points per side (even, >= 4)")
    p.add_argument("--dx", type=float, default=10e-9, help="grid spacing (m)")
    p.add_argument("--d0", type=float, default=1e-12, help="surface diffusion D0 (m^2/s)")
    p.add_argument(
        "--dx-noise",
        type=float,
        default=None,
        help="flux-noise intensity Dx (m^3/s 1D, m^4/s 2D; "
             "default 2.5e-20 m^3/s in 1D, 2.5e-28 m^4/s in 2D)",
    )
    p.add_argument(
        "--dz",
        type=float,
        default=None,
        help="transfer-noise intensity Dz (m^3/s 1D, m^4/s 2D; "
             "default 5.6e-20 m^3/s in 1D, 5.6e-28 m^4/s in 2D)",
    )
    p.add_argument("--mu", type=float, default=10.0, help="wear rate constant (1/s)")
    p.add_argument("--l", type=float, default=50e-9, help="step length of the flux noise (m)")
    p.add_argument(
        "--correlation-length",
        type=float,
        default=0.0,
        help="noise correlation length (m); 0 = delta",
    )
    p.add_argument("--dt", type=float, default=1e-2, help="time step (s)")
    p.add_argument("--steps", type=int, default=100, help="number of steps")
    p.add_argument(
        "--replicas", type=int, default=1, help="independent surfaces averaged in the PSD"
    )
    p.add_argument(
        "--seed", type=seed_type, default=None, help="random seed (default: fresh entropy)"
    )
    p.add_argument(
        "--scheme", default="exact", help="exact (OU per Fourier mode) or euler (lattice reference)"
    )
    p.add_argument(
        "--operator", default="spectral", help="exact scheme: spectral (k^2) or lattice operator"
    )
    p.add_argument("--precision", default="double", help="exact scheme: double or single")
    p.add_argument(
        "--out", default=None, help="folder for height maps (.npy + .json, .asc/.xyz) and psd.csv"
    )
    p.add_argument("--json", action="store_true", help="print the result as JSON")
    i = sub.add_parser(
        "info",
        help="format, size, rms height/gradient, Hurst "
             "exponent and PSD of a measured topography file",
    )
    i.add_argument(
        "file",
        help="topography file: x3p, sur, opd(x), datx, gwy, "
             "MetroPro, plu(x), vk, zon, di/spm, ibw, nc, ... "
        "(SurfaceTopography), or tribolmp .npy/.asc/.xyz",
    )
    i.add_argument("--pixel-size", type=float, default=None, dest="pixel_size",
                   help="grid spacing (m); overrides the file's metadata only when given")
    i.add_argument(
        "--unit",
        default=None,
        help="length unit of the file's numbers (m, mm, um, nm, ...) for files without one",
    )
    i.add_argument(
        "--detrend",
        default="none",
        choices=("none", "mean", "plane", "curvature"),
        help="detrending before the statistics",
    )
    i.add_argument(
        "--channel",
        type=int,
        default=None,
        help="data channel of a multi-channel file (default: the file's default)",
    )
    i.add_argument(
        "--out",
        default=".",
        help="folder for <stem>_topography.png and <stem>_psd.csv (default: .)",
    )
    i.add_argument("--no-figure", action="store_true", help="skip the PNG")
    i.add_argument("--json", action="store_true", help="print the result as JSON")


def run(args) -> int:
    """Dispatch ``evolve`` or ``info``."""
    if args.action == "info":
        return _info(args)
    return _evolve(args)


def _info(args) -> int:
    from pathlib import Path

    from ..models.topography.measured import topography_info
    from . import emit_json

    out = Path(args.out)
    stem = Path(args.file).stem
    info = topography_info(
        args.file,
        pixel_size=args.pixel_size,
        unit=args.unit,
        detrend=args.detrend,
        channel=args.channel,
        png=None if args.no_figure else out / f"{stem}_topography.png",
        psd_csv=out / f"{stem}_psd.csv",
    )
    if args.json:
        emit_json(info)
        return 0
    nx, ny = info["grid"]
    pixel = info["pixel_size_m"]
    print(
        f"{info['file']}: {info['format']} {info['kind']}, "
        f"grid {nx} x {ny}, size {info['size_m'][0]:.4g} x "
        f"{info['size_m'][1]:.4g} m, pixel "
        f"{pixel if pixel is None else format(pixel, '.4g')} m "
        f"(units: {info['unit_source']})"
    )
    grad = "n/a" if info["rms_gradient"] is None else f"{info['rms_gradient']:.4g}"
    hurst = "n/a" if info["hurst"] is None else f"{info['hurst']:.3g}"
    print(
        f"rms height {info['rms_height_m']:.4g} m; rms "
        f"{'gradient' if ny > 1 else 'slope'} {grad}; Hurst {hurst}; "
        f"missing points {info['missing_points']}; detrend {info['detrend']}"
    )
    for note in info["notes"]:
        print(f"note: {note}")
    for key, path in info["files"].items():
        print(f"{key}: {path}")
    return 0


def _evolve(args) -> int:
    """Validate, evolve, optionally write the maps, print a summary or JSON."""
    import numpy as np

    from ..errors import ParameterError
    from ..models.topography import TopographyParams, evolve, save_ascii_grid, save_height_map
    from . import emit_json

    # 2D intensities are per area (m^4/s): the 1D defaults times a 10 nm
    # slab (the default pixel), so the per-pixel noise variance, and with it
    # Rq, match the 1D default instead of being ~10^4 larger (issue 16).
    dim2 = args.dim == 2
    dx_noise = (
        args.dx_noise
        if args.dx_noise is not None
        else (DEFAULT_DX_NOISE_2D if dim2 else DEFAULT_DX_NOISE_1D)
    )
    dz = args.dz if args.dz is not None else (DEFAULT_DZ_2D if dim2 else DEFAULT_DZ_1D)
    params = TopographyParams(
        dim=args.dim, n=args.n, dx=args.dx, d0=args.d0, dx_noise=dx_noise, dz=dz, mu=args.mu,
        l=args.l, correlation_length=args.correlation_length, dt=args.dt, steps=args.steps,
        operator=args.operator, precision=args.precision,
    )
    if args.seed is not None and args.seed < 0:
        raise ParameterError("--seed", "an integer >= 0", args.seed)
    rng = np.random.default_rng(args.seed)
    from ..progress import Progress

    res = evolve(params, rng=rng, scheme=args.scheme, replicas=args.replicas,
                 progress=Progress("topography evolve", "steps", params.steps))
    files = {}
    if args.out:
        from pathlib import Path

        out = Path(args.out)
        h0 = res.h if res.replicas == 1 else res.h[0]
        npy, side = save_height_map(out / "height_map.npy", h0, params.pixel_size)
        files = {"npy": str(npy), "json": str(side)}
        ascii_name = "height_map.asc" if params.dim == 2 else "height_map.xyz"
        files["ascii"] = str(save_ascii_grid(out / ascii_name, h0, params.pixel_size))
        if (out / "height_map.nc").exists():
            files["netcdf"] = str(
                out / "height_map.nc"
            )  # written by save_height_map through SurfaceTopography
        if params.dim == 2 and "netcdf" in files:
            from ..models.topography.measured import write_surface

            files["x3p"] = str(write_surface(out / "height_map.x3p", h0, params.pixel_size))
        table = np.column_stack([res.k, res.psd, res.psd_theory])
        np.savetxt(
            out / "psd.csv", table, delimiter=",", header="k_1_per_m,psd,psd_theory", comments=""
        )
        files["psd_csv"] = str(out / "psd.csv")
    if args.json:
        emit_json(
            {
                "k": res.k,
                "psd": res.psd,
                "psd_theory": res.psd_theory,
                "psd_stationary": res.psd_stationary,
                "time_s": res.time_s,
                "steps_per_s": res.steps_per_s,
                "steps": params.steps,
                "dt_s": params.dt,
                "t_s": res.t_s,
                "dim": params.dim,
                "n": params.grid_points,
                "dx_m": params.pixel_size,
                "replicas": res.replicas,
                "scheme": res.scheme,
                "operator": res.operator,
                "rq_m": res.rq,
                "rq_theory_m": res.rq_theory,
                "mean_m": res.mean,
                "k1_1_per_m": res.k1,
                "k2_1_per_m": res.k2,
                "roughness": res.roughness,
                "files": files,
                "status": res.status,
                "message": res.message,
                "units": {
                    "k": "1/m",
                    "psd": f"m^{params.dim + 2}",
                    "psd_theory": f"m^{params.dim + 2}",
                    "time_s": "s",
                    "steps_per_s": "1/s",
                },
            }
        )
    else:
        print(res.message)
        print(f"Rq = {res.rq:.4g} m (theory {res.rq_theory:.4g} m); {res.steps_per_s:.4g} steps/s; "
              f"wall {res.time_s:.3g} s")
        for key, path in files.items():
            print(f"{key}: {path}")
    return 0
