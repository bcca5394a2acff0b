"""Scene adapters and the ``tribospec simulate`` / ``macro oscillate`` commands."""

import json

import numpy as np
import pytest

from tests.conftest import assert_one_line_error
from tests.macro.helpers import run_main
from tribolmp.models import macro
from tribolmp.models import tribospectroscopy as ts
from tribolmp.scene import default_scene


def test_params_from_scene_and_chain_entry_points():
    scene = default_scene()
    p = ts.params_from_scene(scene)
    assert p.normal_force == pytest.approx(
        scene.load.normal_force / 2
    )  # two contacts share the load
    assert p.model == scene.tribospectroscopy.model
    r = ts.tribospec_from_scene(
        scene, contact_stiffness=1e7, model="stiffness", amplitudes=[0.0, 5e-8, 1e-6]
    )
    mu_n = scene.load.friction_coefficient * p.normal_force
    assert r.force_N == pytest.approx(
        2 * mu_n * np.clip(1 - 1e7 * np.array([0, 5e-8, 1e-6]) / mu_n, 0, None), rel=1e-12
    )
    assert r.length_m == pytest.approx(mu_n / 1e7)
    sp = macro.params_from_scene(scene)
    assert sp.mass == scene.kinematics.mass
    # the default scene's profile is rough: its MDR row is drawn from an explicit Generator
    res = macro.stick_slip_from_scene(
        scene,
        contact_law="mdr",
        law=macro.ConstantFriction(0.35, 0.3),
        duration=2e-3,
        rng=np.random.default_rng(0),
    )
    assert res.events[0]["from_phase"] == "stick"


def test_mdr_stiffness_of_the_scene_contact_is_hertz():
    scene = default_scene()
    p = ts.params_from_scene(scene)
    k = p.contact().stiffness(p.normal_force)
    a = (3 * p.normal_force * p.radius / (4 * p.E_star)) ** (1 / 3)
    # MDR tangential stiffness of a sphere: 2 G* a (sub-grid edge: O(dx^2))
    assert k == pytest.approx(2 * p.G_star * a, rel=1e-4)


def test_cli_simulate_rows_and_convention(cli, capsys):
    res = cli(
        "tribospec", "simulate", "--amplitudes", "0,1e-7,2e-7", "--model", "potential", "--json"
    )
    assert res.returncode == 0, res.stderr
    out = res.json()
    assert out["convention"] == "per-contact" and "dl/4" in out["amplitude_convention"]
    rows = out["rows"]
    assert [r["amplitude_m"] for r in rows] == [0.0, 1e-7, 2e-7]
    for r in rows:
        assert r["force_sq_N2"] == pytest.approx(r["force_N"] ** 2, rel=1e-12)
    lam = default_scene().tribospectroscopy.correlation_length
    assert rows[1]["force_sq_N2"] / rows[0]["force_sq_N2"] == pytest.approx(
        float(ts.pinning_shape(1e-7 / lam)), rel=1e-8
    )
    res = run_main(
        capsys,
        "tribospec",
        "simulate",
        "--amplitudes",
        "2e-7",
        "--convention",
        "probe",
        "--model",
        "potential",
        "--json",
    )
    probe = json.loads(res.stdout)
    assert probe["rows"][0]["amplitude_per_contact_m"] == pytest.approx(1e-7)
    assert probe["rows"][0]["force_N"] == pytest.approx(rows[1]["force_N"], rel=1e-12)
    assert_one_line_error(
        run_main(capsys, "tribospec", "simulate", "--amplitudes=-1e-7"), "amplitudes", code=2
    )
    assert_one_line_error(
        run_main(capsys, "tribospec", "simulate", "--amplitudes", "1e-7", "--model", "magic"),
        "model",
        code=2,
    )


