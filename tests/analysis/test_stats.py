"""Statistics helpers against brute-force or exact references."""

from __future__ import annotations

import numpy as np
import pytest

from tribolmp.analysis.stats import (
    block_standard_error,
    crossing_heights,
    isotonic_fit,
    linear_fit,
    msd_fft,
    mser_truncation,
)
from tribolmp.analysis.synthetic import ar1_mean_stderr


def test_msd_fft_equals_direct_average(rng):
    x = np.cumsum(rng.standard_normal((50, 7, 2)), axis=0)
    direct = np.array(
        [np.mean(np.sum((x[lag:] - x[: x.shape[0] - lag]) ** 2, axis=2)) for lag in range(50)]
    )
    # identical algebra, only floating-point round-off differs
    np.testing.assert_allclose(msd_fft(x), direct, rtol=1e-10, atol=1e-10)


def test_isotonic_fit_properties(rng):
    y = rng.standard_normal(40) + np.linspace(0, 3, 40)
    w = rng.uniform(0.5, 2.0, 40)
    fit = isotonic_fit(y, w)
    assert np.all(np.diff(fit) >= -1e-12)
    # pooling preserves the weighted sum exactly
    assert np.isclose((fit * w).sum(), (y * w).sum())
    # already monotone input is returned unchanged
    mono = np.sort(y)
    np.testing.assert_array_equal(isotonic_fit(mono), mono)
    # brute check against the known solution of a two-point violation
    np.testing.assert_allclose(isotonic_fit([1.0, 0.0], [1.0, 3.0]), [0.25, 0.25])


def test_crossing_heights_linear_profile():
    z = np.linspace(0.0, 10.0, 11)
    f = np.clip((z - 2.0) / 5.0, 0, 1)  # ramp from z = 2 to z = 7
    lo, hi = crossing_heights(z, f, [0.1, 0.9])
    # linear interpolation is exact on a linear ramp
    assert lo == pytest.approx(2.5) and hi == pytest.approx(6.5)
    assert np.isnan(crossing_heights(z, f, [1.5])[0])


def test_mser_finds_the_end_of_a_transient(rng):
    n = 2000
    y = 0.05 * rng.standard_normal(n)
    y[:300] += 1.0  # a step transient of 300 samples
    d, steady = mser_truncation(y)
    # every batch of the step must go (a kept one would add ~20 sigma); MSER
    # may cut a few noisy batches more when that lowers the marginal
    # standard error: allow 10 batches (2.5 % of the data)
    assert 300 <= d <= 350 and steady
    # a steadily drifting series never settles: the minimum sits at the search limit
    d2, steady2 = mser_truncation(np.linspace(0, 1, n) + 0.01 * rng.standard_normal(n))
    assert not steady2


def test_block_standard_error_matches_ar1_theory():
    phi, sig, n = 0.9, 1.0, 2**14
    errs = []
    for seed in range(8):
        g = np.random.default_rng(seed)
        e = g.normal(0, sig, n)
        x = np.empty(n)
        x[0] = e[0] / np.sqrt(1 - phi**2)
        for i in range(1, n):
            x[i] = phi * x[i - 1] + e[i]
        se, converged = block_standard_error(x)
        assert converged
        errs.append(se)
    exact = ar1_mean_stderr(phi, sig, n)
    # blocking estimates scatter by ~sqrt(2/n_blocks) ~ 20 %; the mean of 8
    # by ~7 %: 25 % is > 3 sigma
    assert np.mean(errs) == pytest.approx(exact, rel=0.25)
    # the naive i.i.d. error would be 4.4x smaller: the test separates the two
    assert np.mean(errs) > 2.5 * np.sqrt(1 / (1 - phi**2) / n)


def test_linear_fit_exact_line():
    t = np.arange(10.0)
    a, b, se = linear_fit(t, 3.0 * t - 2.0)
    assert (
        a == pytest.approx(3.0) and b == pytest.approx(-2.0) and se == pytest.approx(0.0, abs=1e-12)
    )
