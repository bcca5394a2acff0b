"""The running-in through the chain: report.json contract and the Fig. 10 shape (issue 15)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from tests.runin.test_runin import _fig10_rates, fig10_checks
from tribolmp.scene import load_scene, parse_scene, scene_path


def _fig10_scene(k1, k2, *, w=1e-9, n=256, dx=1e-6):
    """Build a scene whose C1 rates put the crossovers at k1, k2 inside the part's grid."""
    return {
        "scene": {"name": "fig10", "seed": 7},
        "geometry": {"profile": "rough", "apparent_length": 1e-3, "apparent_width": 1e-3},
        "roughness": {
            "rms_height": 1e-10,
            "grid_points": n,
            "pixel_size": dx,
            "rolloff_wavelength": 100e-6,
            "short_cutoff_wavelength": 4e-6,
            "realizations": 4,
        },
        "load": {"normal_force": 10.0, "pressures": [1e7]},
        "kinematics": {"sliding_velocity": 0.01, "duration": 0.05},
        "rates": {"mu": 0.2, "step_length_m": 2.5e-9, **_fig10_rates(k1, k2, w)},
        "topography": {"dim": 2},
        "contact": {"method": "mdr"},
        # Stationarity is reached many times over (mu phi t ~ 1e5), so the phi sub-steps are not
        # needed.
        "running_in": {"checkpoints": 2, "phi_tolerance": 1e9, "convergence_check": False},
        "outputs": {"requested": ["topography"], "figures": False},
    }


def _evolved(tmp_path, data, name):
    from tribolmp.chain.runner import run_chain

    out = tmp_path / name
    run_chain(parse_scene(data, source=name), out, quiet=True, figures=False)
    rep = json.loads((out / "report.json").read_text())
    h = np.load(out / rep["handoffs"]["topography"]["surface"])
    return h, rep


def test_fig10_shape_appears_only_when_the_rates_put_k1_well_below_k2(tmp_path):
    """Check the chain's evolved spectrum: two plateaus, k^-2 between, iff k1 << k2 (Fig. 10)."""
    n, dx = 256, 1e-6
    yes = _fig10_scene(6e4, 2e6)  # k2/k1 = 33 inside [2 pi/L = 2.5e4, pi/dx = 3.1e6]
    no = _fig10_scene(2e6, 6e4)  # crossovers swapped: the spectrum rises toward high k
    h_yes, rep = _evolved(tmp_path, yes, "yes")
    h_no, _ = _evolved(tmp_path, no, "no")
    vals = rep["results"]["topography"]["values"]
    assert vals["eq23_source"] == "measured (C1)" and vals["domain_size_m"] == pytest.approx(n * dx)
    fig10_checks(h_yes, h_no, yes["rates"], no["rates"], n, dx)


@pytest.mark.slow
def test_rates_given_chain_contract(tmp_path):
    """rates_given.toml end to end (LAMMPS never starts): the issue's report.json contract."""
    from tribolmp.chain.runner import run_chain

    scene = load_scene(scene_path("rates_given"))
    out = tmp_path / "run"
    run_chain(scene, out, quiet=True, figures=True)
    rep = json.loads((out / "report.json").read_text())
    ri = rep["running_in"]
    keys = (
        "sliding_distance_m",
        "time_s",
        "rq_m",
        "normal_stiffness_N_m",
        "real_area_fraction",
        "mu",
    )
    assert (
        len({len(ri[k]) for k in keys}) == 1 and len(ri["rq_m"]) == scene.running_in.checkpoints + 1
    )
    topo = rep["results"]["topography"]["values"]
    r = scene.roughness
    assert topo["domain_size_m"] == pytest.approx(r.grid_points * r.pixel_size)
    assert topo["rq_initial_m"] == pytest.approx(r.rms_height, rel=0.05)
    assert topo["rq_final_m"] == ri["rq_m"][-1]
    mac = rep["results"]["macroscale"]["values"]
    assert mac["contact_stiffness_N_m"] <= mac["contact_stiffness_bound_N_m"]
    A = scene.geometry.apparent_length * scene.geometry.apparent_width
    assert mac["contact_stiffness_bound_N_m"] == pytest.approx(
        2 * scene.effective_modulus * math.sqrt(A / math.pi)
    )
    assert mac["mu_static"] > mac["mu_kinetic"]  # the scene's stated static_ratio 1.25
    traj = np.load(out / rep["handoffs"]["macroscale"]["trajectory"])
    assert {"drive_force", "contact_force", "mu_s_N", "mu_k_N"} <= set(traj.files)
    # Tribospectroscopy: the length came from the evolved surface; the fit ran on noisy data it
    # did not make.
    tri = rep["results"]["tribospectroscopy"]["values"]
    assert tri["length_m"] == pytest.approx(topo["correlation_length_m"])
    f2 = np.load(out / rep["handoffs"]["tribospectroscopy"]["f2"])
    assert not np.allclose(f2["f2_measured"], f2["f2"])
    for fig in ("runin_rq", "runin_psd", "runin_stiffness", "runin_mu", "stick_slip", "f2"):
        assert (out / rep["figures"][fig]).stat().st_size > 1000, fig
    md = (out / "report.md").read_text()
    assert (
        "What ran, from which inputs, under which assumptions" in md
        and "fixed by that identity" in md
    )
