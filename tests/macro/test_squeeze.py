"""Squeeze-film damper in the body's normal direction.

Exact solutions, positivity, contact engagement.
"""

import json
import math

import numpy as np
import pytest

from tribolmp.errors import ParameterError
from tribolmp.models.macro import (
    ContactSprings,
    SqueezeParams,
    profile_from_geometry,
    squeeze_approach,
)
from tribolmp.models.macro.reference import squeeze_approach_gap

E_STAR = 206e9 / (2 * (1 - 0.3**2))
G_STAR = 1.0 / (2 * (2 - 0.3) / (4 * 206e9 / 2.6))
W, R, ETA, H0 = 10.0, 5e-3, 0.1, 1e-6
ALPHA = 6 * math.pi * ETA * R**2


def test_massless_constant_load_is_exponential_and_never_negative():
    dur = 200 * ALPHA / W  # h falls by e^-200 (to ~1e-93 m): an explicit step in h would cross zero
    res = squeeze_approach(SqueezeParams(load=W, radius=R, viscosity=ETA, gap=H0, duration=dur))
    assert res.alpha == pytest.approx(
        ALPHA, rel=1e-14
    )  # the lubrication model's damper is 6 pi eta R^2
    assert np.all(res.gap > 0)
    exact = squeeze_approach_gap(res.t, H0, W, R, ETA)
    # ln h is linear in t here, which Radau integrates to round-off; 1e-9 = the requested rtol
    assert np.max(np.abs(res.log_gap - np.log(exact / H0))) < 1e-9 * 200
    assert np.max(np.abs(res.gap / exact - 1)) < 1e-9 * 200
    # overdamped: the film carries the whole load at every instant
    assert np.max(np.abs(res.film_force / W - 1)) < 1e-9
    assert np.all(res.contact_force == 0.0)


def test_with_mass_the_first_integral_holds():
    # m h'' = -W + alpha V/h  integrates to  m h' + alpha ln(h/h0) + W t = m h'(0)  (exact, any m)
    m, v0 = 0.02, 1e-4
    dur = 20 * ALPHA / W
    p = SqueezeParams(
        load=W, radius=R, viscosity=ETA, gap=H0, duration=dur, mass=m, approach_velocity=v0
    )
    res = squeeze_approach(p)
    assert np.all(res.gap > 0)
    inv = m * (-res.approach_velocity) + ALPHA * res.log_gap + W * res.t - m * (-v0)
    # rtol 1e-9 per step on (ln h, momentum); the invariant's terms are at most W*duration
    assert np.max(np.abs(inv)) < 1e-7 * W * dur
    # once the body has come to rest (V -> 0) the massless exponential is recovered, shifted by
    # the initial momentum: alpha ln(h/h0) = -W t - m v0 (+ m V, here < 1e-6 in ln h)
    assert m * res.approach_velocity[-1] / ALPHA < 1e-6
    assert res.log_gap[-1] == pytest.approx(-W * dur / ALPHA - m * v0 / ALPHA, abs=1e-5)


def test_contact_takes_over_the_load():
    x, g = profile_from_geometry("sphere", W, E_STAR, n_springs=201, radius=R)
    c = ContactSprings(x, g, E_STAR, G_STAR, 0.3)
    d_eq = c.indentation(W)
    hc = 2 * d_eq  # asperities touch at 2 d_eq: equilibrium gap h = d_eq > 0
    res = squeeze_approach(
        SqueezeParams(load=W, radius=R, viscosity=ETA, gap=3 * d_eq, duration=0.05, contact_gap=hc),
        c,
    )
    assert np.all(res.gap > 0)
    # static equilibrium: the MDR contact carries W at the indentation d_eq = h_c - h
    assert res.gap[-1] == pytest.approx(hc - d_eq, rel=1e-6)
    assert res.contact_force[-1] == pytest.approx(W, rel=1e-6)
    assert res.contact_force[0] == 0.0 and res.film_force[-1] < 1e-6 * W


def test_bad_inputs_are_one_line_parameter_errors():
    with pytest.raises(ParameterError, match="gap"):
        SqueezeParams(gap=-1e-6)
    with pytest.raises(ParameterError, match="contact"):
        squeeze_approach(SqueezeParams(contact_gap=1e-7))


def test_tabulated_load_reproduces_the_linear_unloading_path():
    from tribolmp.models.macro import ConstantFriction, StickSlipParams, stick_slip

    law = ConstantFriction(0.4, 0.3)
    kw = {
        "mass": 0.1,
        "drive_stiffness": 1e5,
        "drive_velocity": 0.01,
        "normal_force": 10.0,
        "duration": 0.05,
    }
    ref = stick_slip(StickSlipParams(**kw, unload_time=0.04), law, method="rk45")
    tab = stick_slip(
        StickSlipParams(**kw), law, method="rk45", normal_load=([0.0, 0.04, 0.05], [10.0, 0.0, 0.0])
    )
    # the same piecewise-linear N(t) through two code paths; event times located to rtol 1e-9
    assert tab.n_transitions == ref.n_transitions > 4
    assert np.allclose(
        [e["t"] for e in tab.events], [e["t"] for e in ref.events], rtol=0, atol=1e-9
    )
    with pytest.raises(ParameterError, match="normal_load"):
        stick_slip(StickSlipParams(**kw), law, normal_load=([0.0, 0.0], [1.0, 1.0]))


