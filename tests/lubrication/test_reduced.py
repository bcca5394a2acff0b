"""Reduced models: registry, accuracy against the Reynolds and Stokes references, scene adapter."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tribolmp.errors import ParameterError
from tribolmp.models.lubrication import (
    Params,
    lubrication_summary,
    params_from_scene,
    solve,
    squeeze_damper_force,
)
from tribolmp.models.lubrication import reference as ref
from tribolmp.models.lubrication.reduced import SLIDING, SQUEEZE, sliding_force, squeeze_force
from tribolmp.scene import parse_scene

R, ETA, V = 1e-3, 0.1, 1e-3


@pytest.mark.parametrize("eps", [1e-8, 1e-4, 1e-2])
def test_damper_within_1_percent_of_reynolds(eps):
    p = Params(radius=R, viscosity=ETA, gap=eps * R, velocity=V)
    d = squeeze_force(p, "damper")
    r = squeeze_force(p, "reynolds")
    # The paraboloid Reynolds problem is self-similar in h/R: the remaining
    # difference is the 400-cell discretisation (4e-4) plus the domain cut (2e-6).
    assert abs(d.force / r.force - 1.0) < 1e-3
    assert r.truncation_error < 1e-5


def test_damper_against_stokes_reference_curve():
    eps = np.geomspace(1e-8, 1e-2, 13)
    err = np.array(
        [ref.damper_force(R, ETA, e * R, V) / ref.brenner_force(R, ETA, e * R, V) - 1 for e in eps]
    )
    # the bare damper misses the Cox-Brenner terms (h/5R) ln(R/h) + 0.97 h/R:
    # under 1 % for h/R <= 4e-3, 1.9 % at h/R = 1e-2 (reported, not hidden)
    assert np.all(np.abs(err[eps <= 4e-3]) < 0.01)
    assert err[-1] == pytest.approx(-0.0186, abs=5e-4)
    cb = np.array(
        [
            squeeze_force(
                Params(radius=R, viscosity=ETA, gap=e * R, velocity=V), "cox-brenner"
            ).force
            for e in eps
        ]
    )
    br = np.array([ref.brenner_force(R, ETA, e * R, V) for e in eps])
    assert np.all(np.abs(cb / br - 1) < 1e-4)  # Cox-Brenner: 4e-5 at h/R = 1e-2, less below


def test_velocity_to_zero_is_linear_and_signed():
    p = Params(radius=R, viscosity=ETA, gap=1e-6, velocity=1e-30)
    for model in ("damper", "cox-brenner", "brenner"):
        f = squeeze_force(p, model).force
        assert f > 0 and math.isfinite(f)
        assert squeeze_force(
            Params(radius=R, viscosity=ETA, gap=1e-6, velocity=-1e-30), model
        ).force == pytest.approx(-f)
    assert (
        squeeze_force(Params(radius=R, viscosity=ETA, gap=1e-6, velocity=0.0), "brenner").force
        == 0.0
    )
    pl = Params(radius=R, viscosity=ETA, gap=1e-6, velocity=0.0, power_law_index=0.5)
    assert squeeze_force(pl, "damper").force == 0.0


def test_power_law_models_and_refusals():
    p = Params(radius=R, viscosity=ETA, gap=1e-6, velocity=V, power_law_index=0.8, consistency=0.3)
    assert squeeze_force(p, "damper").force == pytest.approx(
        ref.power_law_squeeze_force(R, 0.3, 0.8, 1e-6, V)
    )
    r = squeeze_force(p, "reynolds")
    # truncated domain (1000 contact radii) and 400 cells: truncation_error
    # is the exact missing share
    assert r.force == pytest.approx(
        squeeze_force(p, "power-law").force * (1 - r.truncation_error), rel=1e-3
    )
    with pytest.raises(ParameterError, match="model"):
        squeeze_force(p, "brenner")
    with pytest.raises(ParameterError, match="power_law_index"):
        Params(power_law_index=1 / 3)
    with pytest.raises(ParameterError, match="cox-brenner"):
        squeeze_force(Params(radius=R, gap=0.2 * R), "cox-brenner")


def test_registries_and_solve():
    assert set(SQUEEZE.names) == {"damper", "cox-brenner", "brenner", "reynolds", "power-law"}
    assert set(SLIDING.names) == {"gcb", "couette", "faxen"}
    res = solve(Params(radius=R, viscosity=ETA, gap=1e-6, velocity=V), method="damper")
    assert res.status == 0 and res.time_s >= 0 and res.units["force"] == "N"
    s = sliding_force(Params(radius=R, viscosity=ETA, gap=1e-6, sliding_velocity=1e-2), "gcb")
    assert s.force == pytest.approx(ref.gcb_sliding_force(R, ETA, 1e-6, 1e-2))


def test_squeeze_damper_force_contract():
    assert squeeze_damper_force(R, ETA, 1e-6, V) == pytest.approx(
        6 * math.pi * ETA * R**2 * V / 1e-6
    )
    for bad in (dict(viscosity=-1.0), dict(gap=0.0), dict(radius=float("nan"))):
        kw = dict(radius=R, viscosity=ETA, gap=1e-6, velocity=V) | bad
        with pytest.raises(ParameterError):
            squeeze_damper_force(**kw)


def test_params_from_scene_and_summary():
    scene = parse_scene(
        {"lubricant": {"viscosity": 0.2, "film_thickness": 2e-6}, "geometry": {"radius": 2e-3}}
    )
    p = params_from_scene(scene)
    assert (p.radius, p.viscosity, p.gap) == (2e-3, 0.2, 2e-6)
    summ = lubrication_summary(scene, gaps_over_radius=[1e-4, 1e-2], reynolds_cells=200)
    assert summ.alpha == pytest.approx(6 * math.pi * 0.2 * 4e-6)
    # damper vs the numerical Reynolds solve: the same thin-film physics, so this is the 200-cell
    # grid error only, identical at both gaps (self-similar problem), not the damper's error
    assert np.all(np.abs(summ.reynolds_grid_error) < 2e-3)
    assert np.ptp(summ.reynolds_grid_error) < 1e-9
    # the damper's own error is against the exact Stokes force (Brenner's series), checked
    # here against the independent Cox-Brenner asymptote -(eps ln(1/eps)/5 + 0.9713 eps)/(1 + ...)
    eps = summ.gap_over_radius
    cb = 1 / (1 + eps * np.log(1 / eps) / 5 + 0.9713 * eps) - 1
    assert summ.error_damper_vs_stokes == pytest.approx(
        cb, rel=5e-3, abs=1e-6
    )  # O(eps^2 ln) terms: 2e-3 at 1e-2
    assert summ.force_brenner.shape == summ.gap.shape
    with pytest.raises(ParameterError, match="lubricant"):
        params_from_scene(parse_scene({}))
