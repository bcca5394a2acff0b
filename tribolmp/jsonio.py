"""JSON sanitising, canonical hashing and atomic file writes: the one implementation.

* :func:`jsonable` turns anything tribolmp produces (numpy arrays and
  scalars, paths, dataclasses, objects with ``to_json_dict``, tuples) into
  plain JSON types; non-finite floats become ``None`` because strict JSON has
  no NaN/inf.
* :func:`dumps` is strict JSON text of :func:`jsonable`;
  :func:`canonical_json` / :func:`hash_inputs` the deterministic form used
  for cache keys.
* :func:`atomic_write_text` / :func:`atomic_write_json` write to a temporary
  file in the target folder and rename it, so a reader (or a kill) never sees
  a half-written file.
* :func:`finite_or_none` and :func:`scalars` are the small helpers hand-off
  writers need.

Foundation module: standard library only (numpy objects are recognised by
duck typing, so importing this never imports numpy).
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import math
import os
import tempfile
from collections.abc import Mapping
from pathlib import Path
from typing import Any

__all__ = [
    "jsonable",
    "dumps",
    "canonical_json",
    "hash_inputs",
    "finite_or_none",
    "scalars",
    "atomic_write_text",
    "atomic_write_json",
]


def _numpy_like(value: Any) -> Any:
    """Convert a numpy array to a list and a numpy scalar to a Python scalar; pass anything else."""
    if type(value).__module__ == "numpy":
        if hasattr(value, "tolist"):
            return value.tolist()
    return value


def jsonable(value: Any) -> Any:
    """Return a copy of ``value`` made of plain JSON types.

    Parameters
    ----------
    value : object
        Mappings (keys become strings), sequences, numpy arrays and scalars,
        ``os.PathLike``, dataclass instances, objects with ``to_json_dict()``.

    Returns
    -------
    object
        dict / list / str / int / float / bool / None; non-finite floats are ``None``.

    Raises
    ------
    TypeError
        For an object with no JSON form.
    """
    value = _numpy_like(value)
    if value is None or isinstance(value, (bool, str, int)):
        return value
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if isinstance(value, Mapping):
        return {str(k): jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [jsonable(v) for v in value]
    if hasattr(value, "to_json_dict"):
        return jsonable(value.to_json_dict())
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return jsonable(dataclasses.asdict(value))
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    if isinstance(value, (set, frozenset)):
        return [jsonable(v) for v in sorted(value, key=repr)]
    raise TypeError(f"not JSON serialisable: {type(value).__name__}")


def dumps(value: Any, *, indent: int | None = None) -> str:
    """Strict JSON text of ``jsonable(value)`` (NaN/inf written as ``null``)."""
    return json.dumps(jsonable(value), indent=indent, allow_nan=False)


def _canon(value: Any) -> Any:
    # Canonical form for hashing: tuples as lists, non-finite floats by repr (a NaN input must
    # hash differently from a missing one), numpy scalars as Python scalars, paths as strings.
    value = _numpy_like(value)
    if isinstance(value, Mapping):
        return {str(k): _canon(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_canon(v) for v in value]
    if isinstance(value, float):
        return repr(value) if not math.isfinite(value) else value
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    return value


def canonical_json(value: Any) -> str:
    """Deterministic JSON text of ``value`` (sorted keys, no whitespace)."""
    return json.dumps(_canon(value), sort_keys=True, separators=(",", ":"), allow_nan=False)


def hash_inputs(value: Any) -> str:
    """SHA-256 hex digest of ``value``'s canonical JSON."""
    return hashlib.sha256(canonical_json(value).encode()).hexdigest()


def finite_or_none(x: Any) -> float | None:
    """``float(x)`` when it is a finite number, else ``None`` (missing, NaN, inf, not a number)."""
    if isinstance(x, bool):
        return None
    try:
        v = float(x)
    except (TypeError, ValueError):
        return None
    return v if math.isfinite(v) else None


def scalars(d: Mapping[str, Any], max_len: int = 64) -> dict[str, Any]:
    """JSON-friendly copy of the scalar (and short numeric list) entries of ``d``.

    Parameters
    ----------
    d : mapping
        E.g. a model :class:`~tribolmp.results.Result` or ``vars(params)``.
    max_len : int
        Longest array or list kept (longer ones belong in a hand-off file).

    Returns
    -------
    dict
        Strings, bools, ints, finite-or-None floats and numeric lists of at most ``max_len``.
    """
    out: dict[str, Any] = {}
    for k, v in d.items():
        v = _numpy_like(v)
        if isinstance(v, float):
            out[k] = v if math.isfinite(v) else None
        elif isinstance(v, (bool, int, str)) or v is None:
            out[k] = v
        elif isinstance(v, (list, tuple)) and len(v) <= max_len and all(
            isinstance(x, (int, float)) and not isinstance(x, bool) for x in v
        ):
            out[k] = [finite_or_none(x) for x in v]
    return out


def _umask() -> int:
    """Return the process umask (read by setting and restoring it: POSIX has no getter)."""
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def atomic_write_text(path: str | Path, text: str) -> Path:
    """Write ``text`` to ``path`` atomically (temporary file in the same folder, fsync, rename).

    Parameters
    ----------
    path : str or Path
        Target file; its folder is created when missing.
    text : str
        Content (UTF-8).

    Returns
    -------
    Path
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        # mkstemp creates mode 0600; results are meant to be read by colleagues on a shared
        # machine, so give the file the mode an ordinary open() would (0666 less the umask).
        os.fchmod(fd, 0o666 & ~_umask())
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write(text)
            fh.flush()
            os.fsync(fh.fileno())
        os.replace(tmp, path)
    except OSError as exc:
        Path(tmp).unlink(missing_ok=True)
        # A full disk or a size limit fails inside write() with no file name: name the target.
        raise OSError(exc.errno, exc.strerror or str(exc), str(path)) from None
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return path


def atomic_write_json(path: str | Path, obj: Any, *, indent: int | None = 2) -> Path:
    """Write ``obj`` as strict, indented JSON atomically (NaN/inf become null)."""
    return atomic_write_text(path, dumps(obj, indent=indent) + "\n")
