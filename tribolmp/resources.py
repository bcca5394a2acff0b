"""What this machine can hold: memory checks made before a run starts.

A grid that cannot fit in memory should fail in ``tribolmp check`` with one
line naming the field, not after minutes of other stages with a
``MemoryError`` (or the kernel's OOM killer).  Foundation module: standard
library and :mod:`tribolmp.errors` only.
"""

from __future__ import annotations

import os

from .errors import ParameterError

__all__ = ["physical_memory_bytes", "check_memory", "format_bytes"]

#: Share of the physical memory one run may plan to use (the OS, LAMMPS and Python need the rest).
MEMORY_SHARE = 0.8


def physical_memory_bytes() -> int:
    """Physical memory of this machine (bytes); a large number when the OS does not say."""
    try:
        return int(os.sysconf("SC_PAGE_SIZE")) * int(os.sysconf("SC_PHYS_PAGES"))
    except (ValueError, OSError, AttributeError):  # pragma: no cover - non-POSIX
        return 1 << 50


def format_bytes(n: float) -> str:
    """``1.5 GiB`` style text."""
    for unit in ("B", "KiB", "MiB", "GiB", "TiB", "PiB"):
        if abs(n) < 1024 or unit == "PiB":
            return f"{n:.3g} {unit}"
        n /= 1024
    return f"{n:.3g} PiB"  # pragma: no cover


def check_memory(nbytes: float, field: str, value: object, what: str,
                 source: str | None = None) -> None:
    """Raise one line when ``nbytes`` of working memory does not fit this machine.

    Parameters
    ----------
    nbytes : float
        Estimated peak working memory (bytes).
    field : str
        The scene key or option that sets the size, e.g. ``"[roughness].grid_points"``.
    value : object
        Its value, for the message.
    what : str
        What needs the memory, e.g. ``"the BEM contact solve"``.
    source : str, optional
        The scene file, prefixed to the message.

    Raises
    ------
    ParameterError
        ``nbytes`` above :data:`MEMORY_SHARE` of the physical memory.
    """
    avail = MEMORY_SHARE * physical_memory_bytes()
    if not nbytes <= avail:
        need = f"{what} would need ~{format_bytes(nbytes)}"
        raise ParameterError(field, f"a size whose working memory fits this machine "
                             f"({format_bytes(avail)} usable); {need}", value, source)
