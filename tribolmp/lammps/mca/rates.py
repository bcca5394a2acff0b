"""The call into the analysis that writes ``rates.json`` (optional dependency)."""

from __future__ import annotations

import importlib.util
from pathlib import Path

__all__ = ["compute_rates_if_available"]


def compute_rates_if_available(out: Path) -> dict | None:
    """``tribolmp.analysis.rates.compute_rates(out)``.

    Or None when the analysis is not installed.
    """
    if importlib.util.find_spec("tribolmp.analysis.rates") is None:
        return None
    from ...analysis.rates import compute_rates  # lazy: MDAnalysis is heavy

    return compute_rates(out)
