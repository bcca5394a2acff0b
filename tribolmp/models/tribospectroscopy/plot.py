"""Figures of tribospectroscopy data and fits (matplotlib imported here only)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .fit import MeasuredCurve, model_curve

__all__ = ["plot_fit"]


def plot_fit(curve: MeasuredCurve, fit, path: str | Path, *, title: str = "") -> Path:
    """Plot measured F^2 (or F) against per-contact amplitude with the fitted curves.

    Parameters
    ----------
    curve : MeasuredCurve
        The data (amplitudes per contact, m).
    fit : Result
        Output of :func:`~tribolmp.models.tribospectroscopy.fit.fit_length`.
    path : str or Path
        PNG file to write.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    q = curve.quantity
    fig, ax = plt.subplots(figsize=(6.0, 4.2), dpi=120)
    ax.plot(curve.amplitude * 1e6, curve.value, "x", color="k", label="data")
    a = np.linspace(0.0, curve.amplitude.max() * 1.02, 400)
    for name, c in fit.candidates.items():
        y = model_curve(name, a, c["length_m"], c["amplitude"], c["background"], q)
        style = "-" if name == fit.model else "--"
        ax.plot(
            a * 1e6,
            y,
            style,
            label=f"{name}: L = {c['length_m'] * 1e9:.1f} ± {c['length_std_m'] * 1e9:.1f} nm",
        )
    ax.set_xlabel("amplitude per contact a = Δl/4 (µm)")
    top = ax.secondary_xaxis("top", functions=(lambda x: 2.0 * x, lambda x: 0.5 * x))
    top.set_xlabel("probe amplitude Δl/2 (µm)", fontsize=8)
    ax.set_ylabel("F² (N²)" if q == "force_sq" else "F (N)")
    ax.set_ylim(bottom=min(0.0, float(np.min(curve.value))))  # data may scatter below zero
    ax.set_xlim(left=0)
    ax.legend(fontsize=8)
    ax.set_title(title or f"tribospectroscopy fit (best: {fit.model})", fontsize=10)
    fig.tight_layout()
    path = Path(path)
    fig.savefig(path)
    plt.close(fig)
    return path
