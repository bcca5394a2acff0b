"""Restart files of the automaton layout before 2026-12-06 continue exactly.

Until 2026-12-06 ``fix mca/state`` kept an automaton's row in another order (stress, plastic
strain tensor, eps_eq, pending increments, X, link counts, counters, von Mises stress, ...)
and streamed the per-atom output into a separate array; now the output columns lead the row
and LAMMPS reads them in place.  A restart file carries the rows, so a file of the old order
is read and reordered (``unpack_restart``).  The fixture (tests/data/mca_restart_layout1,
``generate_mca_restart_fixture.py``) is a restart of the sheared 2D block written by the plugin
of main@2f3eac9, and the state that plugin reached when it continued the file for 300 steps
through rupture and welding.  The claim is bit identity: continuing the same file is the same
arithmetic on the same numbers, whatever the order the row is kept in.  A wrong place for any
value that the law reads (X, the X of the committed step, the pending plastic increments, the
plastic strain, eps_eq, the committed forces) changes the continuation; the output columns
(``f_mca_state``) are compared too.
"""

from __future__ import annotations

import shutil

import numpy as np
import pytest

from tests.data.generate_mca_restart_fixture import HERE, STEPS, run, variables

pytestmark = pytest.mark.lammps


def test_old_layout_restart_continues_bit_for_bit(lammps_available, tmp_path):
    from tribolmp.lammps.plugin import plugin_path

    rst = tmp_path / "block.restart"
    shutil.copy(HERE / "block.restart", rst)
    v = variables(tmp_path / "blk", str(plugin_path()))
    out = tmp_path / "now.npz"
    run(dict(v, steps=str(STEPS), resume="1", restart_in=str(rst)), out)
    ref, now = np.load(HERE / "reference.npz"), np.load(out)
    # the continuation passes rupture and welding (tallies: links broken, welds formed)
    assert ref["tallies"][4] > 0 and ref["tallies"][5] > 0
    order_ref, order_now = np.argsort(ref["id"]), np.argsort(now["id"])
    for key in ("x", "v", "omega", "state"):
        # bit identity, no tolerance (see the module docstring)
        assert np.array_equal(ref[key][order_ref], now[key][order_now]), f"{key} differs"
    assert np.array_equal(ref["tallies"], now["tallies"])
