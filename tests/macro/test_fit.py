"""Inverse problem: fitted lengths, honest uncertainty, model choice, CSV errors."""

import numpy as np
import pytest

from tests.conftest import assert_one_line_error
from tests.macro.helpers import run_main
from tribolmp.errors import DataFileError
from tribolmp.models.tribospectroscopy import models as M
from tribolmp.models.tribospectroscopy.fit import (
    MeasuredCurve,
    fit_length,
    read_curve_csv,
    write_curve_csv,
)

LAM = 50e-9
A = np.linspace(0.0, 0.5e-6, 26)


def _pot(a, lam=LAM, f0=1.0, b=0.1):
    return M.pinning_force_sq(a, lam, f0, b)


@pytest.mark.parametrize("quantity", ["force_sq", "force"])
def test_exact_data_recovers_length_both_models(quantity):
    # the background is a constant in the fitted space (F^2 or F)
    y = _pot(A) if quantity == "force_sq" else np.sqrt(_pot(A, b=0.0)) + 0.1
    r = fit_length(MeasuredCurve(A, y, quantity), "potential", n_boot=0)
    # noise-free data: only the table interpolation (1e-9) and the optimiser
    # tolerance (xatol 1e-10 in ln L) limit the recovery
    assert r.length_m == pytest.approx(LAM, rel=1e-6)
    assert r.length_std_m < 1e-4 * LAM
    L = 2.2e-7
    f = M.shakedown_force(A, 1.5, 1.5 / L) + 0.2
    r = fit_length(MeasuredCurve(A, f, "force"), "stiffness", n_boot=0)
    assert r.length_m == pytest.approx(L, rel=1e-6)
    assert r.force0_N == pytest.approx(3.0, rel=1e-6)
    assert r.background == pytest.approx(0.2, rel=1e-6)


def test_auto_picks_the_generating_model(rng):
    y = _pot(A) * (1 + 0.01 * rng.standard_normal(A.size))
    r = fit_length(MeasuredCurve(A, y, "force_sq"), "auto", rng=rng)
    assert r.model == "potential"
    assert r.candidates["stiffness"]["aic"] - r.candidates["potential"]["aic"] > 10
    f = M.shakedown_force(A, 1.5, 1.5 / 2e-7) * (1 + 0.01 * rng.standard_normal(A.size)) + 0.01
    r = fit_length(MeasuredCurve(A, f, "force"), "auto", rng=rng)
    assert r.model == "stiffness"
    assert r.length_m == pytest.approx(2e-7, rel=0.05)


def test_probe_convention_halves_the_length(tmp_path):
    path = write_curve_csv(tmp_path / "d.csv", A, np.sqrt(_pot(A)))
    per = fit_length(read_curve_csv(path, "per-contact"), "potential", n_boot=0)
    probe = fit_length(read_curve_csv(path, "probe"), "potential", n_boot=0)
    # the file holds F^2 too, so it is fitted in F^2 space in both cases
    assert per.fitted_quantity == "force_sq_N2"
    assert probe.length_m == pytest.approx(per.length_m / 2, rel=1e-6)


def test_noisy_fit_intervals_cover_the_truth(rng):
    # Additive noise of 3 % of F^2(0): a calibrated 68 % interval must contain
    # the true lambda in ~68 % of realisations.  With 40 draws the binomial
    # standard error is 7 %, so [0.45, 0.9] fails only for a miscalibrated interval.
    hits = 0
    n = 40
    for _ in range(n):
        y = _pot(A) + 0.03 * rng.standard_normal(A.size)
        r = fit_length(MeasuredCurve(A, y, "force_sq"), "potential", n_boot=10, rng=rng)
        lo, hi = r.length_interval_m
        hits += lo <= LAM <= hi
    assert 0.45 <= hits / n <= 0.9


def test_relative_noise_needs_relative_weighting(rng):
    hits = 0
    n = 30
    for _ in range(n):
        y = _pot(A) * (1 + 0.1 * rng.standard_normal(A.size))
        r = fit_length(
            MeasuredCurve(A, y, "force_sq"), "potential", weighting="relative", n_boot=10, rng=rng
        )
        lo, hi = r.length_interval_m
        hits += lo <= LAM <= hi
    assert 0.45 <= hits / n <= 0.95


def test_short_data_give_unbounded_uncertainty(rng):
    a = np.array([0.0, 1e-7, 4e-7])
    r = fit_length(MeasuredCurve(a, _pot(a), "force_sq"), "potential", rng=rng)
    # 3 points, 3 parameters: no residual degrees of freedom, the length is not identifiable
    assert not r.bounded
    assert r.status == 1
    assert r.length_std_m > 10 * a.max()


