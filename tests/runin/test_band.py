"""Eq. 23 coefficients measured on an MCA profile reach the part only within the measured band.

The MCA measures the relaxation of its own profile's modes, wavelengths of a few automata up to
its box (50 nm in the campaign).  A part's height map (the default scene: 4 um pixels) resolves
nothing that short.  Extrapolating the k-independent relaxation rate mu from nanometre modes to
micrometre ones wore the default scene's 0.5 um surface to Rq = 4.4 pm within the first
checkpoint interval: flatter than one lattice spacing, which no steel surface can be.
"""

from __future__ import annotations

import numpy as np
import pytest

from tribolmp.environment import data_path
from tribolmp.models import bridges, runin
from tribolmp.scene import default_scene

#: one lattice spacing of steel (m): a continuum surface of atoms has no smaller roughness
ATOMIC_SPACING = 2.5e-10


def test_band_rule():
    off = bridges.mca_band_applies(4e-6, 5e-8)
    assert not off.applies and "no common mode" in off.reason
    assert off.part_shortest_wavelength_m == 8e-6
    assert bridges.mca_band_applies(1e-9, 5e-8).applies  # a nanometre map shares the MCA's modes
    assert bridges.mca_band_applies(2.5e-8, 5e-8).applies  # the edge: 2 dx = L
    assert not bridges.mca_band_applies(1e-9, None).applies  # unknown length: not a measurement


def test_the_shipped_table_states_its_profile_length():
    length = bridges.nanoscale_table_profile_length(data_path("nanoscale_table.json"))
    # the campaign's smoke box (docs/mca_study.md); None would silently disable the table's Eq. 23
    assert length is not None and 1e-8 < length < 1e-6


def _default_part_coefficients(pixel: float):
    from tribolmp.chain.stages.topography import part_coefficients
    from tribolmp.records import Rates

    scene = default_scene()
    table_path = data_path("nanoscale_table.json")
    rows = bridges.load_nanoscale_table(table_path)
    # this run's rates as the default scene's 4 ns nanoscale stage hands them on (no valid C1)
    rates = Rates.from_mapping(
        {"mu": 0.37, "sliding_velocity_m_s": 5.0, "pressure_Pa": 150e6, "transfer_rate": 4e6,
         "automaton_diameter_m": 2.5e-9},
        source="nanoscale stage (rates.json)",
    )
    h0 = np.random.default_rng(3).normal(size=(32, 32)) * scene.roughness.rms_height
    params = runin.RunInParams(
        normal_force=scene.load.normal_force, apparent_area=1e-6, E_star=scene.effective_modulus,
        duration=scene.kinematics.duration, sliding_velocity=scene.kinematics.sliding_velocity,
        checkpoints=2, contact_method="mdr", realizations=2,
    )
    eq, friction, provenance, _ = part_coefficients(
        scene, rates, rates.source, rows, h0, pixel, params, 2.5e-9,
        run_length=scene.nanoscale.box_length,
        table_length=bridges.nanoscale_table_profile_length(table_path),
    )
    return scene, h0, eq, params, provenance(friction(0.01))


def test_a_micrometre_part_does_not_take_the_mca_relaxation_rate():
    _, _, eq, _, prov = _default_part_coefficients(4e-6)
    assert {prov[k]["tier"] for k in bridges.C1_FIELDS} == {"[topography] fallback"}
    why = prov["mu_per_s"]["not_used"]
    assert set(why) == {"measured by this run (nanoscale rates.json)", "nanoscale table"}
    assert all("no common mode" in r for r in why.values())
    assert any("not used at the part" in w for w in eq.warnings)
    # the friction coefficient is a different measurement and still comes from the MCA
    assert prov["mu_kinetic"]["tier"] != "[load].friction_coefficient"


def test_a_nanometre_part_takes_the_table():
    _, _, _, _, prov = _default_part_coefficients(1e-9)
    assert prov["mu_per_s"]["tier"] == "nanoscale table"
    assert "nanoscale table" not in prov["mu_per_s"].get("not_used", {})


@pytest.mark.parametrize("pixel", [4e-6])
def test_running_in_keeps_a_surface_rougher_than_one_lattice_spacing(pixel):
    """Physical bound: the default part's worn surface is not smoother than its lattice."""
    _, h0, eq, params, _ = _default_part_coefficients(pixel)
    res = runin.running_in(h0, pixel, eq, params, rng=np.random.default_rng(1))
    assert res.rq_initial_m == pytest.approx(np.std(h0), rel=0.05)
    # measured: Rq stays 0.5 um (the [topography] coefficients barely change it); with the
    # table's mu (no band rule) it fell to ~4 pm
    assert res.rq_final_m > ATOMIC_SPACING, res.rq_final_m
