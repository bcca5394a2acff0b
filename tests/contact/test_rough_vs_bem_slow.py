"""Slow: MDR ensemble stiffness against the 3D BEM over three decades of pressure."""

from __future__ import annotations

import numpy as np
import pytest

from tribolmp.models.contact import solve_rough
from tribolmp.models.contact.rough import generate_surface, self_affine_psd


@pytest.mark.slow
def test_mdr_stiffness_within_30_percent_of_punch_bem():
    n, dx, E = 128, 2e-6, 1.13e11
    s_rng, e_rng = np.random.default_rng(20060327).spawn(2)
    h = generate_surface(n, dx, self_affine_psd(1e-6, 0.8, n * dx / 4, 8e-6), s_rng)
    pressures = [1e5, 1e6, 1e7, 1e8]
    mdr = solve_rough(h, dx, E, pressures, method="mdr", realizations=16, rng=e_rng)
    bem = solve_rough(h, dx, E, pressures, method="bem", periodic=False)
    ratio = mdr.stiffness / bem.stiffness
    # The goal: +-30 % of the 3D BEM over three decades (1e5 - 1e8 Pa) for the
    # finite rough punch, which is what a finite MDR line represents.  Against the
    # periodic interfacial stiffness the MDR falls below by 2x at high load (sublinear vs
    # linear stiffness, PHYSICS.md §2) -- that comparison is reported, not asserted.
    assert np.all(np.abs(ratio - 1) <= 0.3), ratio
