"""Parameter fields and validation: the one place that says what a valid value is.

Every frozen parameter dataclass of tribolmp (scene sections, model ``Params``,
the shared :class:`~tribolmp.records.Rates` record) declares its fields with
:func:`param` (unit, range, choices, one-line doc) and calls
:func:`validate_dataclass` in ``__post_init__``.  Loose values (function
arguments, JSON hand-offs) are checked with :func:`check_range` and friends.
Every failure is a one-line :class:`~tribolmp.errors.ParameterError` naming the
field, the expected range and the value received.

This is a foundation module: it imports only :mod:`tribolmp.errors` and the
standard library (numpy scalars are recognised without importing numpy).
"""

from __future__ import annotations

import dataclasses
import math
import numbers
import types
import typing
from typing import Any

from .errors import ParameterError

__all__ = [
    "param",
    "validate_dataclass",
    "build_dataclass",
    "field_docs",
    "check_value",
    "describe_range",
    "check_finite",
    "check_range",
    "check_positive",
    "check_choice",
    "check_int",
    "renamed",
]


def describe_range(lo=None, hi=None, lo_open=False, hi_open=False, unit="") -> str:
    """Human-readable interval, e.g. ``'a number in (0, inf) Pa'``.

    Parameters
    ----------
    lo, hi : float or None
        Bounds; ``None`` means unbounded.
    lo_open, hi_open : bool
        Whether the bounds are excluded.
    unit : str
        Unit appended to the interval.

    Returns
    -------
    str
    """
    left = "(" if (lo_open or lo is None) else "["
    right = ")" if (hi_open or hi is None) else "]"
    lo_s = "-inf" if lo is None else f"{lo:g}"
    hi_s = "inf" if hi is None else f"{hi:g}"
    suffix = f" {unit}" if unit else ""
    return f"a number in {left}{lo_s}, {hi_s}{right}{suffix}"


def _outside(v: float, lo, hi, lo_open: bool, hi_open: bool) -> bool:
    return (lo is not None and (v < lo or (lo_open and v == lo))) or (
        hi is not None and (v > hi or (hi_open and v == hi))
    )


# ------------------------------------------------------------- loose values


def _is_real(value: Any) -> bool:
    # numbers.Real covers int, float and numpy's floating/integer scalars; bool is excluded.
    return isinstance(value, numbers.Real) and not isinstance(value, bool)