def test_very_noisy_data_give_wide_uncertainty(rng):
    y = _pot(A) + 0.5 * rng.standard_normal(A.size)  # noise of half the signal
    r = fit_length(MeasuredCurve(A, y, "force_sq"), "potential", rng=rng)
    lo, hi = r.length_interval_m
    assert hi / lo > 3 or not r.bounded
    assert lo <= LAM <= hi


def test_csv_reader_errors(tmp_path):
    cases = {
        "missing.csv": ("amplitude_m,foo\n0,1\n", "force_N or force_sq_N2"),
        "noamp.csv": ("a,force_N\n0,1\n", "amplitude_m"),
        "text.csv": ("amplitude_m,force_N\n0,1\n1e-7,abc\n2e-7,1\n", "line 3"),
        "neg.csv": ("amplitude_m,force_N\n0,1\n-1e-7,1\n2e-7,1\n", ">= 0"),
        "nan.csv": ("amplitude_m,force_N\n0,1\n1e-7,nan\n2e-7,1\n", "finite"),
        "short.csv": ("amplitude_m,force_N\n0,1\n", "at least 3"),
        "empty.csv": ("", "header"),
    }
    for name, (text, frag) in cases.items():
        p = tmp_path / name
        p.write_text(text)
        with pytest.raises(DataFileError, match=frag.replace("(", r"\(")):
            read_curve_csv(p)


def test_cli_fit_json_and_bad_csvs(cli, capsys, tmp_path):
    path = write_curve_csv(tmp_path / "d.csv", A, np.sqrt(_pot(A)))
    res = cli("tribospec", "fit", path, "--model", "auto", "--convention", "per-contact", "--json",
              "--plot", tmp_path / "fit.png")
    assert res.returncode == 0, res.stderr
    out = res.json()
    for key in ("length_m", "length_std_m", "model", "residual"):
        assert key in out
    assert out["model"] == "potential"
    assert out["length_m"] == pytest.approx(LAM, rel=1e-5)
    assert (tmp_path / "fit.png").stat().st_size > 1000
    bad = tmp_path / "bad.csv"
    bad.write_text("amplitude_m,force_N\n0,1\n-2e-7,0.5\n3e-7,0.2\n")
    assert_one_line_error(cli("tribospec", "fit", bad, "--json"), "amplitude_m", ">= 0", code=2)
    # the other bad files through the same main() in-process (saves interpreter start-ups)
    bad.write_text("amplitude_m,force_N\n0,1\n1e-7,x\n3e-7,0.2\n")
    assert_one_line_error(run_main(capsys, "tribospec", "fit", bad), "line 3", "force_N", code=2)
    bad.write_text("amp,force_N\n0,1\n")
    assert_one_line_error(run_main(capsys, "tribospec", "fit", bad), "amplitude_m", code=2)
    assert_one_line_error(
        run_main(capsys, "tribospec", "fit", tmp_path / "nope.csv"), "nope.csv", code=2
    )
    assert_one_line_error(
        run_main(capsys, "tribospec", "fit", bad, "--model", "best"), "model", code=2
    )


def test_noise_around_zero_is_accepted_and_fitted(cli, tmp_path, rng):
    # stiffness data F(a) with additive noise: beyond L the measured force scatters below zero
    a = np.linspace(0.0, 4e-7, 26)
    f = M.shakedown_force(a, 1.5, 1.5 / 2e-7) + 0.05 * rng.standard_normal(a.size)
    assert (f < 0).any()
    path = tmp_path / "neg.csv"
    path.write_text(
        "amplitude_m,force_N\n" + "".join(f"{float(x)!r},{float(y)!r}\n" for x, y in zip(a, f))
    )
    curve = read_curve_csv(path)  # the old reader refused this: force_N: expected a value >= 0
    assert curve.value.min() < 0
    res = cli("tribospec", "fit", path, "--json", "--no-plot", "--noise", "additive")
    assert res.returncode == 0, res.stderr
    out = res.json()
    assert (
        out["model"] == "stiffness"
        and out["noise_model"] == "additive"
        and out["coverage_tested"] is True
    )
    lo, hi = out["length_interval_m"]
    lo95, hi95 = out["length_interval_95_m"]
    assert lo95 <= lo <= out["length_m"] <= hi <= hi95
    # F^2 column with noise around zero (a pinning curve's tail) is accepted too
    y = _pot(A, b=0.0) + 0.03 * rng.standard_normal(A.size)
    path2 = tmp_path / "neg2.csv"
    path2.write_text(
        "amplitude_m,force_sq_N2\n" + "".join(f"{float(x)!r},{float(v)!r}\n" for x, v in zip(A, y))
    )
    r = fit_length(read_curve_csv(path2), "auto")
    assert r.model == "potential" and r.fitted_quantity == "force_sq_N2"
