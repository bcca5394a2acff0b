"""The contact viscosity bounds the timestep (issue 14: the viscosity calibration needs it).

The seed's viscous force between touching, unlinked automata, c = eta A / d per pair, damps
every contact mode; an explicit step is stable only for omega dt <= 2 (sqrt(1 + zeta^2) - zeta).
``MCAParams`` allows half of that limit.  Before this check a scan of the viscosity lost
automata at 0.2 Pa s (exit 3 after 0.3 ns) instead of saying which timestep it needs.
"""

from __future__ import annotations

import math

import pytest

from tribolmp.errors import ParameterError, RunError
from tribolmp.lammps.laws import get_law
from tribolmp.lammps.mapping import MaterialSpec
from tribolmp.lammps.mca import preset_params


def _limit(eta: float, dim: int = 2) -> float:
    spec = MaterialSpec(bond_style="mca", dim=dim, contact_viscosity=eta)
    return get_law("mca").map_material(spec).dt_max_factor


@pytest.mark.parametrize("dim", [2, 3])
def test_limit_without_viscosity_is_the_undamped_verlet_bound(dim):
    z = 6 if dim == 2 else 12
    # the undamped central-difference limit omega_max dt < 2 with omega_max^2 = 2 Z k / m
    assert _limit(0.0, dim) == pytest.approx(2.0 / math.sqrt(2.0 * z), rel=1e-12)


def test_limit_decreases_with_viscosity_as_the_damped_bound():
    etas = [0.0, 0.0125, 0.05, 0.1, 0.2, 1.0]
    lims = [_limit(e) for e in etas]
    assert all(a > b for a, b in zip(lims, lims[1:]))
    # heavy damping: 2 (sqrt(1 + zeta^2) - zeta) -> 1 / zeta, so the limit falls as 1/eta
    assert _limit(10.0) / _limit(20.0) == pytest.approx(2.0, rel=2e-3)


def test_a_too_large_viscosity_names_dt_factor():
    # 0.2 Pa s at the default dt_factor 0.1: the measured blow-up (docs/mca_study.md)
    with pytest.raises(ParameterError, match="dt_factor"):
        preset_params("smoke", contact_viscosity=0.2)
    # half the timestep is allowed (and ran, 20 ns at 150 MPa)
    preset_params("smoke", contact_viscosity=0.2, dt_factor=0.05)
    # the default viscosity at the default step is allowed
    preset_params("smoke")


@pytest.mark.lammps
@pytest.mark.slow
def test_the_rejected_step_is_really_unstable(tmp_path, monkeypatch, lammps_available):
    """Bypass the check (expert deck override) and watch the run lose automata.

    The smoke box at 150 MPa with eta = 0.2 Pa s: at dt_factor 0.1 (rejected) the run blows up
    within 0.3 ns (measured, seed 1); at 0.05 (allowed) the same 1 ns runs.  Which guard stops
    the blow-up depends on the round-off of the trajectory: with the plugin of 2026-12-01 LAMMPS
    lost automata at step 6960, with the batched pair loop of 2026-12-02 (same law, other
    rounding of the stress update) an automaton collects more than maxpartner linked or
    touching partners at step 6476 as the lattice collapses.  Either is the instability.
    """
    from tribolmp.lammps.mca import driver, run_mca

    monkeypatch.setattr(driver, "compute_rates", lambda out: None)
    base = dict(pressure=150e6, sliding_velocity=5.0, duration=1e-9)
    bad = preset_params("smoke", dt_factor=0.1, **base)  # validated at the default eta
    with pytest.raises(RunError, match="lost atoms|more than 12 linked or touching partners"):
        run_mca(bad, tmp_path / "bad", seed=1, overrides={"eta": "200"})
    good = preset_params("smoke", dt_factor=0.05, contact_viscosity=0.2, **base)
    res = run_mca(good, tmp_path / "good", seed=1)
    assert res.natoms > 0


def test_a_scene_sets_the_viscosity_and_the_step(tmp_path):
    """[nanoscale] contact_viscosity and dt_factor reach the run; too large a step is refused."""
    from tribolmp.lammps.mca import params_from_scene
    from tribolmp.scene import load_scene

    bad = tmp_path / "bad.toml"
    bad.write_text("[nanoscale]\ncontact_viscosity = 0.2\n")
    with pytest.raises(ParameterError, match="dt_factor"):
        params_from_scene(load_scene(bad))
    good = tmp_path / "good.toml"
    good.write_text("[nanoscale]\ncontact_viscosity = 0.2\ndt_factor = 0.05\n")
    p = params_from_scene(load_scene(good))
    assert (p.contact_viscosity, p.dt_factor) == (0.2, 0.05)
    spec = p.material()
    assert spec.contact_viscosity == 0.2