def test_load_carried_by_the_film_makes_the_body_slip_earlier():
    """Lubricated body.

    The solid contact takes the load only as the film drains, so the body slips early.
    """
    from scipy.optimize import brentq

    from tribolmp.models.macro import ConstantFriction, StickSlipParams, stick_slip

    x, g = profile_from_geometry("sphere", W, E_STAR, n_springs=201, radius=R)
    c = ContactSprings(x, g, E_STAR, G_STAR, 0.3)
    d_eq = c.indentation(W)
    # heavy oil (5 Pa s); asperities already pressed by 0.5 d_eq at t = 0
    # (N_c = 0.35 W), film draining
    sq = squeeze_approach(
        SqueezeParams(
            load=W, radius=R, viscosity=5.0, gap=0.6 * d_eq, duration=2e-3, contact_gap=1.1 * d_eq
        ),
        c,
        n_out=2001,
    )
    law = ConstantFriction(0.4, 0.3)
    kd, V = 1e5, 0.05
    p = StickSlipParams(
        mass=0.1, drive_stiffness=kd, drive_velocity=V, normal_force=W, duration=2e-3
    )
    dry = stick_slip(p, law)
    wet = stick_slip(p, law, method="rk45", normal_load=(sq.t, sq.contact_force))
    t_dry, t_wet = dry.events[0]["t"], wet.events[0]["t"]
    # first slip where k V t = mu_s N_c(t): an independent root of the same (interpolated) load
    t_ref = brentq(
        lambda t: kd * V * t - 0.4 * np.interp(t, sq.t, sq.contact_force), 1e-9, 2e-3, xtol=1e-15
    )
    assert t_wet == pytest.approx(t_ref, rel=1e-9)
    assert t_dry == pytest.approx(0.4 * W / (kd * V), rel=1e-12)
    # the film still carries a sizeable share of the load at the slip (else this test shows nothing)
    assert wet.events[0]["normal_N"] < 0.9 * W and t_wet < 0.9 * t_dry


def test_scene_adapter_and_cli(capsys):
    from tests.conftest import assert_one_line_error
    from tests.macro.helpers import run_main
    from tribolmp.models import macro
    from tribolmp.scene import default_scene, load_scene
    from tribolmp.scene.schema import __file__ as _schema

    path = __import__("pathlib").Path(_schema).parents[1] / "data" / "scenes" / "lubricated.toml"
    scene = load_scene(path)
    d = macro.contact_from_scene(scene).indentation(scene.load.normal_force)
    res = macro.stick_slip_from_scene(
        scene, contact_gap=scene.lubricant.film_thickness + 0.5 * d, duration=5e-3
    )
    # the solid contact ends up with the whole load once the film has drained to h_c - d_eq
    assert res.squeeze.contact_force[-1] == pytest.approx(scene.load.normal_force, rel=1e-6)
    assert res.squeeze.gap[-1] == pytest.approx(scene.lubricant.film_thickness - 0.5 * d, rel=1e-6)
    assert (
        res.events[0]["normal_N"] < scene.load.normal_force
    )  # slipped while the film still carried load
    out = run_main(capsys, "macro", "squeeze", path, "--duration", "1e-3", "--mass", "0", "--json")
    assert out.returncode == 0, out.stderr
    j = json.loads(out.stdout)
    alpha = 6 * math.pi * scene.lubricant.viscosity * scene.geometry.radius**2
    # no contact: the exponential thinning h0 exp(-W t/alpha) (integrated to rtol 1e-9)
    assert j["final_gap_m"] == pytest.approx(
        scene.lubricant.film_thickness * math.exp(-scene.load.normal_force * 1e-3 / alpha), rel=1e-7
    )
    assert default_scene().lubricant is None  # the embedded scene is dry
    assert_one_line_error(run_main(capsys, "macro", "squeeze", "--json"), "[lubricant]")
    assert_one_line_error(run_main(capsys, "macro", "squeeze", path, "--gap", "-1"), "gap")


def test_film_thinning_past_float_underflow_stays_exact_and_flagged():
    """Regression: ln(h/h0) far below -745 must not evaluate the damper at h = 0.

    There h underflows to 0.0.

    The log gap stays exact (s = -W t / alpha, alpha = 6 pi eta R^2), the film still carries the
    whole load, and the result says the film is still thinning (status 1) instead of raising.
    """
    import math

    from tribolmp.models.macro.normal import SqueezeParams, squeeze_approach

    R, eta, h0, W, T = 5e-3, 0.1, 1e-6, 10.0, 1e-2
    res = squeeze_approach(SqueezeParams(radius=R, viscosity=eta, gap=h0, load=W, duration=T))
    alpha = 6 * math.pi * eta * R**2
    assert res.log_gap[-1] < -745  # the float gap has underflowed
    # Radau in ln h is exact for this linear s(t) up to its tolerance (rtol ~1e-9 of |s|)
    assert abs(res.log_gap[-1] / (-W * T / alpha) - 1.0) < 1e-6
    assert abs(res.film_force[-1] / W - 1.0) < 1e-9
    assert res.gap[-1] >= 0.0 and res.status == 1 and "still thinning" in res.message
