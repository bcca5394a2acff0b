"""The plotting helpers write real PNG figures from synthetic runs."""

from __future__ import annotations

import numpy as np

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
