"""An output folder's simulated work is never deleted silently (never lost data).

Before this guard, ``run_mca(..., resume=True)`` on a folder whose ``meta.json``
differed from the call in any field (a changed parameter, or a field a newer
package version added) deleted its restart files and started over; without
``resume`` any earlier run in the folder was deleted.  An 80 ns run (of 100 ns)
was lost that way.  Now such a call is refused with one line that names the
fields that differ, the chain's stage folders move the other run aside, and
only an explicit overwrite discards it.

These tests build folders by hand (no LAMMPS): the check runs before anything
is prepared or simulated.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from tests.conftest import assert_one_line_error
from tribolmp.errors import SetupError
from tribolmp.lammps.mca import preset_params
from tribolmp.lammps.mca.driver import _expected
from tribolmp.lammps.mca.restart import check_folder, restart_files

pytestmark = pytest.mark.lammps  # imports the LAMMPS driver package (not LAMMPS itself)

PARAMS = preset_params("smoke")


def _fake_run(out: Path, params=PARAMS, *, seed: int = 1, restart: bool = True) -> dict:
    """Build a folder as an interrupted run leaves it (meta, data file, outputs, a restart)."""
    out.mkdir(parents=True, exist_ok=True)
    meta = {"dt_s": 1e-14, "deck_variables": {}, **_expected(params, seed, {})}
    files = {
        "meta.json": json.dumps(meta),
        "system.data": "data file\n",
        "friction.csv": "time_s,friction_N,normal_N,top_x_m\n0,0,0,0\n",
        "traj.lammpstrj": "ITEM: TIMESTEP\n0\n",
    }
    if restart:
        files["restart.232750.bin"] = "restart bytes"
    for name, text in files.items():
        (out / name).write_text(text)
    return files


def _unchanged(out: Path, files: dict) -> bool:
    return all((out / n).is_file() and (out / n).read_text() == t for n, t in files.items())


def test_resume_of_a_different_run_is_refused_naming_the_field(tmp_path):
    files = _fake_run(tmp_path, PARAMS.replace(pressure=382e6))
    with pytest.raises(SetupError) as err:
        check_folder(tmp_path, _expected(PARAMS, 1, {}), resume=True, on_conflict="refuse")
    msg = str(err.value)
    assert "\n" not in msg
    # the field that differs, both values, and what the folder holds
    assert "params.pressure" in msg and "382000000.0" in msg and "restart file" in msg
    assert _unchanged(tmp_path, files)


def test_a_field_an_older_version_lacked_is_named_missing(tmp_path):
    files = _fake_run(tmp_path)
    meta = json.loads((tmp_path / "meta.json").read_text())
    del meta["params"]["dt_factor"]
    (tmp_path / "meta.json").write_text(json.dumps(meta))
    files["meta.json"] = json.dumps(meta)
    with pytest.raises(SetupError, match=r"params\.dt_factor: folder '<missing>'"):
        check_folder(tmp_path, _expected(PARAMS, 1, {}), resume=True, on_conflict="refuse")
    assert _unchanged(tmp_path, files)


def test_a_fresh_run_into_a_folder_holding_a_run_is_refused(tmp_path):
    files = _fake_run(tmp_path)
    with pytest.raises(SetupError, match="holds an earlier run"):
        check_folder(tmp_path, _expected(PARAMS, 1, {}), resume=False, on_conflict="refuse")
    assert _unchanged(tmp_path, files)
    # a finished run whose restart files were pruned is work too
    (tmp_path / "restart.232750.bin").unlink()
    (tmp_path / "rates.json").write_text("{}")
    with pytest.raises(SetupError, match=r"finished run \(rates.json\)"):
        check_folder(tmp_path, _expected(PARAMS, 1, {}), resume=False, on_conflict="refuse")


def test_the_same_run_is_resumed_untouched(tmp_path):
    files = _fake_run(tmp_path)
    meta, archived = check_folder(
        tmp_path, _expected(PARAMS, 1, {}), resume=True, on_conflict="refuse"
    )
    assert meta is not None and meta["seed"] == 1 and archived is None
    assert _unchanged(tmp_path, files)


def test_archive_moves_the_other_run_aside_byte_for_byte(tmp_path):
    files = _fake_run(tmp_path, seed=2)
    meta, archived = check_folder(
        tmp_path, _expected(PARAMS, 1, {}), resume=True, on_conflict="archive"
    )
    assert meta is None and archived == tmp_path / "superseded" / "1"
    assert _unchanged(archived, files)
    assert not restart_files(tmp_path) and not (tmp_path / "meta.json").exists()
    # a second conflict goes to the next slot, never over the first
    _fake_run(tmp_path, seed=3)
    _, again = check_folder(tmp_path, _expected(PARAMS, 1, {}), resume=True, on_conflict="archive")
    assert again == tmp_path / "superseded" / "2" and _unchanged(archived, files)


def test_overwrite_discards_and_a_folder_without_work_starts_over(tmp_path):
    _fake_run(tmp_path / "a", seed=2)
    assert check_folder(
        tmp_path / "a", _expected(PARAMS, 1, {}), resume=True, on_conflict="overwrite"
    ) == (None, None)
    assert not restart_files(tmp_path / "a") and not (tmp_path / "a" / "meta.json").exists()
    # a run that failed before its first restart holds nothing a rerun would not recompute
    # within one restart interval: it is discarded without asking (the fault-recovery case)
    _fake_run(tmp_path / "b", seed=2, restart=False)
    assert check_folder(
        tmp_path / "b", _expected(PARAMS, 1, {}), resume=True, on_conflict="refuse"
    ) == (None, None)
    assert not (tmp_path / "b" / "meta.json").exists()


def test_cli_refuses_with_one_line_and_keeps_the_files(cli, tmp_path):
    out = tmp_path / "run"
    files = _fake_run(out, PARAMS.replace(pressure=382e6))
    res = cli("mca", "run", "--preset", "smoke", "--seed", "1", "--out", out, "--resume")
    assert_one_line_error(res, "out_dir", "params.pressure", "--overwrite", code=2)
    assert _unchanged(out, files)
    res = cli("mca", "run", "--preset", "smoke", "--seed", "1", "--out", out)
    assert_one_line_error(res, "out_dir", "holds an earlier run", "--resume", code=2)
    assert _unchanged(out, files)


def test_cli_overwrite_discards_the_other_run_and_runs(cli, tmp_path, lammps_available):
    out = tmp_path / "run"
    _fake_run(out, PARAMS.replace(pressure=382e6))
    res = cli("mca", "run", "--preset", "smoke", "--seed", "1", "--time", "1e-10", "--out", out,
              "--overwrite", "--json", timeout=300)
    assert res.returncode == 0, res.stderr
    meta = json.loads((out / "meta.json").read_text())
    assert meta["params"]["pressure"] == PARAMS.pressure  # the new run's, not the fake one's
    assert (out / "restart.232750.bin").exists() is False
