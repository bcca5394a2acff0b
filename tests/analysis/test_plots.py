"""The plotting helpers write real PNG figures from synthetic runs."""

from __future__ import annotations

import numpy as np
import pytest

from tribolmp.analysis.plots import plot_friction, plot_profiles, plot_snapshot
from tribolmp.analysis.profiles import CompositionProfile, VelocityProfile
from tribolmp.analysis.synthetic import make_friction, make_shear_mixing, make_walkers

PNG = b"\x89PNG\r\n\x1a\n"


def _is_png(path, min_bytes=5000):
    data = path.read_bytes()
    return data[:8] == PNG and len(data) > min_bytes


def test_friction_and_profiles(tmp_path):
    rng = np.random.default_rng(1)
    make_shear_mixing(tmp_path, rng, n_atoms=800, n_frames=4)
    make_friction(tmp_path, rng, n=500, dt=1e-12)
    assert _is_png(plot_friction(tmp_path, tmp_path / "mu.png"))
    vp = VelocityProfile.from_output(tmp_path).run(start=1).results
    cp = CompositionProfile.from_output(tmp_path).run(start=1).results
    assert _is_png(plot_profiles(vp, cp, tmp_path / "prof.png"))


def test_snapshot_2d_and_3d(tmp_path):
    for dim in (2, 3):
        out = tmp_path / f"d{dim}"
        make_walkers(out, np.random.default_rng(dim), dim=dim, n_walkers=40, n_frames=3)
        assert _is_png(plot_snapshot(out, out / "snap.png"))


def test_draw_into_given_axes(tmp_path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    make_friction(tmp_path, np.random.default_rng(3), n=300, dt=1e-12)
    fig, ax = plt.subplots()
    assert plot_friction(tmp_path, ax=ax) is ax
    assert len(ax.lines) >= 2  # mu(t) and the steady mean
    plt.close(fig)


def _disc_dump(out, radius_nm=1.5):
    """Four rows of non-touching discs (5 nm apart): base, lower body, upper body, slider."""
    from tribolmp.analysis.synthetic import write_dump, write_meta

    out.mkdir()
    xs = np.arange(2.5, 50.0, 5.0)  # 10 per row, 2.5 nm from the periodic x boundary
    rows = [(2.5, 1), (7.5, 2), (12.5, 3), (17.5, 4)]
    pos = np.array([[x, y, 0.0] for y, _ in rows for x in xs])
    mol = np.repeat([m for _, m in rows], xs.size)
    box = np.array([[0.0, 50.0], [0.0, 20.0], [-0.5, 0.5]])
    frame = dict(box=box, mol=mol, pos=pos, vel=np.zeros_like(pos), radius=radius_nm, nbond=0)
    write_dump(out / "traj.lammpstrj", [{**frame, "step": 0}, {**frame, "step": 100}])
    write_meta(
        out,
        dt_s=1e-15,
        dump_interval_steps=100,
        velocity_m_s=5.0,
        diameter_m=2 * radius_nm * 1e-9,
        box_m=box * 1e-9,
    )
    return xs.size


def test_snapshot_draws_discs_of_the_true_diameter(tmp_path):
    """Count the body-coloured pixels inside the axes: they must cover N pi r^2 in data units."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import to_rgb

    from tribolmp.analysis.plots import BODY_COLOURS

    r_nm = 1.5
    n_per_row = _disc_dump(tmp_path / "run", r_nm)
    for dpi in (
        60,
        120,
    ):  # the disc size must not depend on the resolution (markers in points would)
        fig, ax = plt.subplots(figsize=(8, 4), dpi=dpi)
        plot_snapshot(
            tmp_path / "run" / "traj.lammpstrj", ax=ax
        )  # the dump path works as well as the dir
        fig.canvas.draw()
        img = np.asarray(fig.canvas.buffer_rgba())[..., :3].astype(float) / 255
        bb = ax.get_window_extent()
        h = img.shape[0]
        inside = img[int(h - bb.y1) + 1:int(h - bb.y0) - 1, int(bb.x0) + 1:int(bb.x1) - 1]
        (px0, py0), (px1, py1) = ax.transData.transform([(0.0, 0.0), (1.0, 1.0)])
        px_per_nm2 = abs((px1 - px0) * (py1 - py0))
        for mol in (2, 3):
            hit = np.all(np.abs(inside - to_rgb(BODY_COLOURS[mol][0])) < 0.06, axis=-1).sum()
            area = hit / px_per_nm2
            # the anti-aliased rim (~0.5 px around discs 22 px (dpi 60) / 45 px
            # (dpi 120) across) is not counted: measured -8 % / -4 %; 15 % leaves
            # margin for renderer details. Markers of a few points (scatter s=3,
            # the tiny dots of the chain report's figure) would cover < 1 %
            assert area == pytest.approx(n_per_row * np.pi * r_nm**2, rel=0.15), (dpi, mol)
        plt.close(fig)
