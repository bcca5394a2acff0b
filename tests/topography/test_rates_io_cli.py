"""Rates mapping, height-map files and the ``tribolmp topography`` command."""

from __future__ import annotations

import json
import math
from dataclasses import replace

import numpy as np
import pytest

from tests.conftest import assert_one_line_error
from tribolmp.errors import ParameterError, SurfaceFileError
from tribolmp.models.topography import (
    TopographyParams,
    load_height_map,
    params_from_rates,
    params_from_scene,
    save_ascii_grid,
    save_height_map,
    spectra,
)
from tribolmp.scene import default_scene, parse_scene

RATES = {"diffusion_m2_s": 2e-12, "transfer_rate": 1e-3, "wear_rate": 0.5, "detachment_rate": 3.0,
         "reattachment_rate": 1.0, "step_length_m": 2.5e-9, "step_time_s": 1e-9, "mu": 0.3,
         "sliding_velocity_m_s": 5.0, "units": {"diffusion_m2_s": "m^2/s"}}


def test_params_from_rates_mapping():
    """Check the spectrum's plateaus and crossovers: block picture and measured coefficients.

    Checked through the stationary spectrum of :mod:`spectra` (not the mapping's own formulas):
    the high-k plateau of the legacy mapping must be one block's height at the block scale,
    l^(d+2) (issue 15: it was l^(d+2)/(2d) because the analysis sets tau = l^2/D while the mapping
    assumed D = l^2/(2 d tau)); the low-k plateau is l^3 nu_z / (2 mu) by the noise convention
    <f f> = 2 Dz; with the C1 coefficients the crossovers are the measured ones.
    """
    step = 2.5e-9
    big_k, small_k = 1e14, 1e-3  # far beyond both crossovers (k1 = 5e5, k2 ~ 1e6 1/m here)
    for dim in (1, 2):
        p = params_from_rates(RATES, dim=dim, n=64)
        kw = p.theory_kwargs()
        hi = float(spectra.stationary_psd(np.array([big_k]), **kw)[0])
        lo = float(spectra.stationary_psd(np.array([small_k]), **kw)[0])
        # 2D: the slab thickness defaults to one step length, so the 2D plateau is w l^3 = l^4.
        assert hi == pytest.approx(step ** (dim + 2), rel=1e-6)
        assert lo == pytest.approx(step ** (dim + 2) * (3.0 + 1.0) / (2 * 0.5), rel=1e-6)
        assert p.d0 == 2e-12 and p.mu == 0.5
    # The transfer rate is turned into a frequency at the MCA's velocity, never the part's.
    r = params_from_rates(
        {
            "transfer_rate": 2e-3,
            "wear_rate": 0.0,
            "diffusion_m2_s": 1e-12,
            "step_length_m": step,
            "sliding_velocity_m_s": 0.5,
        },
        n=8,
        duration=1.0,
    )
    assert r.dz == pytest.approx(step**3 * 1e-3 / 2) and r.mu == 0.0
    # D0 = 0 is a value (no diffusion), not a missing number replaced by a random-walk guess
    # (old code: `_rate(...) or l^2/(2 d tau)`): the legacy flux noise l^3 D0 vanishes with it.
    z = params_from_rates({**RATES, "diffusion_m2_s": 0.0})
    assert z.d0 == 0.0 and z.dx_noise == 0.0
    # With a measured flux noise, D0 = 0 has no stationary high-k spectrum: an error, not a guess.
    with pytest.raises(ParameterError, match="rates.d0_m2_s"):
        params_from_rates(
            {
                "mu_per_s": 1.0,
                "d0_m2_s": 0.0,
                "dz": 1e-30,
                "dx_l2": 1e-40,
                "sliding_velocity_m_s": 1.0,
            }
        )
    with pytest.raises(ParameterError, match=r"missing \['d0_m2_s', 'dx_l2'\]"):
        params_from_rates({k: v for k, v in RATES.items() if k != "diffusion_m2_s"})
    # Measured C1 coefficients set the shape: the crossovers of the spectrum
    # are sqrt(mu/D0), sqrt(Dz/Dx l^2).
    c1 = {
        "mu_per_s": 1e3,
        "d0_m2_s": 1e-9,
        "dz": 1e-24,
        "dx_l2": 1e-40,
        "sliding_velocity_m_s": 5.0,
    }
    q = params_from_rates(c1, dim=1, n=64, dx=1e-7)
    k = np.geomspace(1e2, 1e10, 4001)
    s = spectra.stationary_psd(k, **q.theory_kwargs())
    slope = np.gradient(np.log(s), np.log(k))
    # Half-way crossings of the log slope (0 -> -2 near k1 = 1e6, -2 -> 0
    # near k2 = 1e8 1/m); mid-way the slope is -2 up to 4 (k1/k)^2 = 0.04:
    k1, k2 = math.sqrt(1e3 / 1e-9), math.sqrt(1e-24 / 1e-40)
    assert k[np.argmin(np.abs(slope[k < math.sqrt(k1 * k2)] + 1.0))] == pytest.approx(k1, rel=0.02)
    assert k[k > math.sqrt(k1 * k2)][
        np.argmin(np.abs(slope[k > math.sqrt(k1 * k2)] + 1.0))
    ] == pytest.approx(k2, rel=0.02)
    assert slope[np.argmin(np.abs(k - math.sqrt(k1 * k2)))] == pytest.approx(-2.0, abs=0.05)


