"""The model contract shared by every tribolmp model (re-exported foundations).

Each model provides

* a frozen ``Params`` dataclass declared with :func:`~tribolmp.params.param`
  and validated in ``__post_init__`` by
  :func:`~tribolmp.params.validate_dataclass`, so that a bad value is rejected
  on construction with a one-line :class:`~tribolmp.errors.ParameterError`;
* a ``solve(params, *, method=..., rng=None) -> Result`` function, where
  ``method`` is chosen by name from a :class:`~tribolmp.results.MethodRegistry`;
* a :class:`~tribolmp.results.Result` carrying arrays *and* diagnostics.

The implementations live in the foundation modules :mod:`tribolmp.params`
(fields, range checks, messages) and :mod:`tribolmp.results` (Result,
MethodRegistry, timed), so that the scene, the analysis and the LAMMPS layer
use them without importing the models.  This module re-exports them for the
model packages.
"""

from __future__ import annotations

from ..params import (
    check_choice,
    check_finite,
    check_int,
    check_positive,
    check_range,
    describe_range,
)
from ..results import MethodRegistry, Result, timed

__all__ = [
    "Result",
    "MethodRegistry",
    "timed",
    "check_finite",
    "check_range",
    "check_positive",
    "check_choice",
    "check_int",
    "describe_range",
]
