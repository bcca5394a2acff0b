"""MCA law: welding of pressed automata, weld strength, repeated break / re-weld (mca_weld.in)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tribolmp.lammps.decks import deck_path
from tribolmp.lammps.law_mca import McaLaw, mca_deck_variables, pair_area
from tribolmp.units import to_lammps

pytestmark = pytest.mark.lammps


def _run(tmp_path, dim=2, ncycles=1, press=0.006, mol2=2, **law):
    from tribolmp.lammps.plugin import plugin_path
    from tribolmp.lammps.session import LammpsSession

    # no viscosity / damping: the force on the driven automaton is then the elastic pair force
    p = McaLaw(dim=dim, contact_viscosity=0.0, link_damping=0.0, **law)
    d = to_lammps(p.diameter, "length")
    v = dict(mca_deck_variables(p))
    v.update(
        plugin=plugin_path(), out=tmp_path, dim=dim, d=d, ncycles=ncycles, press=press, mol2=mol2,
        rho=to_lammps(p.mass, "mass") / (math.pi * d**3 / 6.0),
    )
    with LammpsSession(log=None, variables=v, require=()) as s:
        s.file(deck_path("mca_weld"))
    t = np.loadtxt(tmp_path / "weld.csv", delimiter=",", skiprows=1, ndmin=2)
    return p, d, t


@pytest.mark.parametrize("dim", [2, 3])
def test_pressed_automata_weld_and_separate_at_the_weld_strength(lammps_available, tmp_path, dim):
    p, d, t = _run(tmp_path, dim=dim)
    fx, links, broken, welds = t[:, 1], t[:, 2], t[:, 3], t[:, 4]
    assert welds[-1] == 1 and broken[-1] == 1 and links.max() == 1
    # pull-off force = A * weld_factor * sigma_0 (pair area of the C++ law); within 5 %
    # (measured -0.2 %: the last step before the break, one stroke increment 2G v dt / d below)
    f_weld = pair_area(d, dim) * p.weld_factor * to_lammps(p.ultimate_strength, "pressure")
    assert -fx.min() == pytest.approx(f_weld, rel=0.05)
    # after the break the automata separate: no force at the end of the stroke
    assert fx[-1] == 0.0


def test_weld_strength_is_a_parameter(lammps_available, tmp_path):
    p, d, t = _run(tmp_path, weld_factor=0.25)
    f_weld = pair_area(d, 2) * 0.25 * to_lammps(p.ultimate_strength, "pressure")
    assert -t[:, 1].min() == pytest.approx(f_weld, rel=0.05)


def test_no_weld_when_pressed_below_the_onset(lammps_available, tmp_path):
    # overlap 0.001 nm: contact stress Kc * 0.001 / d = 158 MPa < weld onset sigma_y = 480 MPa
    p, d, t = _run(tmp_path, press=0.001)
    assert p.contact_modulus * 0.001e-9 / p.diameter < p.weld_onset_stress
    assert t[:, 4].max() == 0
    assert t[:, 1].min() >= 0.0  # unlinked automata never pull


def test_break_and_reweld_more_than_ten_times(lammps_available, tmp_path):
    p, d, t = _run(tmp_path, ncycles=12)
    links, broken, welds, cross_formed, cross_broken = (t[:, k] for k in (2, 3, 4, 5, 6))
    # no re-link cap: every cycle welds and breaks again (bpm + fix bond/create maxbond 6 cap at 6)
    assert welds[-1] == 12 and broken[-1] == 12
    # different molecule ids: each weld is a cross-body link
    assert cross_formed[-1] == 12 and cross_broken[-1] == 12
    f_weld = pair_area(d, 2) * p.weld_factor * to_lammps(p.ultimate_strength, "pressure")
    # every cycle separates at the same strength (within 5 %)
    cyc = np.split(t[:, 1], np.flatnonzero(np.diff(welds) > 0) + 1)[1:]
    assert len(cyc) == 12
    assert all(-c.min() == pytest.approx(f_weld, rel=0.05) for c in cyc)


def test_same_body_welds_are_not_cross_body(lammps_available, tmp_path):
    p, d, t = _run(tmp_path, ncycles=2, mol2=1)
    assert t[-1, 4] == 2 and t[-1, 5] == 0 and t[-1, 6] == 0
