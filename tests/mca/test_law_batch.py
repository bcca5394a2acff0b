"""The batched common case of pair mca gives the general path's numbers, bit for bit.

``pair_style mca`` evaluates its pairs in batches: the common case (an existing link, weld or
attachment advanced by one step that does not break) is computed for a whole batch in
vectorised loops (``batch_common``), every other pair (contacts, new links, ruptures, welds,
the first step, re-evaluations) on the general path.  Both are the same expressions in the same
order, so a run with ``batch no`` (every pair on the general path) must reproduce the default
run exactly: positions, velocities, angular velocities and the law's tallies, on the sheared
periodic block of ``mca_block.in`` through link rupture and welding (so that pairs move between
the two paths during the run), in 2D and 3D, with one radius and with radii that differ from
automaton to automaton (the pair constants are then formed per pair).  A change to the law in
one path and not in the other fails it.
"""

from __future__ import annotations

import numpy as np
import pytest

from tests.mca.helpers import run_block
from tribolmp.lammps.material_test import block_setup

pytestmark = pytest.mark.lammps


def _perturb_diameters(data, rng: np.random.Generator, spread: float) -> None:
    """Scale each automaton's diameter in a data file by 1 + U(-spread, spread)."""
    lines = data.read_text().splitlines()
    k = next(i for i, ln in enumerate(lines) if ln.startswith("Atoms"))
    for i in range(k + 1, len(lines)):
        cols = lines[i].split()
        if not cols:
            if i > k + 1:
                break
            continue
        # atom_style bpm/sphere: id mol type diameter density x y z
        cols[3] = repr(float(cols[3]) * (1.0 + rng.uniform(-spread, spread)))
        lines[i] = " ".join(cols)
    data.write_text("\n".join(lines) + "\n")


def _run(tmp_path, name, dim, n, batch, spread, fused="yes", steps=600, **extra):
    v = block_setup("mca", dim, tmp_path / name, n=n)
    if spread:
        _perturb_diameters(tmp_path / name / "block.data", np.random.default_rng(7), spread)
    v.update(vshear=100.0, steps=steps, print_every=steps, mca_batch=batch, mca_fused=fused)
    v.update(extra)
    return run_block(v, tmp_path / f"{name}.npz")


@pytest.mark.parametrize(
    ("dim", "n", "spread"),
    [(2, 12, 0.0), (2, 12, 0.01), (3, 4, 0.0), (3, 4, 0.01)],
    ids=["2d", "2d_radii", "3d", "3d_radii"],
)
def test_batched_common_case_matches_general_path(lammps_available, tmp_path, dim, n, spread):
    ref = _run(tmp_path, "general", dim, n, "no", spread)
    new = _run(tmp_path, "batched", dim, n, "yes", spread)
    # the run must move pairs between the paths: links break (general path) while the intact
    # ones advance (common case), and contacts weld
    assert ref["tallies"][4] > 0, "no link broke: the block is not sheared through rupture"
    assert ref["tallies"][5] > 0, "nothing welded"
    assert ref["tallies"][0] > 0, "no links left"
    for key in ("x", "v", "omega"):
        # bit identity (same operations in the same order), no tolerance
        assert np.array_equal(ref[key], new[key]), f"{key} differs between the two paths"
    assert np.array_equal(ref["tallies"], new["tallies"])
    # which path took the common case: the fused kernel only with one radius and one mass
    # (the tally is the last step's: in 3D the kernel still takes intact stretches of links;
    # the 2D block is then too damaged for four links in a row, and the test below shows it
    # taking every link of an intact one)
    assert ref["fused"] == 0
    assert (new["fused"] > 0) == (dim == 3 and not spread), new["fused"]


@pytest.mark.parametrize(
    ("dim", "n", "vshear", "links_per_automaton"),
    [(2, 24, 10.0, 3), (3, 8, 20.0, 6)],
    ids=["2d", "3d"],
)
def test_fused_kernel_matches_batch(
    lammps_available, tmp_path, dim, n, vshear, links_per_automaton
):
    """The fused kernel of the common case gives the batch's numbers, bit for bit.

    ``pair_style mca`` (one radius and one mass) hands the common case of four pairs at a
    time to a kernel that keeps them in AVX registers from their inputs to their sums
    (``fused4``, one branch per dimension); ``fused no`` leaves them to the batch.  A periodic
    block as above, but larger and sheared by ``fix deform`` with ``remap v`` (image pairs
    across the periodic boundary, b's velocity shifted by the box's rate); the two runs must
    agree exactly.
    """
    # (3D 8 x 8 x 8 cells, 2 048 automata: the test above, whose ramp drive does not deform the
    # box, passed with a wrong velocity shift in the kernel, and its 4-cell block with a wrong
    # position shift; 2D 24 x 24, 576 automata.  Below rupture -- 20 m/s in 3D, 10 m/s in 2D,
    # where 20 m/s broke two links -- every pair stays a link, so the kernel must take them
    # all: the lattice's links, 3 per automaton in 2D (hexagonal), 6 in 3D (fcc).  The test
    # above passes pairs between the paths through rupture and welding)
    kw = dict(steps=600, drive="deform", vshear=vshear)
    ref = _run(tmp_path, "batch", dim, n, "yes", 0.0, fused="no", **kw)
    new = _run(tmp_path, "fused", dim, n, "yes", 0.0, **kw)
    assert ref["fused"] == 0
    links = links_per_automaton * len(new["x"])
    assert new["fused"] == ref["tallies"][0] == links, (new["fused"], ref["tallies"])
    for key in ("x", "v", "omega"):
        # bit identity (same operations in the same order), no tolerance
        assert np.array_equal(ref[key], new[key]), f"{key} differs between batch and kernel"
    assert np.array_equal(ref["tallies"], new["tallies"])


@pytest.mark.parametrize(
    ("dim", "n", "spread"),
    [(2, 12, 0.01), (3, 4, 0.01)],
    ids=["2d_radii", "3d_radii"],
)
def test_pruned_lists_lose_no_contact(lammps_available, tmp_path, dim, n, spread):
    """Pruned evaluation lists (the default) reproduce the full neighbour lists bit for bit.

    ``rebuild_cache`` leaves out the pairs without state that are farther apart than contact
    plus the skin: they cannot touch before LAMMPS rebuilds the lists.  Were one of them to
    touch before, its contact force would be missing and the runs would part -- so the same
    sheared block through rupture and welding (contacts form and open all the time), with radii
    that differ per automaton, must give the same trajectory with ``prune no``.  A limit
    without the skin fails this test.
    """

    def run(name, prune):
        v = block_setup("mca", dim, tmp_path / name, n=n)
        _perturb_diameters(tmp_path / name / "block.data", np.random.default_rng(7), spread)
        v.update(vshear=100.0, steps=600, print_every=600, mca_prune=prune)
        return run_block(v, tmp_path / f"{name}.npz")

    full = run("full", "no")
    pruned = run("pruned", "yes")
    assert full["tallies"][6] > 0, "no contacts: pruning is not exercised"
    assert full["tallies"][5] > 0, "nothing welded"
    for key in ("x", "v", "omega"):
        # bit identity: a pruned pair contributes nothing, a kept one the same numbers
        assert np.array_equal(full[key], pruned[key]), f"{key} differs with pruned lists"
    assert np.array_equal(full["tallies"], pruned["tallies"])
