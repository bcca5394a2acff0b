"""FrictionCoefficient against series of known mean, error and steady start."""

from __future__ import annotations

import numpy as np
import pytest

from tribolmp.analysis.friction import FrictionCoefficient
from tribolmp.analysis.outputs import read_friction_csv
from tribolmp.analysis.synthetic import make_friction
from tribolmp.errors import DataFileError


def test_mean_error_and_steady_start(tmp_path):
    means, errs, z = [], [], []
    for seed in range(6):
        exp = make_friction(tmp_path / str(seed), np.random.default_rng(seed), n=4000, mu=0.3, phi=0.9,
                            sigma_eps=0.01, transient=0.2, tau=2e-9)
        r = FrictionCoefficient(tmp_path / str(seed)).run().results
        assert r.steady and r.status == 0
        # the transient 0.2 exp(-t/tau) must be mostly cut: what is left biases mu by < 1 standard error
        assert r.steady_start_s > 1.5e-9
        z.append((r.mu - exp["mu"]) / exp["mu_err"])
        means.append(r.mu)
        errs.append(r.mu_err / exp["mu_err"])
    # |z| < 4 for each run (Gaussian: false alarm 6e-5 per run)
    assert np.max(np.abs(z)) < 4
    # blocking error vs the exact AR(1) standard error: each within a factor 1.6, the average within 25 %
    assert 1 / 1.6 < min(errs) and max(errs) < 1.6
    assert np.mean(errs) == pytest.approx(1.0, rel=0.25)


def test_transient_is_detected_not_averaged(tmp_path, rng):
    make_friction(tmp_path, rng, n=2000, transient=1.0, tau=2e-9, phi=0.5)
    r = FrictionCoefficient(tmp_path).run().results
    fr = read_friction_csv(tmp_path)
    naive = np.mean(fr["friction_N"] / fr["normal_N"])
    # the naive mean includes the transient (about +0.1); the steady mean does not
    assert naive - 0.3 > 10 * r.mu_err
    assert abs(r.mu - 0.3) < 4 * r.mu_err


def test_drift_is_flagged(tmp_path, rng):
    make_friction(tmp_path, rng, n=4000, transient=0.0, phi=0.5, sigma_eps=0.005, drift=0.2)
    r = FrictionCoefficient(tmp_path).run().results
    assert not r.steady and r.status == 1
    assert "steady" in r.message or "differ" in r.message


def test_sign_convention_and_forced_start(tmp_path, rng):
    make_friction(tmp_path, rng, n=1000, transient=0.0)
    fr = read_friction_csv(tmp_path)
    flipped = {**fr, "friction_N": -fr["friction_N"]}
    a = FrictionCoefficient(fr, start_s=1e-9).run().results
    b = FrictionCoefficient(flipped, start_s=1e-9).run().results
    assert a.mu == pytest.approx(b.mu) and b.sign == -1.0 and a.sign == 1.0
    assert a.steady_start_s >= 1e-9


def test_no_contact_is_an_error():
    data = {"time_s": np.arange(1.0, 21.0), "friction_N": np.zeros(20), "normal_N": np.r_[np.ones(3), np.zeros(17)],
            "top_x_m": np.zeros(20)}
    with pytest.raises(DataFileError, match="normal_N"):
        FrictionCoefficient(data).run()
