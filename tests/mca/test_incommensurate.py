"""Incommensurate bodies (issue 13 item 4): mu(t) has no spectral line at V/d.

With both bodies on one lattice in one orientation (``body_texture="aligned"``, the old setup)
and the brittle bpm law, every asperity slides over the same rows in phase, and mu(t) is a
washboard at the frequency V/d (band/flank power ratio 19-100 at the default scene's size).
With polycrystalline bodies (grains of randomly oriented lattices in both bodies, drawn from
the run's Generator) each contact sees its own row period and the line disappears.  The
default (the mca law, the upper body turned by 90 degrees) has no line either, in the mean
periodogram of three seeds (docs/mca.md gives every texture's measured ratios: with the mca law
the interface disorders within about a nanosecond, and even aligned lattices lose the line).
"""

from __future__ import annotations

import numpy as np
import pytest

from tribolmp.lammps.mca import params_from_scene, run_mca
from tribolmp.scene import default_scene

pytestmark = [pytest.mark.lammps, pytest.mark.slow]


def _mu_periodogram(out, *, t0: float, velocity: float, d: float):
    """(frequency / (V/d), Hann-windowed periodogram) of the detrended mu(t) after ``t0``."""
    fr = np.loadtxt(out / "friction.csv", delimiter=",", skiprows=1)
    t, f, n = fr[:, 0], fr[:, 1], fr[:, 2]
    sel = t > t0  # after the first contact transient
    mu = f[sel] / n[sel].mean()
    mu = mu - np.polyval(np.polyfit(t[sel], mu, 1), t[sel])
    ps = np.abs(np.fft.rfft(mu * np.hanning(len(mu)))) ** 2
    return np.fft.rfftfreq(len(mu), t[1] - t[0]) / (velocity / d), ps


def _band_ratio(r, ps) -> float:
    band = (r >= 0.85) & (r <= 1.15)
    flank = ((r >= 0.55) & (r < 0.8)) | ((r > 1.2) & (r <= 1.45))
    return float(ps[band].mean() / ps[flank].mean())


def washboard_ratio(out, *, t0: float, velocity: float, d: float) -> float:
    """Mean periodogram of mu(t) within 15 % of V/d over its flanks (0.55-0.8, 1.2-1.45 V/d).

    About 1 for a spectrum without a line at V/d (a red spectrum gives somewhat less); a
    washboard puts most of the variance of mu(t) into the band.
    """
    return _band_ratio(*_mu_periodogram(out, t0=t0, velocity=velocity, d=d))


@pytest.mark.parametrize("texture", ["polycrystalline", "aligned"])
def test_no_washboard_line_at_v_over_d(texture, tmp_path, monkeypatch, lammps_available):
    from tribolmp.lammps.mca import driver

    monkeypatch.setattr(driver, "compute_rates", lambda out: None)
    # the default scene's nanoscale size (100 nm box, 25 nm bodies, ~900-1100 automata), 5 ns:
    # 4 ns of sliding after the first nanosecond give 0.25 GHz bins around V/d = 2 GHz
    # measured (and thresholded) with the bpm law; with the mca law "aligned" gives 9.3 (seed 7)
    params = params_from_scene(default_scene()).replace(duration=5e-9, body_texture=texture,
                                                         bond_style="bpm/spring/plastic")
    run_mca(params, tmp_path, seed=7)
    ratio = washboard_ratio(
        tmp_path, t0=1e-9, velocity=params.sliding_velocity, d=params.automaton_diameter
    )
    if texture == "polycrystalline":
        # without a line the ratio is ~1 up to periodogram scatter: measured 0.49, 0.68 and 1.41 for
        # seeds 7, 5 and 3; 3 leaves a margin above that and is 6-30x below the washboard's 19-100
        assert ratio < 3.0, ratio
    else:
        # the documented contrast, i.e. the old single-orientation setup the first case fails on:
        # measured 100 (seed 7) and 19 (seed 3)
        assert ratio > 10.0, ratio


@pytest.mark.parametrize("texture", ["rotated", "aligned"])
def test_3d_rotated_bodies_remove_the_washboard_line(texture, tmp_path, monkeypatch,
                                                     lammps_available):
    """3D: aligned bodies have a line at sqrt(2) V/d, the rotated texture has none.

    The FCC (010) surface repeats along x after a/2 = d/sqrt(2) (the z-average of the
    face-centred square net), so aligned bodies slide over a washboard at sqrt(2) V/d.  The
    ``rotated`` texture (cube axes turned by -+18.43 deg, meeting 36.87 deg apart): the two
    surface nets share no reciprocal vector along x below sqrt(5) 2 pi/d, and the line goes.
    """
    from tribolmp.lammps.mca import driver, preset_params

    monkeypatch.setattr(driver, "compute_rates", lambda out: None)
    # smoke box in 3D (45-50 nm x 11 nm, ~1700 automata), 5 ns: 4 ns after the first contact
    # give bins of 0.125 V/d; the brittle bpm law keeps its surfaces crystalline (the contrast
    # the mca law lacks: it disorders the interface, docs/mca.md)
    params = preset_params("smoke", dim=3, duration=5e-9, body_texture=texture,
                           bond_style="bpm/spring/plastic")
    run_mca(params, tmp_path, seed=7)
    ratio = washboard_ratio(tmp_path, t0=1e-9, velocity=params.sliding_velocity,
                            d=params.automaton_diameter / np.sqrt(2.0))
    if texture == "rotated":
        # measured 0.76 (seed 7); the 2D threshold, 3, is 28x below the aligned line
        assert ratio < 3.0, ratio
    else:
        # measured 21.3 (seed 7): the washboard of one orientation
        assert ratio > 10.0, ratio


def test_default_bodies_and_law_have_no_washboard_line(tmp_path, monkeypatch, lammps_available):
    """The default setup (mca law, auto texture), periodograms of three seeds pooled.

    One 5 ns periodogram has 2-3 bins in the band, so a single seed scatters widely (measured
    single-seed ratios 0.4-4.9, docs/mca.md); the mean periodogram of three seeds is the
    estimate, and it is compared with the same threshold as above.
    """
    from tribolmp.lammps.mca import driver

    monkeypatch.setattr(driver, "compute_rates", lambda out: None)
    params = params_from_scene(default_scene()).replace(duration=5e-9)
    assert params.bond_style == "mca" and params.body_texture == "auto"
    spectra = []
    for seed in (7, 3, 5):
        out = tmp_path / f"s{seed}"
        run_mca(params, out, seed=seed)
        spectra.append(_mu_periodogram(out, t0=1e-9, velocity=params.sliding_velocity,
                                       d=params.automaton_diameter))
    n = min(len(ps) for _, ps in spectra)
    ratio = _band_ratio(spectra[0][0][:n], np.mean([ps[:n] for _, ps in spectra], axis=0))
    # measured 0.85 (rotated, the 2D default); the bpm law's aligned lattice gives 19-100
    # (the contrast test above), so < 2 separates "no line" from a washboard by 10x
    assert ratio < 2.0, ratio
