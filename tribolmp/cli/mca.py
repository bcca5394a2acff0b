"""``tribolmp mca``: movable cellular automata friction on LAMMPS.

``tribolmp mca run [SCENE.toml] [--dim 2|3] [--velocity V] [--pressure P]
[--time T] [--preset smoke|default|paper] [--np N] [--out DIR] [--resume | --overwrite]
[--json]``

``tribolmp mca material-test --law LAW --test uniaxial|shear [--dim 2|3] [--pressure P]
[--mode tension|compression] [--nu NU] [--json]``

``tribolmp mca plugin-path [--rebuild]``: build (cached) and print the MCA plugin's path, for
standalone decks: ``lmp -in deck.in -var plugin $(tribolmp mca plugin-path)``.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from . import seed_type

HELP = "movable cellular automata friction on LAMMPS"

#: JSON fields printed by ``mca run --json`` (a contract checked by others).
JSON_FIELDS = (
    "mu",
    "mu_err",
    "layer_depth_m",
    "diffusion_m2_s",
    "transfer_rate",
    "atom_steps_per_s",
    "time_s",
)


def configure(parser: argparse.ArgumentParser) -> None:
    """Add the ``run`` subcommand."""
    sub = parser.add_subparsers(dest="mca_command", metavar="SUBCOMMAND", parser_class=type(parser))
    sub.required = True
    r = sub.add_parser(
        "run",
        help="run the MCA friction experiment",
        description="Run the MCA friction experiment.",
    )
    r.add_argument(
        "scene", nargs="?", help="scene TOML ([nanoscale] and [material]); default: the preset"
    )
    r.add_argument("--dim", type=int, choices=(2, 3), help="spatial dimension")
    r.add_argument("--velocity", type=float, help="sliding velocity (m/s)")
    r.add_argument("--pressure", type=float, help="normal pressure (Pa)")
    r.add_argument("--time", type=float, help="simulated time (s)")
    r.add_argument(
        "--preset", choices=("smoke", "default", "paper"), help="size/time preset (default: smoke)"
    )
    r.add_argument(
        "--bond-style",
        choices=("mca", "bpm/spring/plastic", "bpm/rotational"),
        help="interaction law (default: the scene's)",
    )
    r.add_argument(
        "--np", type=int, default=1, help="MPI ranks (runs under the mpich wheel's mpiexec)"
    )
    r.add_argument("--seed", type=seed_type, help="seed (default: the scene's [scene].seed)")
    r.add_argument("--out", default="mca_run", help="output directory (default ./mca_run)")
    r.add_argument(
        "--resume", action="store_true", help="continue from the newest restart file in --out"
    )
    r.add_argument(
        "--overwrite",
        action="store_true",
        help="discard an earlier run in --out (without it, a folder holding a run is refused)",
    )
    r.add_argument("--json", action="store_true", help="print the result as JSON")
    r.add_argument(
        "--set",
        action="append",
        default=[],
        metavar="NAME=VALUE",
        help="expert: replace a deck variable (LAMMPS nano units) after validation; "
        "recorded in meta.json (repeatable)",
    )

    m = sub.add_parser(
        "material-test",
        help="measure E, nu, yield, ultimate and shear yield of an interaction law",
        description="Material test of an MCA interaction law on a periodic lattice block.",
    )
    m.add_argument("--law", default="mca", choices=("mca", "bpm/spring/plastic", "bpm/rotational"))
    m.add_argument("--test", default="uniaxial", choices=("uniaxial", "shear", "hydro"))
    m.add_argument("--dim", type=int, default=2, choices=(2, 3), help="spatial dimension")
    m.add_argument("--pressure", type=float, default=0.0, help="superimposed pressure (Pa)")
    m.add_argument("--mode", default="tension", choices=("tension", "compression"))
    m.add_argument("--nu", type=float, help="Poisson ratio (default 0.3)")
    m.add_argument("--json", action="store_true", help="print the result as JSON")

    pp = sub.add_parser(
        "plugin-path",
        help="build (cached) and print the path of the MCA LAMMPS plugin",
        description="Build the MCA plugin if needed and print the path of its shared object.",
    )
    pp.add_argument("--rebuild", action="store_true", help="compile even if cached")


def run(args: argparse.Namespace) -> int:
    """Dispatch ``tribolmp mca SUBCOMMAND``; no physics here."""
    if args.mca_command == "material-test":
        return _material_test(args)
    if args.mca_command == "plugin-path":
        from ..lammps.plugin import plugin_path

        print(plugin_path(rebuild=args.rebuild))
        return 0
    return _run(args)


def _material_test(args: argparse.Namespace) -> int:
    from ..lammps.law_mca import McaLaw
    from ..lammps.material_test import JSON_FIELDS, run_material_test

    params = McaLaw(dim=args.dim, **({"poisson_ratio": args.nu} if args.nu is not None else {}))
    res = run_material_test(
        args.law, args.test, args.dim, pressure=args.pressure, params=params, mode=args.mode
    )
    extra = ("test", "mode", "shear_modulus_Pa", "links_broken", "natoms", "plane_strain")
    payload = {k: res.get(k) for k in (*JSON_FIELDS, *extra)}
    if args.json:
        from . import emit_json

        emit_json(payload)
    else:
        for k, v in payload.items():
            print(f"{k}: {v}")
    return 0


def _overrides(items: list[str]) -> dict[str, str]:
    """``--set NAME=VALUE`` pairs; one-line error for a malformed one."""
    from ..errors import ParameterError

    out = {}
    for item in items:
        name, sep, value = item.partition("=")
        if not sep or not name or not value:
            raise ParameterError("--set", "NAME=VALUE (a deck variable)", item)
        out[name] = value
    return out


def _run(args: argparse.Namespace) -> int:
    """Compose scene -> params -> run_mca; no physics here."""
    from ..lammps.mca import params_from_scene, preset_params, run_mca
    from ..scene import default_scene, load_scene

    scene = load_scene(args.scene) if args.scene else default_scene()
    if args.scene:
        params = params_from_scene(scene)
        if args.preset:
            params = preset_params(
                args.preset, **{k: v for k, v in _scene_overrides(params).items()}
            )
    else:
        params = preset_params(args.preset or "smoke")
    changes = {
        "dim": args.dim,
        "sliding_velocity": args.velocity,
        "pressure": args.pressure,
        "duration": args.time,
        "bond_style": args.bond_style,
    }
    changes = {k: v for k, v in changes.items() if v is not None}
    if changes:
        params = params.replace(**changes)
    from ..locking import DirLock, prepare_dir

    seed = args.seed if args.seed is not None else scene.scene.seed
    out = prepare_dir(args.out, "--out")
    with DirLock(out, what="output folder"):
        res = run_mca(
            params,
            out,
            seed=seed,
            resume=args.resume,
            np=args.np,
            overrides=_overrides(args.set),
            on_conflict="overwrite" if args.overwrite else "refuse",
        )
    payload = {"rates_json": res.get("rates_path"), "out_dir": res["out_dir"]}
    payload.update({k: res.get(k) for k in JSON_FIELDS})
    payload.update(
        {
            "mu_raw": res.get("mu_raw"),
            "wall_time_s": res["wall_time_s"],
            "natoms": res["natoms"],
            "nprocs": res["nprocs"],
            "status": res["status"],
            "message": res["message"],
            "units": res["units"],
        }
    )
    if args.json:
        from . import emit_json

        emit_json(payload)
    else:
        print(f"rates: {payload['rates_json']}")
        for k in JSON_FIELDS:
            print(f"{k}: {payload[k]}")
    for line in _rates_warnings(payload.get("rates_json")):
        print(f"warning: {line}", file=sys.stderr)
    return 0


def _rates_warnings(rates_path) -> list[str]:
    """List what a user must not miss in rates.json: unsteady mu, no sheared layer, warnings."""
    import json

    try:
        rates = json.loads(Path(rates_path).read_text())
    except (OSError, TypeError, ValueError):
        return []
    lines = []
    if rates.get("mu_steady") is False:
        lines.append("mu is NOT steady: it is the mean of the run's second half; "
                     "run longer for a steady value")
    if not rates.get("layer_depth_m"):
        lines.append("no sheared (quasi-liquid) layer was measured in this run")
    return lines + [str(w) for w in rates.get("warnings", [])]


def _scene_overrides(params) -> dict:
    """Scene values that a --preset must not overwrite (everything but the size/time fields)."""
    from dataclasses import asdict

    from ..lammps.mca import PRESETS

    sized = set().union(*(set(p) for p in PRESETS.values())) | {"preset"}
    return {k: v for k, v in asdict(params).items() if k not in sized}