def test_cli_simulate_stiffness_and_oscillate(cli, capsys):
    res = run_main(
        capsys,
        "tribospec",
        "simulate",
        "--amplitudes",
        "0,5e-8,1e-6",
        "--model",
        "stiffness",
        "--contact-stiffness",
        "2e7",
        "--json",
    )
    assert res.returncode == 0, res.stderr
    out = json.loads(res.stdout)
    mu_n = 0.3 * 5.0
    assert [r["force_N"] for r in out["rows"]] == pytest.approx(
        [2 * mu_n, 2 * mu_n * (1 - 2e7 * 5e-8 / mu_n), 0.0]
    )
    osc = cli(
        "macro",
        "oscillate",
        "--amplitude",
        "5e-8",
        "--cycles",
        "2",
        "--steps-per-cycle",
        "100",
        "--json",
    )
    assert osc.returncode == 0, osc.stderr
    o = osc.json()
    assert o["normal_force_N"] == pytest.approx(10.0, rel=1e-8)
    assert o["dissipation_per_cycle_J"][-1] > 0


def test_rough_contact_from_the_contact_model(rng):
    # the body also runs on a rough MDR row (contact model's rough.py): load-dependent
    # stiffness, micro-slip oscillation and the averaged shakedown force
    scene = default_scene()
    assert scene.geometry.profile == "rough"
    c = macro.contact_from_scene(scene, rng=rng, n_springs=256)
    assert c.g.min() == 0.0
    N = 2.0
    d = c.indentation(N)
    assert c.normal_force(d) == pytest.approx(N, rel=1e-9)
    q, k = c.springs(N)
    assert q.sum() == pytest.approx(N, rel=1e-9)
    assert c.stiffness(N) == pytest.approx(k[q > 0].sum(), rel=1e-12)
    # micro-slip: the averaged shakedown force against brute force on the rough row
    L = c.mu * N / c.stiffness(N)
    p = macro.DriftParams(
        normal_force=N,
        amplitude=0.3 * L,
        frequency=65e3,
        sliding_velocity=0.01 * L * 65e3,
        duration=250 / 65e3,
        steps_per_cycle=16,
        slow_steps=250,
    )
    b = macro.drift_under_oscillation(p, c, scheme="brute")
    a = macro.drift_under_oscillation(p, c, scheme="averaged")
    # drift per cycle 1 % of mu N / k: averaging error of that order of 2 mu N
    assert np.max(np.abs(b.force - np.interp(b.t, a.t, a.force))) < 0.02 * 2 * c.mu * N
    res = macro.stick_slip_from_scene(
        scene,
        contact_law="mdr",
        law=macro.ConstantFriction(0.4, 0.3),
        rng=np.random.default_rng(3),
        duration=5e-3,
        unload_time=4e-3,
    )
    assert np.all(np.isfinite(res.x))


def test_rough_profile_without_rng_is_an_error_not_a_sphere():
    # the old adapter silently returned the sphere of [geometry].radius here
    from tribolmp.errors import ParameterError

    scene = default_scene()
    assert scene.geometry.profile == "rough"
    with pytest.raises(ParameterError, match="rng"):
        macro.contact_from_scene(scene)
    # the CLI draws it from [scene].seed: reproducible, and a rough row (many summits), not a sphere
    a = macro.contact_from_scene(scene, rng=np.random.default_rng(scene.scene.seed), n_springs=256)
    b = macro.contact_from_scene(scene, rng=np.random.default_rng(scene.scene.seed), n_springs=256)
    assert np.array_equal(a.g, b.g) and np.count_nonzero(np.diff(np.sign(np.diff(a.g))) > 0) > 3


def test_tribospec_on_a_rough_scene_states_the_sphere_tip(capsys):
    # the probe-tip sphere used for a rough scene's stiffness model is stated, not silent
    res = run_main(
        capsys, "tribospec", "simulate", "--model", "stiffness", "--amplitudes", "0,1e-7", "--json"
    )
    assert res.returncode == 0
    out = json.loads(res.stdout)
    assert len(out["warnings"]) == 1 and "sphere" in out["warnings"][0]
    assert res.stderr.count("\n") == 1 and "warning" in res.stderr
