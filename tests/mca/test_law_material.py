"""MCA law (pair_style mca) material tests: elasticity, yield, hardening, rupture, pressure.

Every test runs the compiled plugin in LAMMPS on an affinely loaded periodic
lattice block (tribolmp.lammps.material_test) and compares with exact
elasticity or with the independent uniform von Mises reference
``j2_reference`` (numpy).  The block is uniform, so the only differences
left are the pressure controller's lag (~0.2 % on moduli, a few MPa on
stresses) and finite-strain geometry at several % strain (<= 2 %).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from tribolmp.lammps.law_mca import McaLaw
from tribolmp.lammps.material_test import j2_reference, offset_yield, run_material_test

pytestmark = pytest.mark.lammps

E = 206e9


def _ref(p: McaLaw, test, dim, strain, pressure=0.0):
    return j2_reference(
        test,
        dim,
        youngs_modulus=p.youngs_modulus,
        poisson_ratio=p.poisson_ratio,
        yield_strength=p.yield_strength,
        ultimate_strength=p.ultimate_strength,
        hardening_modulus=p.hardening_modulus,
        pressure=pressure,
        strain=strain,
    )


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("nu,mode", [(0.3, "tension"), (0.2, "tension"), (0.3, "compression")])
def test_youngs_modulus_and_poisson_ratio_are_independent(lammps_available, dim, nu, mode):
    p = McaLaw(poisson_ratio=nu, dim=dim)
    # elastic part only (0.85 x the yield strain): fast
    r = run_material_test("mca", "uniaxial", dim, params=p, mode=mode,
                          strain=0.85 * p.yield_strength / p.youngs_modulus)
    # issue 13 tolerances: E within 2 %, nu within 0.02.  Measured: |dE| ~0.2 % (the lateral
    # pressure controller lags by ptau * rate), |dnu| < 1e-3; a central-spring lattice gives
    # nu = 1/3 (2D) / 1/4 (3D) whatever nu is asked, which fails the nu = 0.2 case.
    assert r["youngs_modulus_Pa"] == pytest.approx(E, rel=0.02)
    assert r["poisson_ratio"] == pytest.approx(nu, abs=0.02)
    assert r["links_broken"] == 0


def test_automaton_stress_equals_the_virial_stress(lammps_available):
    """Love-Weber stress of each automaton (fix mca/state) = the block's virial stress."""
    r = run_material_test("mca", "uniaxial", 3, strain=0.8 * 480e6 / E)
    s, sa = r["stress_Pa"], r["stress_automaton_Pa"]
    k = s > 100e6
    # identical up to the geometric difference r/2 vs r_i in the branch vector (0.1 % at 0.2 %)
    assert np.allclose(sa[k], s[k], rtol=2e-3)


@pytest.mark.slow
@pytest.mark.parametrize("dim", [2, 3])
def test_yield_hardening_and_tension_rupture_at_the_ultimate(lammps_available, dim):
    p = McaLaw(dim=dim)
    r = run_material_test("mca", "uniaxial", dim, params=p)
    e, s = r["strain"], r["stress_Pa"]
    # reference: the same von Mises solid along the same path (plane strain in 2D)
    k = (e > 0) & (np.arange(len(e)) < np.argmax(s))
    ref = _ref(p, "uniaxial", dim, e[k][::10])
    rs = ref["stress"][:, 0, 0]
    ky = offset_yield(e[k][::10], rs, r["axial_modulus_Pa"])
    # yield: von Mises stress at the offset within 5 % of the reference's (measured +0.1 %)
    seq_ref = float(np.sqrt(1.5 * np.sum((ref["stress"][ky] - np.trace(ref["stress"][ky]) / 3
                                          * np.eye(3)) ** 2)))
    assert r["yield_strength_Pa"] == pytest.approx(seq_ref, rel=0.05)
    assert r["yield_strength_Pa"] == pytest.approx(p.yield_strength, rel=0.05)
    # hardening curve: every point past yield within 5 % of the reference (measured <= 2 %:
    # finite-strain geometry of the stretched lattice at several % strain)
    plastic = ref["ep"] > 1e-4
    assert plastic.sum() > 3
    assert np.allclose(s[k][::10][plastic], rs[plastic], rtol=0.05)
    # rupture: the axial stress peaks at sigma_0 (within 5 %; measured +0.2 % 2D, +2 % 3D) and
    # the links along the axis break there
    assert r["ultimate_strength_Pa"] == pytest.approx(p.ultimate_strength, rel=0.05)
    assert r["links_broken"] > 0
    assert s[-1] < 0.1 * r["ultimate_strength_Pa"]


