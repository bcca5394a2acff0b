"""``tribolmp info``: versions and capabilities."""

from __future__ import annotations

HELP = "versions of tribolmp, LAMMPS (packages), numpy, ase, MDAnalysis, MPI"


def configure(parser) -> None:
    """Add arguments."""
    parser.add_argument("--json", action="store_true", help="machine-readable output")


def gather() -> dict:
    """Collect version and capability information."""
    import importlib.metadata as md
    import os
    import platform

    from .. import __version__
    from ..lammps import lammps_info

    def ver(name: str) -> str:
        try:
            return md.version(name)
        except md.PackageNotFoundError:
            return "not installed"

    lmp = lammps_info()
    return {
        "tribolmp": __version__,
        "python": platform.python_version(),
        "numpy": ver("numpy"),
        "scipy": ver("scipy"),
        "ase": ver("ase"),
        "MDAnalysis": ver("MDAnalysis"),
        "matplotlib": ver("matplotlib"),
        "lammps": {
            "version": lmp["version"],
            "wheel": lmp["wheel"],
            "packages": lmp["packages"],
            "missing_packages": lmp["missing_packages"],
            "missing_styles": lmp["missing_styles"],
        },
        "mpi": {
            "enabled": lmp["mpi"],
            "library": lmp["mpi_library"],
            "mpich_wheel": lmp["mpich_wheel"],
            "ranks": lmp["ranks"],
        },
        "openmp_threads": lmp["threads"],
        "OMP_NUM_THREADS": os.environ.get("OMP_NUM_THREADS", "unset"),
    }


def run(args) -> int:
    """Print the information; only rank 0 prints under mpiexec."""
    info = gather()
    import os

    if int(os.environ.get("PMI_RANK", "0")) != 0:
        return 0
    if args.json:
        from . import emit_json

        emit_json(info)
        return 0
    lmp, mpi = info["lammps"], info["mpi"]
    req = "BPM, GRANULAR, MOLECULE"
    status = "all present" if not lmp["missing_packages"] else f"MISSING {lmp['missing_packages']}"
    lines = [
        f"tribolmp     {info['tribolmp']}",
        f"python       {info['python']}",
        f"numpy        {info['numpy']}",
        f"scipy        {info['scipy']}",
        f"ase          {info['ase']}",
        f"MDAnalysis   {info['MDAnalysis']}",
        f"matplotlib   {info['matplotlib']}",
        f"LAMMPS       {lmp['version']} (wheel {lmp['wheel']})",
        f"  required   {req}: {status}",
        "  styles     "
        + (
            "all required styles present"
            if not lmp["missing_styles"]
            else "MISSING " + ", ".join(lmp["missing_styles"])
        ),
        f"  packages   {' '.join(lmp['packages'])}",
        f"MPI          {mpi['library']} (mpich wheel {mpi['mpich_wheel']}), ranks = {mpi['ranks']}",
        f"OpenMP       {info['openmp_threads']} thread(s) "
        f"per rank (OMP_NUM_THREADS={info['OMP_NUM_THREADS']})",
    ]
    print("\n".join(lines))
    return 0
