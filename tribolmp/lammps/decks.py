"""Locate the LAMMPS input decks shipped with tribolmp.

The decks live in the repository's top-level ``lammps_inputs/`` folder so that
they run standalone (``lmp -in lammps_inputs/mca_friction.in -var ...``).  They
are shipped as package data through the relative symlink
``tribolmp/data/lammps_inputs -> ../../lammps_inputs``, which setuptools
follows when it builds a wheel.  An editable install finds the repository
folder directly.
"""

from __future__ import annotations

from pathlib import Path

from ..errors import MissingFeatureError

__all__ = ["deck_path", "decks_dir", "laws_dir", "list_decks"]

_PKG = Path(__file__).resolve().parents[1]


def decks_dir() -> Path:
    """Folder holding the ``*.in`` decks (package data first, then the repository)."""
    for cand in (_PKG / "data" / "lammps_inputs", _PKG.parent / "lammps_inputs"):
        if cand.is_dir() and any(cand.glob("*.in")):
            return cand
    raise MissingFeatureError(
        f"LAMMPS decks: expected a folder lammps_inputs/ with *.in files next to {_PKG}, got none"
    )


def deck_path(name: str) -> Path:
    """Path of deck ``name`` (with or without ``.in``).

    Raises
    ------
    MissingFeatureError
        When no such deck is installed.
    """
    fname = name if name.endswith(".in") else f"{name}.in"
    path = decks_dir() / fname
    if not path.is_file():
        raise MissingFeatureError(f"LAMMPS deck: expected one of {list_decks()}, got {name!r}")
    return path


def list_decks() -> list[str]:
    """Names of the installed decks (without ``.in``)."""
    return sorted(p.stem for p in decks_dir().glob("*.in"))


def laws_dir() -> Path:
    """Folder of the bond-law deck fragments ``laws/<keyword>.in``.

    See :mod:`tribolmp.lammps.laws`.
    """
    return decks_dir() / "laws"
