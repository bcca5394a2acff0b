"""The model contract shared by every tribolmp model.

Each model provides

* a frozen ``Params`` dataclass, validated in ``__post_init__`` with the
  helpers below, so that a bad value is rejected on construction with a
  one-line :class:`~tribolmp.errors.ParameterError`;
* a ``solve(params, *, method=..., rng=None) -> Result`` function, where
  ``method`` is chosen by name from a :class:`MethodRegistry` (as
  :func:`scipy.integrate.solve_ivp` does);
* a :class:`Result` carrying arrays *and* diagnostics (status, message,
  iterations, wall time), like scipy's ``OdeResult``.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Iterator, Mapping
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import ParameterError

__all__ = [
    "Result",
    "MethodRegistry",
    "Timer",
    "check_finite",
    "check_range",
    "check_positive",
    "check_choice",
    "check_int",
]


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
        return {k: _jsonable(v) for k, v in self.items()}


def _jsonable(value: Any) -> Any:
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, (np.floating, np.integer)):
        return value.item()
    if isinstance(value, Mapping):
        return {str(k): _jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_jsonable(v) for v in value]
    if hasattr(value, "__dataclass_fields__"):
        from dataclasses import asdict

        return _jsonable(asdict(value))
    return value


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
        """Decorator registering ``func`` under ``name``."""

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


class Timer:
    """Wall-clock timer; ``with Timer() as t: ...`` then ``t.elapsed`` (s)."""

    def __enter__(self) -> Timer:
        self.start = time.perf_counter()
        self.elapsed = 0.0
        return self

    def __exit__(self, *exc: object) -> None:
        self.elapsed = time.perf_counter() - self.start


@contextmanager
def timed(result: Result) -> Iterator[Result]:
    """Context manager that stores the elapsed wall time in ``result['time_s']``."""
    t0 = time.perf_counter()
    try:
        yield result
    finally:
        result["time_s"] = time.perf_counter() - t0


# ---------------------------------------------------------------- validation


def check_finite(name: str, value: Any) -> float:
    """Return ``value`` as float, or raise if it is not a finite real number."""
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise ParameterError(name, "a finite real number", value)
    v = float(value)
    if not math.isfinite(v):
        raise ParameterError(name, "a finite real number", value)
    return v


def check_range(
    name: str,
    value: Any,
    lo: float | None = None,
    hi: float | None = None,
    *,
    lo_open: bool = False,
    hi_open: bool = False,
    unit: str = "",
) -> float:
    """Check that a finite number lies in an interval and return it as float.

    Parameters
    ----------
    name : str
        Field name used in the error message.
    value : float
        The value to check.
    lo, hi : float or None
        Bounds; ``None`` means unbounded.
    lo_open, hi_open : bool
        Whether the bounds are excluded.
    unit : str
        Unit appended to the expected range in the message.
    """
    v = check_finite(name, value)
    bad = (
        (lo is not None and (v < lo or (lo_open and v == lo)))
        or (hi is not None and (v > hi or (hi_open and v == hi)))
    )
    if bad:
        raise ParameterError(name, describe_range(lo, hi, lo_open, hi_open, unit), value)
    return v


def describe_range(lo, hi, lo_open=False, hi_open=False, unit="") -> str:
    """Human-readable interval, e.g. ``'a number in (0, inf) Pa'``."""
    left = "(" if (lo_open or lo is None) else "["
    right = ")" if (hi_open or hi is None) else "]"
    lo_s = "-inf" if lo is None else f"{lo:g}"
    hi_s = "inf" if hi is None else f"{hi:g}"
    suffix = f" {unit}" if unit else ""
    return f"a number in {left}{lo_s}, {hi_s}{right}{suffix}"


def check_positive(name: str, value: Any, unit: str = "", *, allow_zero: bool = False) -> float:
    """Shorthand for a strictly (or weakly) positive finite number."""
    return check_range(name, value, 0.0, None, lo_open=not allow_zero, unit=unit)


def check_choice(name: str, value: Any, choices: tuple[str, ...] | list[str]) -> str:
    """Check that ``value`` is one of ``choices``."""
    if not isinstance(value, str) or value not in choices:
        raise ParameterError(name, f"one of {list(choices)}", value)
    return value


def check_int(name: str, value: Any, lo: int | None = None, hi: int | None = None) -> int:
    """Check for an integer in ``[lo, hi]``."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        raise ParameterError(name, "an integer", value)
    v = int(value)
    if (lo is not None and v < lo) or (hi is not None and v > hi):
        lo_s = "-inf" if lo is None else str(lo)
        hi_s = "inf" if hi is None else str(hi)
        raise ParameterError(name, f"an integer in [{lo_s}, {hi_s}]", value)
    return v
