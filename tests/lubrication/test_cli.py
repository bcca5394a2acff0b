"""``tribolmp lubrication`` CLI: JSON contracts and one-line errors."""

from __future__ import annotations

import csv
import math

import pytest

from tests.conftest import assert_one_line_error

SPHERE = ("--radius", "1e-3", "--viscosity", "0.1", "--gap", "1e-6")


def test_squeeze_json_contract(cli):
    res = cli("lubrication", "squeeze", *SPHERE, "--velocity", "1e-3", "--json")
    assert res.returncode == 0, res.stderr
    out = res.json()
    assert {"force", "model", "time_s"} <= set(out)
    assert out["model"] == "damper"
    assert out["force"] == pytest.approx(6 * math.pi * 0.1 * 1e-6 * 1e-3 / 1e-6, rel=1e-12)
    rey = cli(
        "lubrication",
        "squeeze",
        *SPHERE,
        "--velocity",
        "1e-3",
        "--model",
        "reynolds",
        "--cells",
        "200",
        "--json",
    ).json()
    assert rey["force"] == pytest.approx(out["force"], rel=2e-3)  # 200-cell Reynolds grid error


def test_squeeze_power_law_and_sliding(cli):
    pl = cli(
        "lubrication",
        "squeeze",
        *SPHERE,
        "--velocity",
        "1e-3",
        "--power-law-index",
        "0.34",
        "--consistency",
        "0.1",
        "--json",
    )
    assert pl.returncode == 0, pl.stderr
    assert pl.json()["force"] > 0
    g = cli("lubrication", "sliding", *SPHERE, "--velocity", "1e-2", "--json").json()
    c = cli(
        "lubrication", "sliding", *SPHERE, "--velocity", "1e-2", "--model", "couette", "--json"
    ).json()
    assert 2.0 < g["force"] / c["force"] < 2.6


def test_bad_input_subprocess_exit_code(cli):
    assert_one_line_error(
        cli(
            "lubrication",
            "squeeze",
            *SPHERE[:2],
            "--viscosity",
            "-0.1",
            "--gap",
            "1e-6",
            "--velocity",
            "1e-3",
            "--json",
        ),
        "viscosity",
    )


@pytest.mark.parametrize(
    "args, fragment",
    [
        (("--radius", "1e-3", "--viscosity", "0.1", "--gap", "0", "--velocity", "1e-3"), "gap"),
        ((*SPHERE, "--velocity", "1e-3", "--power-law-index", "0.3333"), "power_law_index"),
        (
            (*SPHERE, "--velocity", "1e-3", "--power-law-index", "0.2", "--model", "reynolds"),
            "power_law_index",
        ),
        ((*SPHERE, "--velocity", "1e-3", "--model", "stokes"), "model"),
        ((*SPHERE, "--velocity", "nan"), "velocity"),
    ],
)
def test_bad_input_is_one_line_exit_2(capsys, args, fragment):
    # in-process (same code path as the console script, without the interpreter start-up)
    from tribolmp.cli import main

    code = main(["lubrication", "squeeze", *args, "--json"])
    err = capsys.readouterr().err
    assert code == 2
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert len(lines) == 1 and "Traceback" not in err and fragment in lines[0], err


def test_polish_writes_csv_and_plot(cli, tmp_path):
    scene = tmp_path / "s.toml"
    scene.write_text(
        "[lubricant]\nviscosity = 0.1\n[polishing]\nduration "
        "= 10.0\n[roughness]\ngrid_points = 16\n"
    )
    res = cli("lubrication", "polish", str(scene), "--out", str(tmp_path / "out"), "--steps", "10")
    assert res.returncode == 0, res.stderr
    with open(tmp_path / "out" / "roughness.csv") as fh:
        rows = list(csv.DictReader(fh))
    assert len(rows) == 11 and float(rows[-1]["time_s"]) == pytest.approx(10.0)
    assert float(rows[-1]["sq_m"]) < float(rows[0]["sq_m"])
    assert (tmp_path / "out" / "roughness.png").stat().st_size > 1000
    bad = tmp_path / "bad.toml"
    bad.write_text("[polishing]\npressure = -1.0\n")
    assert_one_line_error(
        cli("lubrication", "polish", str(bad), "--out", str(tmp_path / "o2")), "pressure"
    )


def test_approach_and_summary(cli):
    res = cli(
        "lubrication",
        "approach",
        "--radius",
        "1e-3",
        "--viscosity",
        "0.1",
        "--load",
        "1e6",
        "--gap",
        "1e-5",
        "--duration",
        "1",
        "--steps",
        "2",
        "--json",
    )
    assert res.returncode == 0, res.stderr
    assert res.json()["min_gap"] >= 0
    s = cli("lubrication", "summary", "--json")
    assert s.returncode == 0, s.stderr
    assert s.json()["alpha"] > 0
