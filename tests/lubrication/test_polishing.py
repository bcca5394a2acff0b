"""Lubricated polishing.

Roughness history against a particle-resolved simulation, mass balance, the film.
"""

from __future__ import annotations

import numpy as np
import pytest

from tribolmp.errors import ParameterError
from tribolmp.models.lubrication.polishing import (
    PolishParams,
    params_from_scene,
    polish,
    squeeze_out_time,
)
from tribolmp.scene import parse_scene

BASE = dict(grid_points=32, steps=30, duration=6.0)


def _pair(eta, seed, **kw):
    from tribolmp.models.lubrication.polishing import polish_resolved, self_affine_surface

    p = PolishParams(grid_points=32, steps=6, duration=30.0, viscosity=eta, **kw)
    h0 = self_affine_surface(
        32, p.pixel_size, p.rms_height, p.hurst, p.rolloff_wavelength, np.random.default_rng(seed)
    )
    return polish(p, rng=np.random.default_rng(seed + 10), h0=h0), polish_resolved(
        p, rng=np.random.default_rng(seed + 20), h0=h0
    )


def test_roughness_evolution_matches_a_particle_resolved_simulation():
    """Mean-field polishing against the particle-resolved simulation of the same step.

    (Preston's law itself is no test here: with a thin film the Archard sum is
    k v sum F = k p v A because the load balance is enforced; it holds by
    construction in both models.)  The prediction is the roughness history:
    Sq(t)/Sq(0) of the two models on the same initial map, different particle
    draws, agrees to 0.2 % at every output step (measured, 32^2, 30 s, two maps;
    Sq falls to 0.59-0.60).  The tolerance 1 % is 5x that; a 30 % error in the
    pressure in the reference moves Sq by up to 15 % (measured), failing it.
    """
    for seed in (1, 2):
        mf, ref = _pair(0.1, seed)
        assert ref.sq[-1] < 0.7 * ref.sq[0]
        assert np.max(np.abs(mf.sq / ref.sq - 1)) < 0.01


def test_viscous_film_reduces_removal_and_the_mean_field_underestimates_it():
    # eta 1e3 Pa s: the squeeze-out takes a share of each passage, the film carries part of
    # the load and the removal falls below k p v in both models.  Measured removal/(k p v):
    # mean field 0.334 / 0.360, particle-resolved 0.431 / 0.457 (two maps): the mean field's
    # line-averaged load balance spreads the load over more, lighter contacts, whose
    # squeeze-out takes longer, so it underestimates the removal by ~22 % (a stated limit).
    for seed in (1, 2):
        mf, ref = _pair(1e3, seed)
        assert ref.removal_rate < 0.6 * ref.preston_rate
        assert 0.70 < mf.removal_rate / ref.removal_rate < 0.85


def test_roughness_decreases_and_mass_balances():
    res = polish(
        PolishParams(grid_points=48, steps=60, duration=60.0), rng=np.random.default_rng(3)
    )
    assert res.sq[-1] < 0.8 * res.sq[0]
    # coarse trend: each third of the run ends smoother than the previous one
    thirds = res.sq[:: len(res.sq) // 3]
    assert np.all(np.diff(thirds) < 0)
    # removed volume (Archard sum) equals the volume lost by the height map
    assert res.mass_balance_error < 1e-9
    assert res.volume_change[-1] == pytest.approx(res.removed_volume[-1], rel=1e-9)
    assert res.load_error < 1e-8  # the pad's load balance is solved to round-off


def test_squeeze_out_time_is_the_pair_law_integral():
    from scipy import integrate

    from tribolmp.models.lubrication.pairlaw import pairlaw_sphere_plane_exact

    a, eta, F, hf, hc = 1e-6, 0.1, 1e-5, 1e-6, 1e-9
    # dt = c(h) dh / F with c(h) = F_pairlaw(V = 1) / 1
    # integrate in u = ln h (the integrand ~ 1/h spans three decades)
    t = integrate.quad(
        lambda u: pairlaw_sphere_plane_exact(a, eta, np.exp(u), 1.0) * np.exp(u) / F,
        np.log(hc),
        np.log(hf),
        epsrel=1e-13,
    )[0]
    assert float(squeeze_out_time(a, eta, F, hf, hc)) == pytest.approx(t, rel=1e-9)


def test_deterministic_with_seed_and_validation():
    p = PolishParams(grid_points=16, steps=5, duration=1.0)
    a = polish(p, rng=np.random.default_rng(1))
    b = polish(p, rng=np.random.default_rng(1))
    assert np.array_equal(a.h, b.h)
    with pytest.raises(ParameterError, match="film_cutoff"):
        PolishParams(film_cutoff=2e-6, film_thickness=1e-6)
    with pytest.raises(ParameterError, match="h0"):
        polish(p, rng=np.random.default_rng(1), h0=np.zeros((3, 3)))


def test_params_from_scene():
    scene = parse_scene(
        {"lubricant": {"viscosity": 0.3}, "polishing": {"pressure": 2e5, "velocity": 0.2}}
    )
    p = params_from_scene(scene, grid_points=16)
    assert (p.viscosity, p.pressure, p.sliding_velocity, p.grid_points) == (0.3, 2e5, 0.2, 16)
    assert p.E_star == pytest.approx(scene.effective_modulus)


def test_result_does_not_depend_on_output_steps():
    # sub-steps cap the local cut per step, so coarse output steps give the same physics
    a = polish(PolishParams(grid_points=16, steps=3, duration=60.0), rng=np.random.default_rng(5))
    b = polish(PolishParams(grid_points=16, steps=30, duration=60.0), rng=np.random.default_rng(5))
    assert a.sq[-1] < 0.7 * a.sq[0]
    # different random particle sequences: Sq agrees within the run-to-run scatter (measured ~3 %)
    assert a.sq[-1] == pytest.approx(b.sq[-1], rel=0.1)
