"""LateralDiffusion against Brownian walkers of known D riding on sliding bodies."""

from __future__ import annotations

import numpy as np
import pytest

from tribolmp.analysis.diffusion import LateralDiffusion, Unwrapper
from tribolmp.analysis.outputs import open_trajectory, read_meta
from tribolmp.analysis.synthetic import make_walkers
from tribolmp.errors import ParameterError


def _run(tmp_path, seed, **kw):
    exp = make_walkers(tmp_path, np.random.default_rng(seed), **kw)
    meta = read_meta(tmp_path)
    return exp, meta, open_trajectory(tmp_path, meta)


@pytest.mark.parametrize("dim", [2, 3])
def test_known_diffusion_coefficient(tmp_path, dim):
    exp, meta, u = _run(tmp_path, 11, dim=dim, n_walkers=300, n_frames=80)
    r = LateralDiffusion(u, meta).run().results
    assert r.lateral_dims == exp["lateral_dims"]
    assert r.n_surface == exp["n_surface"]
    # seed-to-seed scatter of D/D_true: 3.5 % (2D) and 2.3 % (3D) at 200 walkers x 60 frames,
    # about 2.5 % and 1.7 % here; 10 % is 4 sigma.  Forgetting the drift (V = 20 m/s) or the
    # dimension factor would be off by orders of magnitude or by 2x.
    assert r.diffusion_m2_s == pytest.approx(exp["diffusion_m2_s"], rel=0.10)
    # the MSD at the longest fitted lag is linear in time: MSD = 2 n D t
    lag = r.lag_s[20]
    assert r.msd_m2[20] == pytest.approx(2 * r.lateral_dims * exp["diffusion_m2_s"] * lag, rel=0.15)


def test_reference_frames_agree_for_rigid_bodies(tmp_path):
    # D = 4e-9 m^2/s: the rms displacement over the fit window (3.2 nm)
    # exceeds one diameter (diffusive regime)
    exp, meta, u = _run(tmp_path, 5, n_walkers=150, n_frames=50, diffusion=4e-9)
    d = {ref: LateralDiffusion(u, meta, reference=ref).run().results.diffusion_m2_s
         for ref in ("group", "body", "anchor")}
    # bulk, base and slider move rigidly with the body here, so the three frames see the same
    # walks; they differ only by the noise of the walkers inside the group/body mean (~1/N)
    assert d["body"] == pytest.approx(d["anchor"], rel=0.03)
    assert d["group"] == pytest.approx(d["anchor"], rel=0.03)
    # against the truth: scatter ~4.5 % at 300 walkers x 50 frames; 4 sigma
    assert d["anchor"] == pytest.approx(exp["diffusion_m2_s"], rel=0.18)


def test_unwrapper_follows_across_the_boundary():
    L = np.array([10.0])
    x_true = np.arange(0, 60.0, 0.9)[:, None]  # crosses the box six times
    un = Unwrapper(x_true[0] % L)
    for x in x_true[1:]:
        out = un.update(x % L, L)
    assert out[0] == pytest.approx(x_true[-1, 0])


def test_bad_arguments(tmp_path):
    exp, meta, u = _run(tmp_path, 1, n_walkers=10, n_frames=8)
    with pytest.raises(ParameterError, match="reference"):
        LateralDiffusion(u, meta, reference="lab")
    with pytest.raises(ParameterError, match="fit_range"):
        LateralDiffusion(u, meta, fit_range=(0.5, 0.2))


def test_diffusive_walkers_pass_the_regime_test(tmp_path):
    exp, meta, u = _run(tmp_path, 21, n_walkers=200, n_frames=80, diffusion=4e-9)
    r = LateralDiffusion(u, meta).run().results
    # Brownian walkers: MSD exponent 1 (scatter ~0.03 at 400 walkers); rms sqrt(2 D t) = 4 nm at the
    # end of the 2 ns window, above d = 2.5 nm
    assert 0.9 < r.msd_exponent < 1.1
    assert r.rms_displacement_m > meta.automaton_diameter_m
    assert r.diffusive is True and r.diffusion_reason == ""
    assert r.diffusion_m2_s == pytest.approx(exp["diffusion_m2_s"], rel=0.15)


def test_sheared_walkers_are_not_diffusion(tmp_path):
    # shear dispersion: per-walker drift of 2 m/s sd on top of a weak walk (sd^2 t >>
    # 2 D from 0.2 ns on), MSD ~ t^2; a linear fit would report a D 40x the true one
    exp, meta, u = _run(
        tmp_path, 22, n_walkers=200, n_frames=80, diffusion=2e-10, shear_velocity_sd=2.0
    )
    r = LateralDiffusion(u, meta).run().results
    assert r.msd_exponent > 1.5
    assert r.diffusive is False
    assert np.isnan(r.diffusion_m2_s)
    assert "t^" in r.diffusion_reason and "ballistic" in r.diffusion_reason
    assert r.diffusion_fit_m2_s > 10 * exp["diffusion_m2_s"]


def test_caged_walkers_are_not_diffusion(tmp_path):
    # diffusive in form but rms below one diameter: D = 1e-10 m^2/s gives
    # sqrt(2 D 2 ns) = 0.6 nm < 2.5 nm
    exp, meta, u = _run(tmp_path, 23, n_walkers=200, n_frames=80, diffusion=1e-10)
    r = LateralDiffusion(u, meta).run().results
    assert 0.8 < r.msd_exponent < 1.2
    assert r.diffusive is False
    assert np.isnan(r.diffusion_m2_s)
    assert "below one automaton diameter" in r.diffusion_reason
