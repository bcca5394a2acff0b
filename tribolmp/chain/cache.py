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

import json
import os
import shutil
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..jsonio import atomic_write_json, atomic_write_text, canonical_json, hash_inputs
from ..locking import DirLock

__all__ = [
    "StageCache",
    "CachedStage",
    "hash_inputs",
    "canonical_json",
    "atomic_write_text",
    "atomic_write_json",
]

#: Length of the hex key used in directory names (64 bits are plenty for a per-run cache).
KEY_LENGTH = 16


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
            raise KeyError(
                f"stage {self.stage!r} has no file {name!r}; "
                f"it has {sorted(self.record.get('files', {}))}"
            ) from None


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
        # A hand-off file that was truncated or deleted after the commit (a full disk, a copy
        # interrupted by the user) must not be trusted as a hit: recompute instead.
        for name, size in record.get("file_sizes", {}).items():
            try:
                if (path / name).stat().st_size != size:
                    return None
            except OSError:
                return None
        return CachedStage(stage, key, path, record)

    def entry_lock(self, stage: str, key: str, *, quiet: bool = False) -> DirLock:
        """Return the (unacquired) lock that serialises computing one entry across processes.

        Two runs sharing a cache folder then compute an entry once: the second
        waits, and finds the committed result when it gets the lock.
        """
        self.root.mkdir(parents=True, exist_ok=True)
        return DirLock(
            self.root,
            wait=True,
            what=f"cache entry {stage}-{key}",
            name=f".{stage}-{key}.lock",
            quiet=quiet,
        )

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
        sizes = {}
        for rel in (record.get("files") or {}).values():
            f = work / rel
            if f.is_file():
                sizes[rel] = f.stat().st_size
        record = {**record, "stage": stage, "key": key, "complete": True, "file_sizes": sizes}
        atomic_write_json(work / "result.json", record)
        final = self.final_dir(stage, key)
        if final.exists():  # a concurrent or forced rerun: replace the old result
            self.discard(stage, key)
        os.replace(work, final)
        return CachedStage(stage, key, final, json.loads((final / "result.json").read_text()))