def check_finite(name: str, value: Any) -> float:
    """Return ``value`` as float, or raise if it is not a finite real number.

    Parameters
    ----------
    name : str
        Field name used in the error message.
    value : object
        The value to check.

    Returns
    -------
    float
    """
    if not _is_real(value):
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

    Returns
    -------
    float
    """
    v = check_finite(name, value)
    if _outside(v, lo, hi, lo_open, hi_open):
        raise ParameterError(name, describe_range(lo, hi, lo_open, hi_open, unit), value)
    return v


def check_positive(name: str, value: Any, unit: str = "", *, allow_zero: bool = False) -> float:
    """Shorthand for a strictly (or, with ``allow_zero``, weakly) positive finite number."""
    return check_range(name, value, 0.0, None, lo_open=not allow_zero, unit=unit)


def check_choice(name: str, value: Any, choices: tuple[str, ...] | list[str]) -> str:
    """Check that ``value`` is one of ``choices`` and return it."""
    if not isinstance(value, str) or value not in choices:
        raise ParameterError(name, f"one of {list(choices)}", value)
    return value


def check_int(name: str, value: Any, lo: int | None = None, hi: int | None = None) -> int:
    """Check for an integer in ``[lo, hi]`` and return it as int."""
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise ParameterError(name, "an integer", value)
    v = int(value)
    if (lo is not None and v < lo) or (hi is not None and v > hi):
        lo_s = "-inf" if lo is None else str(lo)
        hi_s = "inf" if hi is None else str(hi)
        raise ParameterError(name, f"an integer in [{lo_s}, {hi_s}]", value)
    return v


# ------------------------------------------------------- dataclass fields


def param(
    default: Any = dataclasses.MISSING,
    *,
    unit: str = "",
    lo: float | None = None,
    hi: float | None = None,
    lo_open: bool = False,
    hi_open: bool = False,
    choices: tuple | None = None,
    doc: str = "",
) -> Any:
    """Declare a validated dataclass field.

    Parameters
    ----------
    default : object
        Default value; omit for a required field.
    unit : str
        SI unit of the value (documentation and messages).
    lo, hi : float, optional
        Bounds of the allowed interval (inclusive unless ``lo_open``/``hi_open``).
        For list-valued fields they apply to every element.
    lo_open, hi_open : bool
        Exclude the bound.
    choices : tuple, optional
        Allowed values (for strings and integers).
    doc : str
        One-line description.

    Returns
    -------
    dataclasses.Field
    """
    meta = dict(unit=unit, lo=lo, hi=hi, lo_open=lo_open, hi_open=hi_open, choices=choices, doc=doc)
    if isinstance(default, (list, dict, set)):
        raise TypeError("use a tuple for sequence defaults (the dataclasses are frozen)")
    return dataclasses.field(default=default, metadata=meta)


def _strip_optional(tp: Any) -> tuple[Any, bool]:
    origin = typing.get_origin(tp)
    if origin in (typing.Union, types.UnionType):
        args = [a for a in typing.get_args(tp) if a is not type(None)]
        if len(args) == 1:
            return args[0], True
    return tp, False


def _type_name(tp: Any) -> str:
    if typing.get_origin(tp) is tuple:
        (inner, *_rest) = typing.get_args(tp)
        return f"a list of {_type_name(inner)}s"
    return {float: "number", int: "integer", str: "string", bool: "boolean"}.get(tp, str(tp))


def _check_scalar(name: str, tp: Any, value: Any, meta: dict) -> Any:
    unit = meta.get("unit", "")
    choices = meta.get("choices")
    if tp is bool:
        if not isinstance(value, bool):
            raise ParameterError(name, "a boolean (true or false)", value)
        return value
    if tp is str:
        if not isinstance(value, str):
            raise ParameterError(name, "a string", value)
        if choices is not None and value not in choices:
            raise ParameterError(name, f"one of {list(choices)}", value)
        return value
    if tp is int:
        if isinstance(value, bool) or not isinstance(value, int):
            raise ParameterError(name, "an integer", value)
        if choices is not None and value not in choices:
            raise ParameterError(name, f"one of {list(choices)}", value)
    elif tp is float:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise ParameterError(name, f"a finite number{' in ' + unit if unit else ''}", value)
        value = float(value)
        if not math.isfinite(value):
            raise ParameterError(name, "a finite number", value)
    else:  # pragma: no cover - schema bug, not user input
        raise TypeError(f"unsupported field type {tp!r} for {name}")
    lo, hi = meta.get("lo"), meta.get("hi")
    lo_open, hi_open = meta.get("lo_open", False), meta.get("hi_open", False)
    if _outside(value, lo, hi, lo_open, hi_open):
        raise ParameterError(name, describe_range(lo, hi, lo_open, hi_open, unit), value)
    return value


def check_value(name: str, tp: Any, value: Any, meta: dict) -> Any:
    """Validate and normalise one value against its annotated type and field metadata.

    Parameters
    ----------
    name : str
        Field name for messages.
    tp : type
        The annotation (``float``, ``int``, ``str``, ``bool``, ``tuple[X, ...]``,
        optionally ``| None``).
    value : object
        The value.
    meta : dict
        Field metadata as written by :func:`param`.

    Returns
    -------
    object
        The normalised value (ints to floats where a float is declared, lists to tuples).
    """
    tp, optional = _strip_optional(tp)
    if value is None:
        if optional:
            return None
        raise ParameterError(name, f"a {_type_name(tp)}", value)
    if typing.get_origin(tp) is tuple:
        inner = typing.get_args(tp)[0]
        if isinstance(value, (str, bytes)) or not isinstance(value, (list, tuple)):
            raise ParameterError(name, _type_name(tp), value)
        return tuple(check_value(f"{name}[{i}]", inner, v, meta) for i, v in enumerate(value))
    return _check_scalar(name, tp, value, meta)


def validate_dataclass(obj: Any, prefix: str = "") -> None:
    """Validate every field of a frozen dataclass instance in place.

    Call from ``__post_init__``.  Values are normalised (ints to floats where a
    float is declared, lists to tuples) with ``object.__setattr__``.

    Parameters
    ----------
    obj : dataclass instance
        The instance to validate.
    prefix : str
        Prefix for field names in messages, e.g. ``"[material]."``.
    """
    hints = typing.get_type_hints(type(obj))
    for f in dataclasses.fields(obj):
        if not f.init:
            continue
        value = getattr(obj, f.name)
        norm = check_value(prefix + f.name, hints[f.name], value, dict(f.metadata))
        if norm is not value:
            object.__setattr__(obj, f.name, norm)


def build_dataclass(cls: type, data: dict, prefix: str = "", source: str | None = None) -> Any:
    """Build ``cls`` from a mapping, rejecting unknown keys and missing required keys.

    Parameters
    ----------
    cls : type
        A dataclass type.
    data : dict
        Key-value pairs, e.g. one TOML table.
    prefix : str
        Prefix for field names in messages, e.g. ``"[material]."``.
    source : str, optional
        File name prefixed to error messages.

    Returns
    -------
    object
        The validated instance.
    """
    if not isinstance(data, dict):
        raise ParameterError(prefix.rstrip("."), "a table", data, source)
    names = {f.name: f for f in dataclasses.fields(cls) if f.init}
    aliases = getattr(
        cls, "__field_aliases__", {}
    )  # old key -> field (params.renamed handles them)
    for key in data:
        if key not in names and key not in aliases:
            raise ParameterError(
                prefix + str(key), f"one of the known keys {sorted(names)}", "unknown key", source
            )
    given = {aliases.get(k, k) for k in data}
    for name, f in names.items():
        if (
            name not in given
            and f.default is dataclasses.MISSING
            and f.default_factory is dataclasses.MISSING
        ):
            raise ParameterError(prefix + name, "a value (this key is required)", "nothing", source)
    try:
        return cls(**data)
    except ParameterError as exc:
        if source and not exc.source:
            # re-raise with the file name and the section prefix
            field_name = exc.field if exc.field.startswith(prefix) else prefix + exc.field
            raise type(exc)(field_name, exc.expected, exc.got, source) from None
        raise


def field_docs(cls: type) -> list[tuple[str, str, str, str]]:
    """Return ``(name, unit, range, doc)`` rows describing a dataclass's fields."""
    rows = []
    for f in dataclasses.fields(cls):
        m = f.metadata
        if m.get("choices"):
            rng = f"one of {list(m['choices'])}"
        elif m.get("lo") is not None or m.get("hi") is not None:
            rng = describe_range(m.get("lo"), m.get("hi"), m.get("lo_open"), m.get("hi_open"))
        else:
            rng = ""
        rows.append((f.name, m.get("unit", ""), rng, m.get("doc", "")))
    return rows


