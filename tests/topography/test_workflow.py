"""Smoke test of workflows/fig10_topography_spectrum.py (quick variant) and its numbers."""

from __future__ import annotations

import importlib.util
import json
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def load(name):
    spec = importlib.util.spec_from_file_location(name, ROOT / "workflows" / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def check_summary(out: Path, slope_sd: float):
    for name in (
        "fig10_topography_spectrum.png",
        "running_in.png",
        "fig10_psd.csv",
        "running_in.csv",
        "surface_2d.npy",
        "surface_2d.json",
    ):
        assert (out / name).stat().st_size > 0, name
    assert (out / "fig10_topography_spectrum.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    s = json.loads((out / "summary.json").read_text())
    f = s["fig10"]
    # Fitted slope agrees with the analytic curve fitted over the same range, within
    # slope_sd standard errors of the fit.
    assert abs(f["slope_1d"] - f["slope_1d_theory_same_range"]) < slope_sd * f["slope_1d_err"]
    # Every log bin within 5 sampling sd of theory (~40 bins: P(any > 5 sd)
    # < 1e-4 under the theory).
    assert f["max_logbin_deviation_sd"] < 5
    # The simulated high-k plateau against the analytic Dx l^2/D0: the theory over the same
    # modes is within 4 % of the plateau, and the measured mean within 4 sampling sd (~0.2 %) of
    # the theory. (This replaces low/high == (k2/k1)^2, an algebraic identity of the inputs.)
    assert f["high_plateau_theory_same_modes_m3"] == pytest.approx(f["high_plateau_m3"], rel=0.04)
    assert (
        abs(f["high_plateau_measured_m3"] / f["high_plateau_theory_same_modes_m3"] - 1)
        < 4 * f["high_plateau_sampling_sd"]
    )
    r = s["running_in"]
    # Both starts approach the stationary roughness (within 15 %: 8 replicas of a surface
    # whose Rq^2 is dominated by a few low-k modes).
    assert r["rq_initial_rough"] > 2 * r["rq_stationary_theory"]
    for key in ("rq_final_flat", "rq_final_rough"):
        assert r[key] == pytest.approx(r["rq_stationary_theory"], rel=0.15)
    return f


def test_fig10_workflow_quick(tmp_path):
    mod = load("fig10_topography_spectrum")
    assert mod.main(["--quick", "--out", str(tmp_path / "q")]) == 0
    check_summary(tmp_path / "q", slope_sd=4)


@pytest.mark.slow
def test_fig10_workflow_full(tmp_path):
    mod = load("fig10_topography_spectrum")
    assert mod.main(["--out", str(tmp_path / "f")]) == 0
    f = check_summary(tmp_path / "f", slope_sd=3)
    assert f["slope_2d_radial"] == pytest.approx(f["slope_2d_radial_theory"], abs=0.1)
    assert f["slope_2d_line_scans"] == pytest.approx(f["slope_2d_line_scans_theory"], abs=0.1)
    assert f["slope_2d_line_scans_theory"] == pytest.approx(-1.0, abs=0.05)
