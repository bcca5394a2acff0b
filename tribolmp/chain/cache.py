"""Content-addressed cache of stage results, with atomic commits.

A stage's cache key is the SHA-256 of its inputs in canonical JSON: the scene
sections it reads, the planner's options, the keys of the upstream stages it
consumes and the tribolmp version.  A stage computes into
``<root>/<stage>-<key>.partial/`` (which survives an interrupt, so a LAMMPS
run can resume from its restart files there) and is committed by writing
``result.json`` to a temporary name, renaming it, and renaming the whole
directory to ``<root>/<stage>-<key>/``.  ``rename`` is atomic on POSIX, so a
Ctrl-C or a kill at any instant leaves either a complete committed stage or a
resumable partial one, never a half-written result.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import shutil
import tempfile
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

__all__ = ["StageCache", "CachedStage", "hash_inputs", "canonical_json", "atomic_write_text", "atomic_write_json"]

#: Length of the hex key used in directory names (64 bits are plenty for a per-run cache).
KEY_LENGTH = 16


def _canon(value: Any) -> Any:
    # Canonical form: tuples as lists, floats by repr so 0.1 hashes stably, dict keys sorted by json.
    if isinstance(value, Mapping):
        return {str(k): _canon(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_canon(v) for v in value]
    if isinstance(value, float):
        return repr(value) if not math.isfinite(value) else value
    if hasattr(value, "item") and callable(value.item):  # numpy scalar
        return _canon(value.item())
    if isinstance(value, Path):
        return str(value)
    return value


def canonical_json(value: Any) -> str:
    """Deterministic JSON text of ``value`` (sorted keys, no whitespace)."""
    return json.dumps(_canon(value), sort_keys=True, separators=(",", ":"), allow_nan=False)


def hash_inputs(value: Any) -> str:
    """SHA-256 hex digest of ``value``'s canonical JSON."""
    return hashlib.sha256(canonical_json(value).encode()).hexdigest()


def atomic_write_text(path: str | Path, text: str) -> Path:
    """Write ``text`` to ``path`` atomically (temporary file in the same folder, then rename)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write(text)
            fh.flush()
            os.fsync(fh.fileno())
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return path


def atomic_write_json(path: str | Path, obj: Any) -> Path:
    """Write ``obj`` as strict, indented JSON atomically (NaN/inf become null)."""
    from ..cli import _clean, _default

    text = json.dumps(_clean(json.loads(json.dumps(obj, default=_default))), indent=2, allow_nan=False)
    return atomic_write_text(path, text + "\n")


@dataclass(frozen=True)
class CachedStage:
    """A committed stage: its folder and its ``result.json`` content."""

    stage: str
    key: str
    path: Path
    record: dict

    @property
    def values(self) -> dict:
        """The stage's output numbers (SI)."""
        return self.record.get("values", {})

    def file(self, name: str) -> Path:
        """Absolute path of the hand-off file registered as ``name``."""
        try:
            return self.path / self.record["files"][name]
        except KeyError:
            raise KeyError(f"stage {self.stage!r} has no file {name!r}; it has {sorted(self.record.get('files', {}))}") from None


class StageCache:
    """Stage results on disk under ``root`` (normally ``<out>/cache``).

    Parameters
    ----------
    root : str or Path
        Cache folder; created when needed.
    """

    def __init__(self, root: str | Path):
        self.root = Path(root)

    def key(self, stage: str, inputs: Mapping[str, Any]) -> str:
        """Cache key of ``stage`` for ``inputs`` (includes the tribolmp version)."""
        from .. import __version__

        return hash_inputs({"stage": stage, "tribolmp": __version__, "inputs": inputs})[:KEY_LENGTH]

    def final_dir(self, stage: str, key: str) -> Path:
        """Folder of a committed result."""
        return self.root / f"{stage}-{key}"

    def partial_dir(self, stage: str, key: str) -> Path:
        """Working folder of an uncommitted (possibly interrupted) computation."""
        return self.root / f"{stage}-{key}.partial"

    def lookup(self, stage: str, key: str) -> CachedStage | None:
        """Return the committed result of ``stage`` with ``key``, or None."""
        path = self.final_dir(stage, key)
        try:
            record = json.loads((path / "result.json").read_text())
        except (OSError, ValueError):
            return None
        if record.get("key") != key or not record.get("complete"):
            return None
        return CachedStage(stage, key, path, record)

    def workdir(self, stage: str, key: str, *, fresh: bool = False) -> Path:
        """Create (or reuse, for checkpoint resume) the working folder; ``fresh`` empties it."""
        path = self.partial_dir(stage, key)
        if fresh and path.exists():
            shutil.rmtree(path)
        path.mkdir(parents=True, exist_ok=True)
        return path

    def discard(self, stage: str, key: str) -> None:
        """Remove the committed result (used by ``--force``); the partial folder is kept."""
        path = self.final_dir(stage, key)
        if path.exists():
            # Rename first so a half-deleted folder can never look like a valid result.
            trash = path.with_name(path.name + ".discard")
            if trash.exists():
                shutil.rmtree(trash)
            os.replace(path, trash)
            shutil.rmtree(trash, ignore_errors=True)

    def commit(self, stage: str, key: str, record: dict) -> CachedStage:
        """Write ``result.json`` into the working folder and rename it to the final folder."""
        work = self.partial_dir(stage, key)
        record = {**record, "stage": stage, "key": key, "complete": True}
        atomic_write_json(work / "result.json", record)
        final = self.final_dir(stage, key)
        if final.exists():  # a concurrent or forced rerun: replace the old result
            self.discard(stage, key)
        os.replace(work, final)
        return CachedStage(stage, key, final, json.loads((final / "result.json").read_text()))
