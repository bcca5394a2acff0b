"""Calibration of the tribospectroscopy intervals: coverage over many synthetic noisy data sets.

For each noise model (additive 3 % of the zero-amplitude value, or 10 %
proportional) and each generating model (pinning potential in F^2, contact
stiffness in F, background 0 so the data scatter around zero where the
friction has vanished; amplitudes 0-10 lambda for the pinning curve, 0-2 L
for the stiffness curve, which is zero beyond L) we draw independent data sets, fit with
``model="auto"`` and count how often the 68 % and 95 % intervals contain the
true length and how often the generating model is chosen.
"""

from __future__ import annotations

import zlib

import numpy as np
import pytest

from tribolmp.models.tribospectroscopy import models as M
from tribolmp.models.tribospectroscopy.fit import MeasuredCurve, fit_length

LAM, L_STIFF = 50e-9, 2e-7


def _design(n_points, span):
    return np.linspace(0.0, span, n_points)


def _data(kind, noise, n_points, rng):
    if kind == "potential":
        a = _design(n_points, 10 * LAM)  # the slow 1/a tail needs ~10 lengths
        f = M.pinning_force_sq(a, LAM, 1.0, 0.0)  # F^2, F(0) = 1 N
        quantity, true = "force_sq", LAM
    else:
        a = _design(n_points, 2 * L_STIFF)  # F = 0 beyond L: half the points see the slope
        f = M.shakedown_force(a, 1.5, 1.5 / L_STIFF)  # F, 3 N at a = 0, 0 beyond L
        quantity, true = "force", L_STIFF
    if noise == "additive":
        y = f + 0.03 * f[0] * rng.standard_normal(a.size)
    else:
        y = f * (1.0 + 0.10 * rng.standard_normal(a.size))
    return MeasuredCurve(a, y, quantity), true


def coverage(kind, noise, n_sets, n_points, seed):
    """(fraction covered by the 68 % interval, by the 95 % interval, model right) over n_sets."""
    rng = np.random.default_rng(seed)
    c68 = c95 = right = 0
    for _ in range(n_sets):
        curve, true = _data(kind, noise, n_points, rng)
        r = fit_length(curve, "auto", noise=noise)
        right += r.model == kind
        lo, hi = r.length_interval_m
        c68 += lo <= true <= hi
        lo, hi = r.length_interval_95_m
        c95 += lo <= true <= hi
    return c68 / n_sets, c95 / n_sets, right / n_sets


# The stiffness curve under proportional noise needs the bootstrap-calibrated threshold
# (interval="auto" picks it): with the F-form profile threshold it covers only 51 % / 82 %
# (measured, 200 sets), because its kink sits where the noise vanishes.  It costs ~0.3 s per
# fit, so it runs in the slow test only.
CASES = [("potential", "additive"), ("stiffness", "additive"), ("potential", "proportional")]
ALL_CASES = CASES + [("stiffness", "proportional")]


def test_interval_method_and_coverage_flag():
    curve, _ = _data("stiffness", "proportional", 26, np.random.default_rng(7))
    r = fit_length(curve, "stiffness", noise="proportional")
    assert "calibrated" in r.interval_method and r.coverage_tested is True
    r = fit_length(curve, "stiffness", noise="proportional", interval="profile")
    assert (
        "F threshold" in r.interval_method and r.coverage_tested is False
    )  # the undercovering form
    curve, _ = _data("stiffness", "additive", 26, np.random.default_rng(7))
    r = fit_length(curve, "auto", noise="additive")
    assert r.coverage_tested is True and r.noise_model == "additive"
    assert (
        fit_length(curve, "auto", n_boot=5).coverage_tested is False
    )  # bootstrap hull: not the tested method


@pytest.mark.parametrize("kind, noise", CASES)
def test_interval_coverage_quick(kind, noise):
    # 60 sets of 20 points: binomial standard errors 6.0 % (68 %) and 2.8 % (95 %); the
    # bands below are ~2.5 of those around the nominal levels (the 200-set slow run
    # holds the bands 60-76 % and 91-98 %)
    # zlib.crc32, not hash(): str hashes are salted per interpreter (PYTHONHASHSEED), which made
    # this draw, and so the test's outcome, change from run to run
    c68, c95, right = coverage(kind, noise, 60, 20, seed=zlib.crc32(f"{kind}-{noise}".encode()))
    assert 0.53 <= c68 <= 0.83, c68
    assert 0.88 <= c95 <= 1.0, c95
    assert right >= 0.95, right


@pytest.mark.slow
@pytest.mark.parametrize("n_points", [20, 26])
@pytest.mark.parametrize("kind, noise", ALL_CASES)
def test_interval_coverage_200_sets(kind, noise, n_points):
    c68, c95, right = coverage(kind, noise, 200, n_points, seed=1000 + n_points)
    assert 0.60 <= c68 <= 0.76, c68  # the band (binomial sd at 200 sets: 3.3 %)
    assert 0.91 <= c95 <= 0.98, c95  # (binomial sd 1.5 %)
    assert right >= 0.95, right
