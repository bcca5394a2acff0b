"""SurfaceProfile: the lower body's column-mass height h(x, t).

Checked against stacked columns of known height.
"""

from __future__ import annotations

import numpy as np
import pytest

from tribolmp.analysis.outputs import (
    MOL_BASE,
    MOL_LOWER,
    MOL_SLIDER,
    MOL_UPPER,
    open_trajectory,
    read_meta,
)
from tribolmp.analysis.surface import SurfaceProfile
from tribolmp.analysis.synthetic import write_dump, write_meta


def _columns(out, heights_per_frame, d=2.5, n_upper=4):
    """Square lattice (spacing d nm) with columns of given heights.

    Column j of the lower side holds heights[j] automata (base row included),
    an upper body of n_upper rows sits on top of the highest column, a slider row above.
    """
    nx = heights_per_frame.shape[1]
    L = nx * d
    frames = []
    for k, hcol in enumerate(heights_per_frame):
        pos, mol = [], []
        for j, n in enumerate(hcol):
            for i in range(n):
                pos.append(((j + 0.5) * d, (i + 0.5) * d, 0.0))
                mol.append(MOL_BASE if i == 0 else MOL_LOWER)
        top = heights_per_frame.max() + 1
        for j in range(nx):
            for i in range(n_upper + 1):
                pos.append(((j + 0.5) * d, (top + i + 0.5) * d, 0.0))
                mol.append(MOL_SLIDER if i == n_upper else MOL_UPPER)
        pos = np.asarray(pos)
        n = pos.shape[0]
        frames.append(
            dict(
                step=1000 * k,
                box=np.array([[0, L], [0, (top + n_upper + 1) * d], [-0.5, 0.5]]),
                mol=np.asarray(mol),
                pos=pos,
                vel=np.zeros((n, 3)),
                radius=d / 2,
                nbond=4,
                id=np.arange(1, n + 1),
            )
        )
    write_dump(out / "traj.lammpstrj", frames)
    write_meta(out, dt_s=1e-13, dump_interval_steps=1000, velocity_m_s=5.0, diameter_m=d * 1e-9,
               box_m=frames[0]["box"] * 1e-9)


def test_column_mass_height_is_exact_for_stacked_columns(tmp_path, rng):
    nx, nt, d = 16, 5, 2.5
    base = 12
    heights = base + rng.integers(-2, 3, size=(nt, nx))
    heights[0] = base + np.array(
        [0, 1, 2, 1, 0, -1, -2, -1] * 2
    )  # frame 0: the bulk below 10 rows is full
    # the automaton count must stay the same in every frame (the dump contract): pad the last column
    total = heights[0].sum()
    heights[1:, -1] += total - heights[1:].sum(axis=1)
    _columns(tmp_path, heights, d=d)
    meta = read_meta(tmp_path)
    r = SurfaceProfile(open_trajectory(tmp_path, meta), meta).run().results
    assert r.h_m.shape == (nt, nx)
    assert r.column_width_m == pytest.approx(d * 1e-9)
    # bulk density of a square lattice: 1/d^2; height = bottom + n d exactly
    assert r.bulk_density == pytest.approx(1 / (d * 1e-9) ** 2, rel=1e-6)
    np.testing.assert_allclose(r.h_m, heights * d * 1e-9, rtol=0, atol=1e-14)
    np.testing.assert_allclose(r.t_s, np.arange(nt) * 1e-10, rtol=1e-6)
