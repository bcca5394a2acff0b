"""The Eq. 23 fit (tribolmp.analysis.eq23) on synthetic h(x, t) with known coefficients.

The synthetic profiles come from the project's exact Ornstein-Uhlenbeck
integrator of Eq. 23 (tribolmp.models.topography, "exact" scheme: exact in
distribution for any step), sampled like an MCA run: 40 columns of 2.5 nm
(a 100 nm box), a frame every 0.05 ns, white measurement noise of 1 nm rms
per column per frame (the column-mass shot noise of an MCA profile), started
in the stationary state.
"""

from __future__ import annotations

import numpy as np
import pytest

from tribolmp.analysis.eq23 import COEFFICIENTS, fit_eq23, read_profile, write_profile
from tribolmp.errors import DataFileError
from tribolmp.models.topography.spde import TopographyParams, make_stepper

from ..conftest import assert_one_line_error

# MCA-like magnitudes: gamma(k1) = 2.4e9 1/s (0.4 ns), gamma dt = 0.6 reached at mode 5 or 6
TRUE = {"mu_per_s": 2e9, "d0_m2_s": 1e-7, "dz": 1e-16, "dx_l2": 1e-33}
NX, DX, DT, NOISE, L_STEP = 40, 2.5e-9, 5e-11, 1e-9, 2.5e-9


def synth(rng, *, replicas=1, nt=800, true=TRUE, h0="stationary", noise=NOISE):
    """Return h(x, t) of ``replicas`` independent runs of the exact OU integrator.

    Shape (replicas, nt, NX).
    """
    p = TopographyParams(
        dim=1,
        grid_points=NX,
        pixel_size=DX,
        d0=true["d0_m2_s"],
        dx_noise=true["dx_l2"] / L_STEP**2,
        dz=true["dz"],
        mu=true["mu_per_s"],
        l=L_STEP,
        dt=DT,
        steps=1,
    )
    st = make_stepper(p, rng=rng, replicas=replicas, h0=h0)
    h = np.empty((replicas, nt, NX))
    for i in range(nt):
        st.step()
        h[:, i] = st.heights()
    h += noise * rng.standard_normal(h.shape)
    return np.arange(NX) * DX, np.arange(nt) * DT, h


def test_recovers_coefficients_within_reported_errors(rng):
    x, t, h = synth(rng)
    res = fit_eq23(x, t, h[0])
    assert all(res["valid"].values()), res["reasons"]
    assert res["n_modes_used"] >= 4 and len(res["modes_used"]) == res["n_modes_used"]
    for c in COEFFICIENTS:
        # 3 reported standard errors: a fixed seed, so this either holds or the fit/errors are wrong
        assert abs(res[c] - TRUE[c]) < 3 * res[f"{c}_err"], (c, res[c], res[f"{c}_err"])
        assert res["units"][c] in ("1/s", "m^2/s", "m^3/s", "m^5/s")


def test_errors_cover_truth_at_their_stated_rate():
    # 200 independent runs, all replicas of one vectorised OU integration
    rng = np.random.default_rng(20240614)
    x, t, h = synth(rng, replicas=200)
    fits = [fit_eq23(x, t, hr) for hr in h]
    for c in COEFFICIENTS:
        ok = np.array([f["valid"][c] for f in fits])
        assert ok.mean() >= 0.95, (c, ok.mean())
        v = np.array([f[c] for f in fits if f["valid"][c]])
        e = np.array([f[f"{c}_err"] for f in fits if f["valid"][c]])
        z = np.abs(v - TRUE[c]) / e
        n = z.size
        # The errors are jackknife standard errors over 20 blocks (19 dof): nominal coverage
        # of +-1 err is P(|t_19| < 1) = 0.670 and of +-2 err P(|t_19| < 2) = 0.940.  Allowed:
        # 3 binomial standard deviations of n runs around these (0.033 and 0.017 for n = 200).
        for width, p in ((1.0, 0.670), (2.0, 0.940)):
            cov = float(np.mean(z < width))
            tol = 3 * np.sqrt(p * (1 - p) / n)
            assert abs(cov - p) < tol, (c, width, cov, p, tol)