def renamed(**old_to_new: str):
    """Class decorator keeping old field names of a renamed dataclass field working.

    ``@renamed(modulus="E_star")`` on a dataclass whose field is now ``E_star``:
    the constructor (and :func:`dataclasses.replace`) accepts ``modulus=`` as
    well (the old name wins when both are given, which is what ``replace``
    passes), reading ``obj.modulus`` returns ``obj.E_star``,
    :func:`build_dataclass` (scene files) accepts the old key, and a
    validation error names the field as the caller spelled it.  The aliases are
    listed in ``cls.__field_aliases__`` and documented in docs/conventions.md.

    Parameters
    ----------
    **old_to_new : str
        Old name -> current field name.

    Returns
    -------
    callable
        The decorator.
    """

    def deco(cls: type) -> type:
        names = {f.name for f in dataclasses.fields(cls)}
        bad = {o: n for o, n in old_to_new.items() if n not in names or o in names}
        if bad:
            raise TypeError(f"{cls.__name__}: bad field aliases {bad}")
        init = cls.__init__

        def __init__(self, *args: Any, **kwargs: Any) -> None:
            used = {}
            for old, new in old_to_new.items():
                if old in kwargs:
                    kwargs[new] = kwargs.pop(old)
                    used[new] = old
            try:
                init(self, *args, **kwargs)
            except ParameterError as exc:
                # The message names the field as the caller spelled it (e.g. a CLI's old flag).
                head, _, tail = exc.field.rpartition(".")
                if tail in used:
                    field = f"{head}.{used[tail]}" if head else used[tail]
                    raise type(exc)(field, exc.expected, exc.got, exc.source) from None
                raise

        __init__.__doc__ = init.__doc__
        __init__.__wrapped__ = init
        cls.__init__ = __init__
        for old, new in old_to_new.items():
            alias = property(
                lambda self, _n=new: getattr(self, _n), doc=f"Deprecated alias of ``{new}``."
            )
            setattr(cls, old, alias)
        cls.__field_aliases__ = {**getattr(cls, "__field_aliases__", {}), **old_to_new}
        return cls

    return deco

