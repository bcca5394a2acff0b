"""Results with diagnostics and named method registries: the model contract's data types.

Each model provides

* a frozen ``Params`` dataclass, validated in ``__post_init__`` with
  :mod:`tribolmp.params`, so that a bad value is rejected on construction with a
  one-line :class:`~tribolmp.errors.ParameterError`;
* a ``solve(params, *, method=..., rng=None) -> Result`` function, where
  ``method`` is chosen by name from a :class:`MethodRegistry` (as
  :func:`scipy.integrate.solve_ivp` does);
* a :class:`Result` carrying arrays *and* diagnostics (status, message,
  iterations, wall time), like scipy's ``OdeResult``.

Foundation module (the analysis and the LAMMPS layer use it too): it imports
only :mod:`tribolmp.errors`, :mod:`tribolmp.jsonio` and the standard library.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any

from .errors import ParameterError

__all__ = ["Result", "MethodRegistry", "timed"]


class Result(dict):
    """Dictionary with attribute access that carries a model's diagnostics.

    Standard keys (always present):

    ``status``
        0 on success, a negative number on failure, positive for warnings.
    ``message``
        Human-readable one-line summary.
    ``method``
        Name of the method that produced it.
    ``time_s``
        Wall time in seconds.
    ``nit``
        Number of iterations / steps (0 where not meaningful).
    ``units``
        Mapping from result key to its SI unit string.

    Examples
    --------
    >>> r = Result(force=1.0, units={"force": "N"})
    >>> r.force
    1.0
    """

    _defaults = {"status": 0, "message": "", "method": "", "time_s": 0.0, "nit": 0}

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        for key, value in self._defaults.items():
            self.setdefault(key, value)
        self.setdefault("units", {})

    def __getattr__(self, name: str) -> Any:
        try:
            return self[name]
        except KeyError as exc:
            raise AttributeError(
                f"result has no field {name!r}; available: {sorted(self)}"
            ) from exc

    def __setattr__(self, name: str, value: Any) -> None:
        self[name] = value

    def __dir__(self) -> list[str]:  # pragma: no cover - convenience
        return sorted(set(super().__dir__()) | set(self))

    @property
    def success(self) -> bool:
        """True when ``status`` is not negative."""
        return self["status"] >= 0

    def to_json_dict(self) -> dict[str, Any]:
        """Return a JSON-serialisable copy (arrays become lists, numpy scalars floats)."""
        from .jsonio import jsonable

        return jsonable(dict(self))


@dataclass
class MethodRegistry:
    """Named registry of solver implementations.

    Parameters
    ----------
    kind : str
        What the methods solve, used in error messages (e.g. ``"contact"``).
    """

    kind: str
    _methods: dict[str, Callable[..., Any]] = field(default_factory=dict)

    def register(self, name: str) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
        """Register the decorated function under ``name``."""

        def deco(func: Callable[..., Any]) -> Callable[..., Any]:
            if name in self._methods:
                raise KeyError(f"{self.kind} method {name!r} registered twice")
            self._methods[name] = func
            return func

        return deco

    def get(self, name: str, field_name: str = "method") -> Callable[..., Any]:
        """Return the implementation named ``name`` or raise a one-line ParameterError."""
        try:
            return self._methods[name]
        except (KeyError, TypeError):
            raise ParameterError(field_name, f"one of {sorted(self._methods)}", name) from None

    def __contains__(self, name: object) -> bool:
        return name in self._methods

    def __iter__(self) -> Iterator[str]:
        return iter(self._methods)

    @property
    def names(self) -> list[str]:
        """Registered method names."""
        return sorted(self._methods)


@contextmanager
def timed(result: Result) -> Iterator[Result]:
    """Context manager that stores the elapsed wall time in ``result['time_s']``."""
    t0 = time.perf_counter()
    try:
        yield result
    finally:
        result["time_s"] = time.perf_counter() - t0