def test_run_too_short_for_the_slow_modes_is_invalid(rng):
    # 5 ns: the slowest mode (1/gamma = 0.42 ns) spans 12 relaxation times, below the 20 required
    x, t, h = synth(rng, nt=100)
    res = fit_eq23(x, t, h[0])
    for c in ("mu_per_s", "dz"):
        assert res["valid"][c] is False
        assert res[c] is None and res[f"{c}_err"] is None
        assert "slowest mode" in res["reasons"][c]
    assert res["modes"]["used"][0] is False
    assert "relaxation times" in res["modes"]["reason"][0]


def test_non_stationary_profile_is_invalid(rng):
    # start from a roughness 20x the stationary one in every mode (as an MCA run
    # starts from its initial roughness, several times the steady one): it decays
    # over the first ~1.5 ns (slow modes) and the two halves of the run differ
    x, t, h = synth(rng, nt=400, h0=None)
    p = TopographyParams(
        dim=1,
        grid_points=NX,
        pixel_size=DX,
        d0=TRUE["d0_m2_s"],
        dx_noise=TRUE["dx_l2"] / L_STEP**2,
        dz=TRUE["dz"],
        mu=TRUE["mu_per_s"],
        l=L_STEP,
        dt=DT,
        steps=1,
    )
    st = make_stepper(p, rng=rng, replicas=1, h0="stationary")
    h0 = 20 * st.heights()[0]
    st.set_state(h0)
    hh = np.empty((400, NX))
    for i in range(400):
        st.step()
        hh[i] = st.heights()[0]
    res = fit_eq23(x, t, hh + NOISE * rng.standard_normal(hh.shape))
    assert res["stationary"] is False
    assert not any(res["valid"].values())
    assert all("not stationary" in res["reasons"][c] for c in COEFFICIENTS)
    # and the same run, analysed after the transient, is stationary
    late = fit_eq23(x, t, hh, start_s=4e-9)
    assert late["stationary"] is True


def test_profile_npz_roundtrip_and_bad_input(tmp_path, rng):
    x, t, h = synth(rng, nt=100)
    path = write_profile(tmp_path / "profile.npz", x, t, h[0])
    back = read_profile(path)
    np.testing.assert_array_equal(back["h"], h[0])
    np.testing.assert_array_equal(back["x"], x)
    with pytest.raises(DataFileError, match="h: expected shape"):
        write_profile(tmp_path / "bad.npz", x, t, h[0][:, :-1])
    with pytest.raises(DataFileError, match="t: expected uniformly spaced"):
        write_profile(tmp_path / "bad.npz", x, t[::-1], h[0])
    (tmp_path / "junk.npz").write_text("not an archive")
    with pytest.raises(DataFileError, match="expected a numpy .npz"):
        read_profile(tmp_path / "junk.npz")


def test_cli_eq23_fit(tmp_path, rng, cli):
    x, t, h = synth(rng)
    write_profile(tmp_path / "profile.npz", x, t, h[0])
    res = cli("analysis", "eq23-fit", tmp_path / "profile.npz", "--json")
    assert res.returncode == 0, res.stderr
    out = res.json()
    for c in COEFFICIENTS:
        assert c in out and f"{c}_err" in out and c in out["valid"] and c in out["units"]
    assert all(isinstance(m, int) for m in out["modes_used"]) and out["modes_used"]
    assert out["units"]["dx_l2"] == "m^5/s"
    text = cli("analysis", "eq23-fit", tmp_path / "profile.npz")
    assert text.returncode == 0 and "mu_per_s" in text.stdout
    assert_one_line_error(cli("analysis", "eq23-fit", tmp_path / "missing.npz"), "no such file")
    assert_one_line_error(
        cli("analysis", "eq23-fit", tmp_path / "profile.npz", "--min-relaxations", "-1"),
        "--min-relaxations",
    )
