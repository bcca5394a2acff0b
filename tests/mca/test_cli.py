"""``tribolmp mca run``: JSON contract, scene input, one-line errors."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from tests.conftest import assert_one_line_error

FIELDS = (
    "mu",
    "mu_err",
    "layer_depth_m",
    "diffusion_m2_s",
    "transfer_rate",
    "atom_steps_per_s",
    "time_s",
)


@pytest.mark.lammps
def test_smoke_preset_json(cli, lammps_available, tmp_path):
    # the CI smoke: whole CLI path incl. the analysis' rates.json, under a minute
    res = cli("mca", "run", "--preset", "smoke", "--out", tmp_path / "run", "--json", timeout=120)
    assert res.returncode == 0, res.stderr
    data = res.json()
    for key in FIELDS:
        assert key in data, key
    assert data["time_s"] == pytest.approx(1e-9, rel=1e-3)
    assert data["atom_steps_per_s"] > 0
    if data["rates_json"] is not None:  # written by tribolmp.analysis.rates when present
        rates = json.loads(Path(data["rates_json"]).read_text())
        assert rates["mu"] == data["mu"] and rates["time_s"] == pytest.approx(data["time_s"])
        # issue 12: what rates.json flags is said on stderr too (it printed only mu before)
        assert ("mu is NOT steady" in res.stderr) == (rates.get("mu_steady") is False)
        assert ("no sheared (quasi-liquid) layer was measured" in res.stderr) == (
            not rates.get("layer_depth_m")
        )


@pytest.mark.lammps
def test_scene_file_and_overrides(cli, lammps_available, tmp_path):
    scene = tmp_path / "s.toml"
    scene.write_text(
        "[nanoscale]\nautomaton_diameter = 2.5e-9\ndim "
        "= 2\nsliding_velocity = 2.0\npressure = 50e6\n"
        "duration = 0.1e-9\nbox_length = 25e-9\nbody_height "
        "= 10e-9\nroughness_rms = 1e-9\npreset = 'smoke'\n"
    )
    out = tmp_path / "run"
    res = cli("mca", "run", scene, "--velocity", "3", "--out", out, "--json", timeout=120)
    assert res.returncode == 0, res.stderr
    meta = json.loads((out / "meta.json").read_text())
    assert meta["velocity_m_s"] == 3.0  # command line beats the scene
    assert meta["pressure_Pa"] == 50e6
    # the 2D default (rotated upper body) fits the box to both lattices within 3 spacings
    assert abs(meta["box_m"][0][1] - 25e-9) <= 3 * 2.5e-9


@pytest.mark.parametrize(
    "args, fragments",
    [
        (("--velocity", "-1"), ("sliding_velocity", "expected")),
        (("--pressure", "900e6"), ("pressure", "crush")),
        (("--np", "0"), ("np",)),
        (("--dim", "4"), ("--dim",)),
        (("--preset", "huge"), ("--preset",)),
    ],
)
def test_bad_input_one_line_exit_2(cli, args, fragments, tmp_path):
    res = cli("mca", "run", *args, "--out", tmp_path / "x", "--json")
    assert_one_line_error(res, *fragments, code=2)
    assert not (tmp_path / "x" / "system.data").exists()  # rejected before anything was built
