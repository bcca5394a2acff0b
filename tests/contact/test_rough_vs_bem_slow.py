"""Slow: the shipped rough-contact references are what today's BEM computes at full resolution."""

from __future__ import annotations

import json

import numpy as np
import pytest

from tests.data import DATA_DIR
from tests.data import contact_references as cr
from tribolmp.models.contact.bem import solve_bem
from tribolmp.models.contact.interfacial import interfacial_stiffness

_NAMES = sorted(json.loads((DATA_DIR / "contact_references.json").read_text())["classes"])


@pytest.mark.slow
@pytest.mark.parametrize("name", [_NAMES[0], _NAMES[-1]])
def test_references_reproduce_at_full_resolution(name):
    # Recompute map 0 of two classes (first and last by name) on its reference grid (512^2, or
    # 256^2 for light-mode classes) at two resolved pressures
    # (periodic cell via the C5 function interfacial_stiffness, and the rigid square punch):
    # the stiffness must equal the shipped value to 1e-6 (BEM tolerance 1e-10, tangent CG 1e-8),
    # and the MDR/punch and MDR/periodic ratios of that map then follow from the shipped MDR row.
    refs = json.loads((DATA_DIR / "contact_references.json").read_text())
    cls = refs["classes"][name]
    ok = np.nonzero(cr.resolved_mask(cls))[0]
    js = [ok[0], ok[len(ok) // 2]]
    m = cls["maps"][0]
    h, dx = cr.reference_surface(cls["recipe"], m["seed"], cr.n_base(cls))
    P = [cls["pressures"][j] for j in js]
    per = interfacial_stiffness(h, dx, cr.E_STAR, P, tol=cr.BEM_TOL)
    assert np.all(per.resolved)  # >= 20 pixels per patch at these pressures
    for i, j in enumerate(js):
        assert per.stiffness[i] == pytest.approx(m["periodic"]["stiffness"][j], rel=1e-6)
        assert per.stiffness_per_area[i] == pytest.approx(
            m["periodic"]["stiffness"][j] / cr.SIDE**2, rel=1e-6
        )
        assert per.mean_gap[i] == pytest.approx(m["periodic"]["mean_gap"][j], rel=1e-6)
    punch = solve_bem(h, dx, cr.E_STAR, P[0], periodic=False, tol=cr.BEM_TOL)
    assert punch.stiffness == pytest.approx(m["punch"]["stiffness"][js[0]], rel=1e-6)
    # Physical bound: a partial contact is softer than the closed square punch of side L, whose
    # stiffness is 2 E* sqrt(A/pi) within 4 % (checked in test_bem.py) -> 5 % margin.
    assert punch.stiffness < 2 * cr.E_STAR * cr.SIDE / np.sqrt(np.pi) * 1.05
