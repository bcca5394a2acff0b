"""Reading the output-directory contract: meta.json, friction.csv, the dump and its units."""

from __future__ import annotations

import json

import numpy as np
import pytest

from tribolmp.analysis.outputs import (
    MCAMeta,
    open_trajectory,
    read_friction_csv,
    read_meta,
    resume_frames,
)
from tribolmp.analysis.synthetic import write_dump, write_friction_csv, write_meta
from tribolmp.errors import DataFileError


def _frames(n_frames=3, lo=(-10.0, 5.0, -0.5), every=100):
    pos = np.array([[1.0, 6.0, 0.0], [2.0, 9.0, 0.0], [3.0, 12.0, 0.0], [4.0, 14.0, 0.0]])
    mol = np.array([1, 2, 3, 4])
    box = np.array([[lo[0], lo[0] + 20.0], [lo[1], lo[1] + 10.0], [lo[2], lo[2] + 1.0]])
    out = []
    for k in range(n_frames):
        p = pos.copy()
        p[:, 0] += k
        # ids written in reverse order: the reader must sort by id
        out.append(
            dict(
                step=k * every,
                box=box,
                mol=mol[::-1],
                pos=p[::-1],
                vel=np.ones((4, 3)) * k,
                radius=1.25,
                nbond=np.arange(4)[::-1],
                id=np.arange(4, 0, -1),
            )
        )
    return out


def _write(tmp_path, frames, dt=2e-14, every=100):
    write_dump(tmp_path / "traj.lammpstrj", frames)
    write_meta(tmp_path, dt_s=dt, dump_interval_steps=every, velocity_m_s=5.0, diameter_m=2.5e-9,
               box_m=[[0, 2e-8], [0, 1e-8], [0, 1e-9]])


def test_positions_are_absolute_and_time_is_real(tmp_path):
    _write(tmp_path, _frames())
    meta = read_meta(tmp_path)
    u = open_trajectory(tmp_path, meta)
    assert u.trajectory.n_frames == 3
    ts = u.trajectory[2]
    # MDAnalysis would shift the origin to 0; we keep the LAMMPS frame (nm)
    np.testing.assert_allclose(ts.positions[:, 1], [6.0, 9.0, 12.0, 14.0], atol=1e-5)
    np.testing.assert_allclose(ts.positions[:, 0], [3.0, 4.0, 5.0, 6.0], atol=1e-5)
    np.testing.assert_allclose(ts.data["box_lo"], [-10.0, 5.0, -0.5])
    np.testing.assert_array_equal(ts.data["mol"], [1, 2, 3, 4])
    np.testing.assert_array_equal(ts.data["c_nbond"], [0, 1, 2, 3])
    # step 200 x 2e-14 s = 4 ps (MDAnalysis time unit), not 200 ps
    assert ts.time == pytest.approx(4.0)
    # dt is the time between frames (100 steps x 0.02 ps = 2 ps), not the MD timestep (0.02
    # ps): an MSD divided by u.trajectory.dt is then per frame interval, not 100x off
    assert u.trajectory.dt == pytest.approx(2.0)
    assert [t.time for t in u.trajectory] == pytest.approx([0.0, 2.0, 4.0])
    # frame 0 too (read while the Universe is built)
    assert u.trajectory[0].time == 0.0
    assert u.trajectory[2].velocities[0, 0] == pytest.approx(2.0)


def test_time_of_a_dump_that_starts_late(tmp_path):
    # a dump appended after a restart starts at step 5000: its times are
    # step x timestep, not frame x dt
    frames = _frames()
    for k, f in enumerate(frames):
        f["step"] = 5000 + 100 * k
    _write(tmp_path, frames)
    meta = read_meta(tmp_path)
    u = open_trajectory(tmp_path, meta)
    assert u.trajectory.dt == pytest.approx(2.0)
    assert u.trajectory[0].time == pytest.approx(100.0)  # 5000 x 0.02 ps
    assert u.trajectory[2].time == pytest.approx(104.0)


def test_meta_contract_and_errors(tmp_path):
    _write(tmp_path, _frames())
    meta = read_meta(tmp_path)
    assert meta.dump_interval_s == pytest.approx(2e-12)
    assert meta.normal_axis == 1 and meta.lateral_axes == (0,)
    raw = json.loads((tmp_path / "meta.json").read_text())
    del raw["velocity_m_s"]
    with pytest.raises(DataFileError, match="velocity_m_s"):
        MCAMeta.from_dict(raw)
    raw = json.loads((tmp_path / "meta.json").read_text())
    raw["dump_interval_s"] = 1.0
    with pytest.raises(DataFileError, match="dump_interval_s"):
        MCAMeta.from_dict(raw)
    m3 = MCAMeta.from_dict({**json.loads((tmp_path / "meta.json").read_text()), "dimension": 3})
    assert m3.lateral_axes == (0, 2)


def test_meta_of_a_running_job_reads(tmp_path):
    """Check a running job's meta.json (no throughput yet; the units block only names it)."""
    _write(tmp_path, _frames())
    raw = json.loads((tmp_path / "meta.json").read_text())
    raw.pop("atom_steps_per_s", None)
    raw["units"] = {"atom_steps_per_s": "1/s", "dt_s": "s"}
    meta = MCAMeta.from_dict(raw)
    assert meta.atom_steps_per_s is None and meta.dt_s == pytest.approx(2e-14)


def test_missing_dump_column_is_a_one_line_error(tmp_path):
    _write(tmp_path, _frames())
    text = (tmp_path / "traj.lammpstrj").read_text().replace(" c_nbond", " c_other")
    (tmp_path / "traj.lammpstrj").write_text(text)
    with pytest.raises(DataFileError, match="c_nbond") as info:
        open_trajectory(tmp_path)
    assert "\n" not in str(info.value)


def test_resume_duplicates_are_dropped(tmp_path):
    frames = _frames(5)
    # a run interrupted after step 400 and resumed from the restart at step 200
    write_dump(tmp_path / "traj.lammpstrj", frames + frames[2:])
    write_meta(tmp_path, dt_s=2e-14, dump_interval_steps=100, velocity_m_s=5.0, diameter_m=2.5e-9,
               box_m=[[0, 2e-8], [0, 1e-8], [0, 1e-9]])
    u = open_trajectory(tmp_path)
    frames_kept, steps = resume_frames(u)
    np.testing.assert_array_equal(steps, [0, 100, 200, 300, 400])
    np.testing.assert_array_equal(frames_kept, [0, 1, 5, 6, 7])
    t = np.array([1.0, 2.0, 3.0, 4.0, 3.0, 4.0, 5.0]) * 1e-12
    write_friction_csv(tmp_path / "friction.csv", t, np.arange(7.0), np.ones(7), np.zeros(7))
    fr = read_friction_csv(tmp_path)
    np.testing.assert_allclose(fr["time_s"], np.array([1, 2, 3, 4, 5]) * 1e-12)
    np.testing.assert_allclose(fr["friction_N"], [0, 1, 4, 5, 6])


def test_friction_csv_errors(tmp_path):
    (tmp_path / "friction.csv").write_text("time_s,friction_N\n1,2\n2,3\n")
    with pytest.raises(DataFileError, match="expected columns"):
        read_friction_csv(tmp_path)
    write_friction_csv(tmp_path / "friction.csv", [1.0, 2.0], [np.nan, 1.0], [1.0, 1.0], [0.0, 0.0])
    with pytest.raises(DataFileError, match="line 2"):
        read_friction_csv(tmp_path)
