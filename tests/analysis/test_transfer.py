"""BondTurnover and MassTransfer against a scripted trajectory with exact answers."""

from __future__ import annotations

import numpy as np
import pytest

from tribolmp.analysis.outputs import open_trajectory, read_meta
from tribolmp.analysis.transfer import STATE_LAYER, STATE_LOWER, STATE_UPPER, BondTurnover, MassTransfer, count_events
from tribolmp.analysis.synthetic import make_transfer


@pytest.fixture(scope="module")
def scripted(tmp_path_factory):
    out = tmp_path_factory.mktemp("transfer")
    exp = make_transfer(out, np.random.default_rng(3))
    meta = read_meta(out)
    return meta, open_trajectory(out, meta), exp


def test_links_broken_and_formed_exactly(scripted):
    meta, u, exp = scripted
    r = BondTurnover(u, meta).run().results
    # disjoint automata per interval: the c_nbond differences identify every link
    assert r.broken_total == exp["broken_total"]
    assert r.formed_total == exp["formed_total"]
    span = r.time_s[-1] - r.time_s[0]
    assert r.broken_per_s == pytest.approx(exp["broken_total"] / span)


def test_transfer_detachment_reattachment_exactly(scripted):
    meta, u, exp = scripted
    r = MassTransfer(u, meta, window=1).run().results
    for key in ("transfer_events", "detach_events", "reattach_events", "returned_events", "n_surface"):
        assert r[key] == exp[key], key
    # noise-free motion: rates are exact up to round-off of the float32 positions
    for key in ("sliding_distance_m", "transfer_rate", "net_transfer_rate", "detachment_rate",
                "reattachment_rate", "wear_rate"):
        assert r[key] == pytest.approx(exp[key], rel=1e-4), key
    assert r.crossed_lower_up[-1] == exp["crossed_lower_up"]
    assert r.crossed_upper_down[-1] == exp["crossed_upper_down"]
    assert r.crossed_lower_up[0] == 0


def test_default_window_keeps_events(scripted):
    meta, u, exp = scripted
    r = MassTransfer(u, meta).run().results
    # V dt_dump = 1 nm < d = 2.5 nm: the default window averages over 3 frames; the scripted
    # transfers are permanent, so they are still counted exactly
    assert r.window == 3
    assert r.transfer_events == exp["transfer_events"]


def test_count_events_by_hand():
    own = np.array([STATE_LOWER, STATE_UPPER, STATE_LOWER])
    states = np.array([
        [STATE_LOWER, STATE_UPPER, STATE_LOWER],
        [STATE_LAYER, STATE_UPPER, STATE_UPPER],  # 0 detaches; 2 jumps to the upper body
        [STATE_LOWER, STATE_LOWER, STATE_UPPER],  # 0 returns; 1 transfers down
    ])
    ev = count_events(states, own)
    np.testing.assert_array_equal(ev["detach"], [2, 1])
    np.testing.assert_array_equal(ev["reattach"], [1, 2])
    np.testing.assert_array_equal(ev["transfer"], [1, 1])
    np.testing.assert_array_equal(ev["returned"], [0, 1])