@pytest.mark.parametrize(
    "rates, match",
    [
        ({"step_time_s": 1e-9, "detachment_rate": 1.0, "sliding_velocity_m_s": 1.0}, "missing"),
        ({**RATES, "diffusion_m2_s": -1.0}, "rates.diffusion_m2_s"),
        (
            {
                **{k: v for k, v in RATES.items() if not k.endswith("tachment_rate")},
                "sliding_velocity_m_s": None,
            },
            "rates.sliding_velocity_m_s",
        ),
        (
            {
                "step_length_m": 1e-9,
                "diffusion_m2_s": 1e-12,
                "wear_rate": 1.0,
                "sliding_velocity_m_s": 1.0,
            },
            r"missing \['dz'\]",
        ),
        ({**RATES, "wear_rate": float("nan")}, "rates.wear_rate"),
    ],
)
def test_params_from_rates_errors(rates, match):
    with pytest.raises(ParameterError, match=match):
        params_from_rates(rates)


def test_params_from_scene_direct_and_rates():
    scene = default_scene()
    p = params_from_scene(scene)
    t = scene.topography
    assert (p.dim, p.n, p.dx, p.d0, p.mu) == (t.dim, t.grid_points, t.pixel_size, t.d0, t.mu)
    assert p.duration == pytest.approx(t.duration)
    # The default [topography] has both plateaus and a k^-2 range inside the grid's band.
    k1, k2 = p.crossovers()
    assert 2 * math.pi / p.length < k1 < k2 / 5 < math.pi / p.dx
    # Given rates win over [topography] rates; the grid still comes from [topography].
    q = params_from_scene(scene, rates=RATES)
    assert q.d0 == 2e-12 and q.n == t.grid_points and q.dx == t.pixel_size
    data = {"rates": {"diffusion_m2_s": 3e-12, "step_length_m": 2e-9, "step_time_s": 1e-9,
                      "transfer_rate": 1e-2, "wear_rate": 1e-2, "sliding_velocity_m_s": 5.0},
            "kinematics": {"sliding_velocity": 0.1}}
    s = params_from_scene(parse_scene(data))
    # The transfer frequency is taken at the MCA's 5 m/s, not the part's 0.1 m/s (issue 15).
    assert s.d0 == 3e-12 and s.dz == pytest.approx(
        2e-9**3 * 5e-2 / 2 * (2e-9 if s.dim == 2 else 1.0)
    )


@pytest.mark.parametrize("shape", [(64,), (16, 24)])
def test_height_map_roundtrip(tmp_path, rng, shape):
    h = rng.normal(scale=1e-9, size=shape)
    npy, side = save_height_map(tmp_path / "surf", h, 5e-9)
    meta = json.loads(side.read_text())
    assert meta["pixel_size_m"] == 5e-9 and meta["shape"] == list(shape)
    h2, px = load_height_map(npy)
    np.testing.assert_array_equal(h2, h)
    assert px == 5e-9
    for name in (["surf.asc", "surf.xyz"] if len(shape) == 2 else ["surf.xyz"]):
        path = save_ascii_grid(tmp_path / name, h, 5e-9)
        h3, px3 = load_height_map(path)
        np.testing.assert_allclose(h3, h, rtol=1e-9)  # 10 significant digits written
        assert px3 == pytest.approx(5e-9, rel=1e-9)


def test_ascii_grid_is_esri_layout(tmp_path):
    h = np.arange(6.0).reshape(2, 3)
    path = save_ascii_grid(tmp_path / "g.asc", h, 1e-6)
    lines = path.read_text().splitlines()
    assert lines[0] == "ncols 3" and lines[1] == "nrows 2" and lines[4].startswith("cellsize 1e-06")
    # First data row is y = 0 (h[0]), as instruments export text grids and
    # SurfaceTopography reads them.
    assert [float(v) for v in lines[6].split()] == [0.0, 1.0, 2.0]


