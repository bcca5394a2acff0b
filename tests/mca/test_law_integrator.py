"""fix nve/mca (the plugin's integrator of the mca law) reproduces fix nve/bpm/sphere bit for bit.

The mca law never reads an automaton's orientation, so its decks integrate with the plugin's
``nve/mca``: the velocity-Verlet arithmetic of ``nve/bpm/sphere`` without the quaternion
update.  The claim is bit identity of positions, velocities and angular velocities (the whole
trajectory of the law), checked on the sheared periodic block of ``mca_block.in`` with the
default (damped, viscous, so rotations feed back into the forces) law, through link rupture
and welding, in 2D, 2D with the disc moment of inertia, and 3D.  A wrong moment of inertia
(``nve/mca disc`` against the sphere's) fails it at the first comparison.  (``fix nve/sphere``
forms the inverse moment of inertia in another order: it happens to round alike on this block,
but not on the smoke friction run, whose friction.csv then differs from row 4 on; that is why
the law has its own integrator instead of ``nve/sphere``.)
"""

from __future__ import annotations

import numpy as np
import pytest

from tests.mca.helpers import run_block
from tribolmp.lammps.material_test import block_setup

pytestmark = pytest.mark.lammps


def _run(tmp_path, name, dim, n, integrator):
    v = block_setup("mca", dim, tmp_path / name, n=n)
    v.update(vshear=100.0, steps=600, print_every=600, integrator=integrator)
    return run_block(v, tmp_path / f"{name}.npz")


@pytest.mark.parametrize(
    ("dim", "n", "option"), [(2, 12, ""), (2, 12, " disc"), (3, 4, "")], ids=["2d", "2d_disc", "3d"]
)
def test_nve_mca_reproduces_nve_bpm_sphere_bit_for_bit(lammps_available, tmp_path, dim, n, option):
    ref = _run(tmp_path, "bpm_sphere", dim, n, "nve/bpm/sphere" + option)
    new = _run(tmp_path, "nve_mca", dim, n, "nve/mca" + option)
    # the run must exercise the law's events, else identity would be cheap
    assert ref["tallies"][4] > 0, "no link broke: the block is not sheared through rupture"
    assert np.abs(ref["omega"]).max() > 0.0
    for key in ("x", "v", "omega"):
        # bit identity (same operations in the same order), no tolerance
        assert np.array_equal(ref[key], new[key]), f"{key} differs from nve/bpm/sphere"
    assert np.array_equal(ref["tallies"], new["tallies"])


def test_nve_mca_rejects_disc_in_3d(lammps_available, tmp_path):
    with pytest.raises(AssertionError, match="disc"):
        _run(tmp_path, "disc3d", 3, 4, "nve/mca disc")
