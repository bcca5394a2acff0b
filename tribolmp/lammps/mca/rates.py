"""The call into the analysis that writes ``rates.json``."""

from __future__ import annotations

from pathlib import Path

__all__ = ["compute_rates"]


def compute_rates(out: Path) -> dict:
    """Run :func:`tribolmp.analysis.rates.compute_rates` on the output folder ``out``.

    Parameters
    ----------
    out : Path
        A finished MCA output folder (``friction.csv``, ``traj.lammpstrj``, ``meta.json``).

    Returns
    -------
    dict
        The rates record, also written to ``out/rates.json``.
    """
    from ...analysis.rates import compute_rates as _compute  # lazy: MDAnalysis is heavy

    return _compute(out)
