"""Figures of an MCA run: mu(t), a Fig. 9-like snapshot coloured by body, profiles.

matplotlib is imported inside each function (with the ``Agg`` backend), so
importing this module is cheap.  Every function writes a PNG and returns its
path.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .outputs import MOL_BASE, MOL_LOWER, MOL_SLIDER, MOL_UPPER, NM

__all__ = ["plot_friction", "plot_snapshot", "plot_profiles", "BODY_COLOURS"]

#: Colour and label per molecule id (base, lower body, upper body, slider).
BODY_COLOURS = {
    MOL_BASE: ("#555555", "base (fixed)"),
    MOL_LOWER: ("#1f77b4", "lower body"),
    MOL_UPPER: ("#d62728", "upper body"),
    MOL_SLIDER: ("#222222", "slider (rigid)"),
}


def _figure(plt, ax, path, size):
    if ax is not None:
        return ax.figure, ax, False
    if path is None:
        from ..errors import ParameterError

        raise ParameterError("path", "a PNG path when no axes are given", None)
    fig, ax = plt.subplots(figsize=size)
    return fig, ax, True


def _finish(plt, fig, ax, own, path, dpi):
    if not own:
        return ax
    path = Path(path)
    fig.savefig(path, dpi=dpi, bbox_inches="tight")
    plt.close(fig)
    return path


def _pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def plot_friction(source, path=None, *, ax=None, title: str | None = None):
    """Plot mu(t) with the averaging window's start and the mean +- error (marked when not steady).

    Parameters
    ----------
    source : str, Path or Result
        An MCA output directory / ``friction.csv``, or the ``results`` of a
        :class:`~tribolmp.analysis.friction.FrictionCoefficient` run.
    path : str or Path, optional
        PNG to write (with its own figure).
    ax : matplotlib Axes, optional
        Draw into these axes instead (e.g. a panel of a report); nothing is saved.
    title : str, optional
        Figure title.

    Returns
    -------
    Path or Axes
        The PNG written, or ``ax`` when drawing into given axes.
    """
    from .friction import FrictionCoefficient

    res = source if hasattr(source, "mu_t") else FrictionCoefficient(source).run().results
    plt = _pyplot()
    fig, ax, own = _figure(plt, ax, path, (6.4, 3.6))
    t_ns = np.asarray(res.time_s) / 1e-9
    ax.plot(t_ns, res.mu_t, lw=0.6, color="#1f77b4", label=r"$\mu(t)=F_t/F_n$")
    t0 = res.window_start_s / 1e-9
    steady = bool(res.steady)
    what = f"steady from {t0:.3g} ns" if steady else f"NO steady state; mean from {t0:.3g} ns"
    ax.axvline(t0, color="k", ls=":", lw=1, label=what)
    ax.axhspan(res.mu - res.mu_err, res.mu + res.mu_err, color="#d62728", alpha=0.3)
    ax.axhline(
        res.mu,
        color="#d62728",
        lw=1.2,
        ls="-" if steady else "--",
        label=rf"$\mu$ = {res.mu:.3f} $\pm$ {res.mu_err:.3f}" + ("" if steady else " (not steady)"),
    )
    ax.set_xlabel("time (ns)")
    ax.set_ylabel(r"friction coefficient $\mu$")
    ax.legend(loc="best", fontsize=8)
    if title:
        ax.set_title(title, fontsize=9)
    return _finish(plt, fig, ax, own, path, dpi=130)


def plot_snapshot(out_dir, path=None, *, ax=None, frame: int = -1, title: str | None = None,
                  slab_m: float | None = None):
    """Draw the automata of one dump frame coloured by body (like the seed's Fig. 9).

    Automata are drawn as discs of their true diameter (twice the dump's
    ``radius`` column, in data units, so they keep their size at any figure
    size or dpi), coloured by body; discs cut by the periodic x boundary are
    completed by their periodic image.  In 3D only a slab ``slab_m`` thick
    (default two diameters) in the middle of the periodic z-extent is drawn.
    The original interface (frame 0) is marked.

    Parameters
    ----------
    out_dir : str or Path
        MCA output directory, or its ``traj.lammpstrj`` (``meta.json`` must sit
        next to it).
    path : str or Path, optional
        PNG to write (with its own figure).
    ax : matplotlib Axes, optional
        Draw into these axes instead; nothing is saved.
    frame : int
        Dump frame (default the last one).
    title : str, optional
        Figure title (default: time of the frame).
    slab_m : float, optional
        Slab thickness in 3D (m).

    Returns
    -------
    Path or Axes
        The PNG written, or ``ax`` when drawing into given axes.
    """
    from matplotlib.collections import EllipseCollection
    from matplotlib.patches import Patch

    from .outputs import open_trajectory, read_meta
    from .profiles import interface_height

    out_dir = Path(out_dir)
    if out_dir.is_file():
        out_dir = out_dir.parent
    meta = read_meta(out_dir)
    u = open_trajectory(out_dir, meta)
    ts0 = u.trajectory[0]
    y0 = interface_height(ts0.positions[:, meta.normal_axis], ts0.data["mol"])
    ts = u.trajectory[frame]
    pos = ts.positions.astype(float)
    mol = ts.data["mol"].astype(int)
    rad = ts.data["radius"].astype(float)
    keep = np.ones(len(mol), bool)
    if meta.dimension == 3:
        lo, hi = ts.data["box_lo"][2], ts.data["box_lo"][2] + ts.dimensions[2]
        half = 0.5 * (slab_m or 2 * meta.automaton_diameter_m) / NM
        mid = 0.5 * (lo + hi)
        keep = np.abs(pos[:, 2] - mid) <= half
    plt = _pyplot()
    box = ts.dimensions[:3]
    lo = ts.data["box_lo"]
    xs, ys, r = pos[keep, 0], pos[keep, meta.normal_axis], rad[keep]
    colours = np.array([BODY_COLOURS.get(m, ("#999999", ""))[0] for m in mol[keep]])
    # periodic images of the discs that the x boundary cuts
    x0, x1 = lo[0], lo[0] + box[0]
    left, right = xs - r < x0, xs + r > x1
    xs = np.concatenate([xs, xs[left] + box[0], xs[right] - box[0]])
    ys = np.concatenate([ys, ys[left], ys[right]])
    r = np.concatenate([r, r[left], r[right]])
    colours = np.concatenate([colours, colours[left], colours[right]])
    margin = float(r.max()) + 0.5
    width = 9.0
    aspect = (ys.max() - ys.min() + 2 * margin) / box[0]
    fig, ax, own = _figure(plt, ax, path, (width, max(2.5, width * aspect + 0.8)))
    # EllipseCollection with units="xy" takes full widths in data units (nm): true automaton size
    coll = EllipseCollection(
        2 * r,
        2 * r,
        np.zeros_like(r),
        units="xy",
        offsets=np.column_stack([xs, ys]),
        offset_transform=ax.transData,
        facecolors=colours,
        edgecolors="none",
    )
    ax.add_collection(coll)
    ax.axhline(y0, color="k", ls="--", lw=0.8)
    ax.set_xlim(x0, x1)
    ax.set_ylim(ys.min() - margin, ys.max() + margin)
    ax.set_aspect("equal")
    ax.set_xlabel("x (nm)")
    ax.set_ylabel("y (nm)")
    handles = [Patch(color=c, label=lab) for c, lab in BODY_COLOURS.values()]
    handles.append(plt.Line2D([], [], color="k", ls="--", lw=0.8, label="original interface"))
    ax.legend(
        handles=handles,
        loc="upper center",
        bbox_to_anchor=(0.5, -0.18),
        ncol=5,
        fontsize=7,
        frameon=False,
    )
    ax.set_title(title or f"t = {ts.time * 1e-3:.3g} ns", fontsize=9)
    return _finish(plt, fig, ax, own, path, dpi=150)


def plot_profiles(velocity, composition, path=None, *, ax=None, title: str | None = None):
    """Velocity v_x/V and upper-body fraction against height above the original interface.

    Parameters
    ----------
    velocity, composition : Results
        ``results`` of :class:`VelocityProfile` and :class:`CompositionProfile`.
    path : str or Path, optional
        PNG to write (with its own figure).
    ax : matplotlib Axes, optional
        Draw into these axes instead; nothing is saved.

    Returns
    -------
    Path or Axes
        The PNG written, or ``ax``.
    """
    plt = _pyplot()
    fig, ax, own = _figure(plt, ax, path, (4.2, 4.8))
    y0 = velocity.interface_height_m
    z = (np.asarray(velocity.heights_m) - y0) / 1e-9
    ax.plot(
        np.asarray(velocity.vx_m_s) / velocity.reference_velocity_m_s,
        z,
        "o-",
        ms=3,
        label=r"$v_x/V$",
    )
    zc = (np.asarray(composition.heights_m) - composition.interface_height_m) / 1e-9
    ax.plot(composition.upper_fraction, zc, "s-", ms=3, label="upper-body fraction")
    for h in (velocity.layer_bottom_m, velocity.layer_top_m):
        if np.isfinite(h):
            ax.axhline((h - y0) / 1e-9, color="#1f77b4", ls=":", lw=0.8)
    ax.axhline(0.0, color="k", ls="--", lw=0.8)
    ax.set_xlim(-0.1, 1.1)
    ax.set_xlabel("fraction")
    ax.set_ylabel("height above original interface (nm)")
    ax.legend(fontsize=8, loc="lower right")
    ax.set_title(
        title
        or f"layer {velocity.layer_depth_m / 1e-9:.3g} nm, "
           f"mixed {composition.mixed_width_m / 1e-9:.3g} nm",
        fontsize=9,
    )
    return _finish(plt, fig, ax, own, path, dpi=130)
