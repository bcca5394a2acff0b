"""Progress lines for loops that can last more than a few seconds.

:class:`Progress` prints ``label: 42 % (4200/10000 steps), ETA 12 s`` on
stderr, at most every ``interval`` seconds and never for a loop that ends
within the first interval, so short commands stay silent and long ones never
look hung.  Models accept any ``progress(fraction, what="")`` callable (the
chain passes its own bar); this is the one the command line uses.
Foundation module: standard library only.
"""

from __future__ import annotations

import sys
import time

__all__ = ["Progress", "call_progress"]


class Progress:
    """Rate-limited progress printer with an ETA.

    Parameters
    ----------
    label : str
        What is running, e.g. ``"topography evolve"``.
    unit : str
        Name of the counted items in the line (``"steps"``, ``"cycles"``).
    total : int, optional
        Number of items, for the counts in the line.
    interval : float
        Seconds between lines (and before the first).
    stream : file, optional
        Default stderr.
    """

    def __init__(self, label: str, unit: str = "steps", total: int | None = None,
                 interval: float = 2.0, stream=None):
        self.label, self.unit, self.total = label, unit, total
        self.interval = interval
        self.stream = stream
        self._t0 = time.monotonic()
        self._last = self._t0

    def __call__(self, fraction: float, what: str = "") -> None:
        """Report ``fraction`` (0-1) done; prints only when ``interval`` has passed."""
        now = time.monotonic()
        if now - self._last < self.interval and fraction < 1.0:
            return
        if fraction >= 1.0 and now - self._t0 < self.interval:
            return  # a short job: no lines at all
        self._last = now
        f = min(max(float(fraction), 0.0), 1.0)
        eta = (now - self._t0) * (1 - f) / f if f > 0 else float("inf")
        count = f" ({int(round(f * self.total))}/{self.total} {self.unit})" if self.total else ""
        tail = f", ETA {eta:.0f} s" if f < 1 else f", done in {now - self._t0:.0f} s"
        print(f"{self.label}: {100 * f:3.0f} %{count}{tail}{' ' + what if what else ''}",
              file=self.stream or sys.stderr, flush=True)


def call_progress(progress, i: int, total: int, what: str = "") -> None:
    """Call ``progress(i / total, what)`` about 200 times over a loop (cheap in hot loops)."""
    if progress is not None and (i == total or i % max(1, total // 200) == 0):
        progress(i / total, what)