@pytest.mark.parametrize("dim", [2, 3])
def test_no_rupture_in_isotropic_compression_to_2_GPa(lammps_available, dim):
    r = run_material_test("mca", "hydro", dim, mode="compression")
    assert r["max_mean_compression_Pa"] >= 2e9
    assert r["links_broken"] == 0
    assert r["links_final"] == r["links_initial"]


@pytest.mark.slow
@pytest.mark.parametrize("dim", [2, 3])
def test_no_rupture_in_uniaxial_compression_through_yield(lammps_available, dim):
    r = run_material_test("mca", "uniaxial", dim, mode="compression")
    # 10x the yield strain: the block flows at its yield stress, no link breaks (a link
    # needs tension, or pure shear at sigma_0/sqrt(3), to break)
    assert r["strain"][-1] > 9 * 480e6 / E
    assert np.max(r["sigma_eq_Pa"]) > 480e6
    assert r["links_broken"] == 0


def _shear_yield_reference(p: McaLaw, dim, pressure, modulus):
    g = np.linspace(1e-5, 6 * math.sqrt(3) * p.yield_strength / p.youngs_modulus, 400)
    ref = _ref(p, "shear", dim, g, pressure=pressure)
    t = ref["stress"][:, 0, 1]
    return float(t[offset_yield(g, t, modulus)])


@pytest.mark.parametrize(
    "dim,pressure",
    [(2, 0.0), (2, 150e6), (2, 382e6),
     pytest.param(3, 0.0, marks=pytest.mark.slow), pytest.param(3, 150e6, marks=pytest.mark.slow),
     pytest.param(3, 382e6, marks=pytest.mark.slow)],
)
def test_shear_yield_does_not_depend_on_pressure(lammps_available, dim, pressure):
    p = McaLaw(dim=dim)
    r = run_material_test("mca", "shear", dim, pressure=pressure, params=p)
    k = p.yield_strength / math.sqrt(3.0)
    if dim == 3:
        # von Mises: tau_y = sigma_y / sqrt(3) at every pressure (within 5 %; measured < 0.3 %)
        assert r["shear_yield_stress_Pa"] == pytest.approx(k, rel=0.05)
    else:
        # plane strain: sigma_zz = 2 nu (-P) until flow relaxes it, so the onset is the
        # plane-strain value sqrt(sigma_y^2 - ((1 - 2 nu) P)^2) / sqrt(3), from the reference
        # (within 5 %; measured < 0.3 %); it stays within 5 % of sigma_y / sqrt(3) up to 382 MPa
        ref = _shear_yield_reference(p, 2, pressure, r["shear_modulus_Pa"])
        assert r["shear_yield_stress_Pa"] == pytest.approx(ref, rel=0.05)
        assert r["shear_yield_stress_Pa"] == pytest.approx(k, rel=0.05)
    assert r["shear_modulus_Pa"] == pytest.approx(p.shear_modulus, rel=0.02)


def test_contrast_bpm_spring_plastic_yield_depends_on_pressure(lammps_available):
    """Documented contrast (issue 13): the per-link plastic spring yields at ~0.6 P."""
    t0 = run_material_test("bpm/spring/plastic", "shear", 2, pressure=0.0)["shear_yield_stress_Pa"]
    t382 = run_material_test("bpm/spring/plastic", "shear", 2, pressure=382e6)[
        "shear_yield_stress_Pa"
    ]
    # measured 446 -> 227 MPa (0.59 P): a change of ~50 %, far outside the 5 % band that the
    # mca law meets; the test fails if the bpm law became pressure-insensitive
    assert abs(t382 / t0 - 1.0) > 0.2
    assert t382 == pytest.approx(0.6 * 382e6, rel=0.1)
