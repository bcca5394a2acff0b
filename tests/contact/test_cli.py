"""The ``tribolmp contact`` command line: JSON contracts and one-line errors."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from tests.conftest import assert_one_line_error
from tribolmp.models.contact import reference as ref
from tribolmp.models.contact.rough import generate_surface, self_affine_psd


class _InProcess:
    """Result of ``tribolmp.cli.main`` run in this process.

    In-process because subprocesses cost ~4 s each on 2 busy cores.
    """

    def __init__(self, code, out, err):
        self.returncode, self.stdout, self.stderr = code, out, err


@pytest.fixture
def run(capsys):
    from tribolmp.cli import main

    def _run(*args):
        code = main([str(a) for a in args])
        out = capsys.readouterr()
        return _InProcess(code, out.out, out.err)

    return _run


@pytest.fixture
def surface(tmp_path):
    h = generate_surface(
        32, 2e-6, self_affine_psd(1e-6, 0.8, 6.4e-5, 8e-6), np.random.default_rng(1)
    )
    path = tmp_path / "surf.npy"
    np.save(path, h)
    return path, h


def test_axisymmetric_json(cli, run):
    res = cli(
        "contact",
        "axisymmetric",
        "--profile",
        "sphere",
        "--radius",
        "1e-3",
        "--modulus",
        "1e11",
        "--indentation",
        "1e-6",
        "--json",
    )
    assert res.returncode == 0, res.stderr
    out = res.json()
    assert {"force", "contact_radius", "time_s"} <= set(out)
    assert out["force"] == pytest.approx(float(ref.hertz_force(1e-6, 1e-3, 1e11)), rel=1e-6)
    assert out["contact_radius"] == pytest.approx(math.sqrt(1e-9), rel=1e-6)
    res = run(
        "contact",
        "axisymmetric",
        "--profile",
        "cone",
        "--half-angle",
        "70",
        "--modulus",
        "1e11",
        "--indentation",
        "1e-6",
        "--json",
    )
    # half-angle from the axis: f = r / tan(70 deg)
    assert json.loads(res.stdout)["force"] == pytest.approx(
        float(ref.cone_force(1e-6, 70.0, 1e11)), rel=1e-6
    )
    res = run(
        "contact",
        "axisymmetric",
        "--profile",
        "flat",
        "--radius",
        "1e-3",
        "--modulus",
        "1e11",
        "--indentation",
        "1e-6",
        "--method",
        "bem",
        "--grid",
        "32",
        "--json",
    )
    assert res.returncode == 0, res.stderr
    assert json.loads(res.stdout)["force"] == pytest.approx(
        2e2, rel=3e-2
    )  # 2 E* R d; pixelated edge at 32^2


def test_axisymmetric_adhesion_json(run):
    res = run(
        "contact",
        "axisymmetric",
        "--profile",
        "sphere",
        "--radius",
        "1e-3",
        "--modulus",
        "1e9",
        "--indentation",
        "1e-8",
        "--work-of-adhesion",
        "0.05",
        "--json",
    )
    assert res.returncode == 0, res.stderr
    out = json.loads(res.stdout)
    assert out["pull_off_force"] == pytest.approx(
        ref.jkr_pull_off_force_control(1e-3, 0.05), rel=1e-4
    )
    a = out["contact_radius"]
    assert out["force"] == pytest.approx(float(ref.jkr_force(a, 1e-3, 1e9, 0.05)), rel=1e-6)


def test_rough_json_mdr_and_bem(cli, run, surface):
    path, h = surface
    common = (
        "contact",
        "rough",
        "--surface",
        path,
        "--pixel-size",
        "2e-6",
        "--modulus",
        "1e11",
        "--pressures",
        "1e6,1e7",
        "--json",
    )
    mdr = cli(*common, "--method", "mdr", "--realizations", "4", "--seed", "2")
    assert mdr.returncode == 0, mdr.stderr
    rows = mdr.json()
    assert [r["pressure"] for r in rows] == [1e6, 1e7]
    for r in rows:
        assert {
            "pressure",
            "force",
            "stiffness",
            "approach",
            "time_s",
            "stiffness_q10",
            "stiffness_q90",
        } <= set(r)
        assert "area_fraction" not in r  # the MDR contact length is not an area
        assert r["force"] == pytest.approx(r["pressure"] * (32 * 2e-6) ** 2, rel=1e-12)
    bem = run(*common, "--method", "bem", "--periodic")
    assert bem.returncode == 0, bem.stderr
    for r in json.loads(bem.stdout):
        assert {"pressure", "force", "stiffness", "approach", "time_s", "area_fraction"} <= set(r)
        assert 0 < r["area_fraction"] < 1


def test_bad_input_one_line_subprocess(cli, surface):
    path, _ = surface
    # One real subprocess: exit code 2, one line, no traceback.
    res = cli(
        "contact",
        "rough",
        "--surface",
        path,
        "--pixel-size",
        "2e-6",
        "--modulus",
        "1e9",
        "--pressures",
        "1e6,2e9",
        "--json",
    )
    assert_one_line_error(res, "pressures", "below the modulus")


def test_bad_input_one_line(run, surface, tmp_path):
    path, h = surface
    base = ("contact", "rough", "--pixel-size", "2e-6", "--pressures", "1e6", "--json")
    bad = h.copy()
    bad[1, 1] = np.inf
    np.save(tmp_path / "nan.npy", bad)
    assert_one_line_error(
        run(*base, "--surface", tmp_path / "nan.npy", "--modulus", "1e11"), "surface", "finite"
    )
    np.save(tmp_path / "one.npy", h[0])
    assert_one_line_error(
        run(*base, "--surface", tmp_path / "one.npy", "--modulus", "1e11"), "surface", "2D array"
    )
    np.save(tmp_path / "three.npy", h[None])
    assert_one_line_error(
        run(*base, "--surface", tmp_path / "three.npy", "--modulus", "1e11"), "surface", "2D array"
    )
    (tmp_path / "text.npy").write_text("not an array")
    assert_one_line_error(
        run(*base, "--surface", tmp_path / "text.npy", "--modulus", "1e11"), "surface"
    )
    assert_one_line_error(run(*base, "--surface", path, "--modulus=-1e11"), "modulus")
    np.save(tmp_path / "rect.npy", h[:, :16])
    assert_one_line_error(
        run(*base, "--surface", tmp_path / "rect.npy", "--modulus", "1e11", "--method", "bem"),
        "square",
    )
    assert_one_line_error(
        run(
            "contact",
            "axisymmetric",
            "--profile",
            "sphere",
            "--modulus",
            "1e11",
            "--indentation",
            "1e-6",
        ),
        "--radius",
    )
    assert_one_line_error(
        run(
            "contact",
            "axisymmetric",
            "--profile",
            "sphere",
            "--radius",
            "1e-3",
            "--modulus=-5",
            "--indentation",
            "1e-6",
        ),
        "modulus",
    )
    assert_one_line_error(
        run(
            "contact",
            "axisymmetric",
            "--profile",
            "sphere",
            "--radius",
            "1e-3",
            "--modulus",
            "1e9",
            "--indentation",
            "1e-8",
            "--work-of-adhesion",
            "0.1",
            "--method",
            "bem",
        ),
        "work_of_adhesion",
    )


def test_rough_mdr_flags_closed_lines(run, surface):
    # At p = 3e9 Pa on E* = 1e11 Pa (p/E* = 0.03, p/(E* h'rms) ~ 0.2) most lines of this 32-point
    # surface close; at 1e6 Pa none does.  A closed line's stiffness is E* L exactly, so the JSON's
    # closed_fraction must match the share of rows at the punch limit, and the run warns once.
    path, h = surface
    L = 32 * 2e-6
    res = run(
        "contact",
        "rough",
        "--surface",
        path,
        "--pixel-size",
        "2e-6",
        "--modulus",
        "1e11",
        "--pressures",
        "1e6,3e9",
        "--realizations",
        "8",
        "--seed",
        "3",
        "--json",
    )
    assert res.returncode == 0, res.stderr
    low, high = json.loads(res.stdout)
    assert low["closed_fraction"] == 0.0 and low["warnings"] == []
    assert (
        high["closed_fraction"] > 0.1
        and len(high["warnings"]) == 1
        and "punch limit" in high["warnings"][0]
    )
    assert high["stiffness_q90"] == pytest.approx(1e11 * L, rel=1e-12)
    lines = [ln for ln in res.stderr.splitlines() if ln.strip()]
    assert len(lines) == 1 and lines[0].startswith("warning:") and "3e+09 Pa" in lines[0]