def test_height_map_errors(tmp_path):
    with pytest.raises(SurfaceFileError, match="pixel_size"):
        save_height_map(tmp_path / "a", np.zeros(8), -1.0)
    with pytest.raises(SurfaceFileError, match="finite"):
        save_height_map(tmp_path / "a", np.array([0.0, np.nan, 1.0]), 1.0)
    (tmp_path / "bad.npy").write_bytes(b"not numpy")
    with pytest.raises(SurfaceFileError):
        load_height_map(tmp_path / "bad.npy")
    with pytest.raises(SurfaceFileError, match=".asc"):
        save_ascii_grid(tmp_path / "p.asc", np.zeros(8), 1.0)


def test_cli_evolve_json_contract(cli, tmp_path):
    args = [
        "topography",
        "evolve",
        "--dim",
        "1",
        "--n",
        "128",
        "--dx",
        "1e-8",
        "--d0",
        "1e-12",
        "--dx-noise",
        "2.5e-20",
        "--dz",
        "5.6e-20",
        "--mu",
        "10",
        "--l",
        "5e-8",
        "--dt",
        "0.05",
        "--steps",
        "20",
        "--replicas",
        "100",
        "--seed",
        "7",
        "--scheme",
        "exact",
        "--out",
        str(tmp_path / "o"),
        "--json",
    ]
    res = cli(*args)
    assert res.returncode == 0, res.stderr
    out = res.json()
    for key in ("k", "psd", "psd_theory", "time_s", "steps_per_s"):
        assert key in out
    k = np.array(out["k"])
    assert len(k) == 64 and np.all(k > 0) and k[0] == pytest.approx(2 * math.pi / 128e-8)
    ratio = np.array(out["psd"]) / np.array(out["psd_theory"])
    # 100 replicas: 63 complex modes, each mean of 100 Exp(1) (sd 10 %): all within 5 sd.
    assert np.all(np.abs(ratio[:-1] - 1) < 0.5) and abs(ratio.mean() - 1) < 0.04
    # Normalisation <h^2> = (1/L) sum S: the theory sum equals the
    # theoretical Rq^2 (k = 0 excluded).
    L = 128e-8
    assert spectra.mean_square_from_psd(k, np.array(out["psd_theory"]), L) == pytest.approx(
        out["rq_theory_m"] ** 2
    )
    h, px = load_height_map(tmp_path / "o" / "height_map.npy")
    assert h.shape == (128,) and px == 1e-8
    assert (tmp_path / "o" / "height_map.xyz").exists()
    # Same seed, same numbers.
    assert cli(*args).json()["psd"] == out["psd"]


def test_cli_2d_and_euler(cli):
    res = cli(
        "topography",
        "evolve",
        "--dim",
        "2",
        "--n",
        "32",
        "--dx",
        "1",
        "--d0",
        "1",
        "--dx-noise",
        "1",
        "--dz",
        "1",
        "--mu",
        "0.01",
        "--l",
        "0.1",
        "--dt",
        "0.1",
        "--steps",
        "30",
        "--scheme",
        "euler",
        "--seed",
        "1",
        "--json",
    )
    assert res.returncode == 0, res.stderr
    out = res.json()
    assert out["operator"] == "lattice" and len(out["k"]) == 16
    assert np.all(np.diff(out["k"]) > 0)


@pytest.mark.parametrize(
    "extra, fragments",
    [
        (["--d0", "-1"], ["d0: expected", "[0, inf)"]),
        (["--dz", "-1e-20"], ["dz: expected"]),
        (["--mu", "-2"], ["mu: expected"]),
        (["--dx", "0"], ["dx: expected", "(0, inf)"]),
        (["--dx", "-1e-9"], ["dx: expected"]),
        (["--n", "2"], ["n: expected", "[4,"]),
        (["--n", "9"], ["n: expected an even number"]),
        (["--dim", "3"], ["dim: expected"]),
        (
            ["--scheme", "euler", "--dt", "1"],
            ["dt: expected a step below the explicit stability limit"],
        ),
        (["--scheme", "rk4"], ["scheme: expected"]),
        (["--replicas", "0"], ["replicas: expected"]),
        (["--steps", "abc"], ["--steps"]),
    ],
)
def test_cli_bad_parameters_one_line_exit_2(cli, extra, fragments):
    res = cli("topography", "evolve", "--n", "16", "--steps", "2", *extra, "--json")
    assert_one_line_error(res, *fragments, code=2)


def test_params_replace_is_validated():
    p = TopographyParams(grid_points=16)
    with pytest.raises(ParameterError, match="mu"):
        replace(p, mu=-1.0)
