"""Explicit random number generators.

Randomness enters tribolmp only through a :class:`numpy.random.Generator`
passed by the caller.  Global numpy state is never used.  LAMMPS seeds are
derived from the generator so that a whole chain is reproducible from one
integer seed.
"""

from __future__ import annotations

import numpy as np

__all__ = ["as_generator", "lammps_seed", "spawn"]


def as_generator(rng: np.random.Generator | int | None) -> np.random.Generator:
    """Return a Generator; an int seeds a new one, ``None`` gives fresh entropy.

    Parameters
    ----------
    rng : Generator, int or None
        Source of randomness.
    """
    if isinstance(rng, np.random.Generator):
        return rng
    if rng is None or isinstance(rng, (int, np.integer)):
        return np.random.default_rng(rng)
    raise TypeError(
        f"rng: expected a numpy.random.Generator, an int or None, got {type(rng).__name__}"
    )


def lammps_seed(rng: np.random.Generator) -> int:
    """Draw a seed valid for LAMMPS random number generators (1 ... 900 000 000)."""
    return int(rng.integers(1, 900_000_000))


def spawn(rng: np.random.Generator, n: int) -> list[np.random.Generator]:
    """Split ``rng`` into ``n`` statistically independent child generators (one per replica)."""
    return list(rng.spawn(n))
