"""One function decides the friction coefficient for every consumer of a scene (issue 11)."""

from __future__ import annotations

import dataclasses

import numpy as np

from tribolmp.models.friction import friction_coefficient
from tribolmp.records import Rates
from tribolmp.scene import load_scene, scene_path


def test_precedence_nanoscale_then_rates_then_load():
    given = load_scene(scene_path("rates_given"))  # [rates].mu = 0.16, [load] default 0.3
    dry = dataclasses.replace(given, rates=None)
    measured = Rates(mu=0.21, mu_static=0.25, source="nanoscale stage k (rates.json)")
    c = friction_coefficient(given, measured)
    assert (c.mu, c.mu_static, c.mu_kinetic, c.source) == (
        0.21,
        0.25,
        0.21,
        "nanoscale stage k (rates.json)",
    )
    c = friction_coefficient(given)
    assert (c.mu, c.source) == (0.16, "[rates].mu")
    c = friction_coefficient(dry)
    assert (c.mu, c.source) == (dry.load.friction_coefficient, "[load].friction_coefficient")
    # a nanoscale record without a measured mu falls through to the scene
    assert friction_coefficient(given, Rates(dz=1e-30)).mu == 0.16


def test_every_consumer_uses_the_decision():
    # contact_from_scene used [load].friction_coefficient even when [rates].mu was given; the rigid
    # body and the tribospectroscopy probe used [rates].mu: the consumers disagreed on one scene.
    from tribolmp.models.macro import contact_from_scene
    from tribolmp.models.tribospectroscopy import params_from_scene as tribo_params

    scene = load_scene(scene_path("rates_given"))
    mu = friction_coefficient(scene).mu
    assert mu != scene.load.friction_coefficient  # the scene makes the disagreement visible
    assert contact_from_scene(scene, rng=np.random.default_rng(1)).mu == mu
    assert tribo_params(scene).mu == mu


def test_velocity_weakening_default_ratio_lives_in_the_model():
    from tribolmp.models.macro.friction import DYNAMIC_TO_STATIC, VelocityWeakening

    law = VelocityWeakening(mu_s=0.4, mu_k=None, v_c=1e-3)
    assert law.mu_k == DYNAMIC_TO_STATIC * 0.4
    assert VelocityWeakening(mu_s=0.4, mu_k=0.1).mu_k == 0.1
