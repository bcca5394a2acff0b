"""Figures of the lubrication models (matplotlib imported only here, Agg backend)."""

from __future__ import annotations

from pathlib import Path

__all__ = ["plot_polishing"]


def plot_polishing(res, path) -> Path:
    """Roughness Sq, Sa (um) and removed depth (um) against time (s), plus the final map."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
    ax1.plot(res.t, res.sq * 1e6, label="Sq")
    ax1.plot(res.t, res.sa * 1e6, label="Sa")
    area = res.h.size * res.pixel_size**2
    ax1.plot(res.t, res.removed_volume / area * 1e6, "--", label="mean depth removed")
    ax1.set_xlabel("time (s)")
    ax1.set_ylabel("um")
    ax1.legend()
    ax1.set_title("lubricated polishing")
    n = res.h.shape[0]
    ext = [0, n * res.pixel_size * 1e6, 0, n * res.pixel_size * 1e6]
    im = ax2.imshow(res.h.T * 1e6, origin="lower", extent=ext, cmap="viridis")
    fig.colorbar(im, ax=ax2, label="height (um)")
    ax2.set_xlabel("x (um), sliding direction")
    ax2.set_ylabel("y (um)")
    ax2.set_title("final topography")
    fig.tight_layout()
    path = Path(path)
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path
