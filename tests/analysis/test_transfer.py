"""BondTurnover and MassTransfer against a scripted trajectory with exact answers."""

from __future__ import annotations

import numpy as np
import pytest

from tribolmp.analysis.outputs import open_trajectory, read_meta
from tribolmp.analysis.synthetic import make_transfer
from tribolmp.analysis.transfer import (
    STATE_LAYER,
    STATE_LOWER,
    STATE_UPPER,
    BondTurnover,
    MassTransfer,
    count_events,
    counting_rate,
    persistent_membership,
)


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


def test_transfer_and_wear_exactly(scripted):
    meta, u, exp = scripted
    r = MassTransfer(u, meta, window=1).run().results
    # default persistence: the slider moves 2 d = 5 nm, 5 frames at 1 nm/frame
    assert r.persistence_frames == 5
    for key in (
        "transfer_events",
        "detach_events",
        "return_events",
        "n_surface",
        "net_transfer_lower_to_upper",
        "wear_lower",
        "wear_upper",
    ):
        assert r[key] == exp[key], key
    # noise-free motion: rates are exact up to round-off of the float32 positions
    for key in (
        "span_s",
        "sliding_distance_m",
        "transfer_per_s",
        "transfer_per_s_err",
        "transfer_per_m",
        "transfer_rate",
        "wear_lower_per_s",
        "wear_lower_per_s_err",
        "wear_upper_per_m",
        "wear_upper_per_m_err",
    ):
        assert r[key] == pytest.approx(exp[key], rel=1e-4), key
    assert r.crossed_lower_up[-1] == exp["crossed_lower_up"]
    assert r.crossed_upper_down[-1] == exp["crossed_upper_down"]
    assert r.crossed_lower_up[0] == 0


def test_short_visits_are_not_transfer(scripted):
    meta, u, exp = scripted
    # with no persistence every instantaneous flip counts: the 3 two-frame
    # flickers to the upper body become 3 transfers and 3 returns -- what
    # the velocity-state count of the old analysis reported
    r1 = MassTransfer(u, meta, window=1, persistence_s=0.0).run().results
    assert r1.transfer_events == exp["transfer_events"] + exp["flicker_events"]
    assert r1.return_events == exp["return_events"] + exp["flicker_events"]
    r5 = MassTransfer(u, meta, window=1).run().results
    assert r5.transfer_events == exp["transfer_events"]


def test_default_window_keeps_events(scripted):
    meta, u, exp = scripted
    r = MassTransfer(u, meta).run().results
    # V dt_dump = 1 nm < d = 2.5 nm: the default window averages over 3 frames; the scripted
    # transfers are permanent, so they are still counted exactly
    assert r.window == 3
    assert r.transfer_events == exp["transfer_events"]


def test_persistent_membership_by_hand():
    L, M, U = STATE_LOWER, STATE_LAYER, STATE_UPPER
    states = np.array([[L, U], [U, U], [U, L], [L, L], [U, L], [U, L], [U, L]])
    own = np.array([L, U])
    mem = persistent_membership(states, own, 3)
    # automaton 0: the 2-frame visit to U is ignored; the 3-frame run from
    # frame 4 is accepted at frame 4
    np.testing.assert_array_equal(mem[:, 0], [L, L, L, L, U, U, U])
    # automaton 1: its run of L from frame 2 lasts 5 frames: member of the lower body from frame 2
    np.testing.assert_array_equal(mem[:, 1], [U, U, L, L, L, L, L])
    # a run still shorter than the persistence at the end is not (yet) a change
    mem2 = persistent_membership(np.array([[L], [L], [M], [M]]), np.array([L]), 3)
    np.testing.assert_array_equal(mem2[:, 0], [L, L, L, L])


def test_counting_rate_errors():
    assert counting_rate(16, 2.0) == (8.0, 2.0)
    # nothing counted: the error is one event per exposure, not 0
    assert counting_rate(0, 4.0) == (0.0, 0.25)


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


def _linked_run(out, with_links: bool):
    """Write and analyse rigid bodies whose two lower automata weld to the upper body at frame 10.

    The lower body rests, the upper body and slider move at V; from frame 10 on, two lower-body
    automata have all their links to the upper body while still moving with the lower body.
    """
    from tribolmp.analysis.synthetic import write_dump, write_meta

    d, n_row, V, dt_ns = 2.5, 10, 10.0, 0.1
    rows = [(0.5 * d, 1), (1.5 * d, 2), (2.5 * d, 2), (3.5 * d, 3), (4.5 * d, 3), (5.5 * d, 4)]
    h = np.concatenate([np.full(n_row, y) for y, _ in rows])
    mol = np.concatenate([np.full(n_row, m) for _, m in rows])
    x0 = np.tile((np.arange(n_row) + 0.5) * d, len(rows))
    moving = mol >= 3
    welded = np.nonzero(mol == 2)[0][-2:]
    frames = []
    for k in range(30):
        x = np.mod(x0 + np.where(moving, V * dt_ns * k, 0.0), n_row * d)
        cross = np.zeros(h.size, dtype=int)
        if k >= 10:
            cross[welded] = 4
        extra = (
            {"f_mca_state[8]": np.full(h.size, 4), "f_mca_state[9]": cross} if with_links else None
        )
        frames.append(
            dict(
                step=1000 * k,
                box=np.array([[0, n_row * d], [0, 6 * d], [-0.5, 0.5]]),
                mol=mol,
                pos=np.column_stack([x, h, np.zeros(h.size)]),
                vel=np.column_stack([np.where(moving, V, 0.0), np.zeros(h.size), np.zeros(h.size)]),
                radius=d / 2,
                nbond=4,
                extra=extra,
            )
        )
    write_dump(out / "traj.lammpstrj", frames)
    write_meta(out, dt_s=1e-13, dump_interval_steps=1000, velocity_m_s=V, diameter_m=d * 1e-9,
               box_m=frames[0]["box"] * 1e-9)
    meta = read_meta(out)
    return MassTransfer(open_trajectory(out, meta), meta, window=1).run().results


def test_links_to_the_other_body_are_membership(tmp_path):
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    # with the mca law's per-automaton link columns: the two welded automata
    # are members of the upper body
    r = _linked_run(tmp_path / "a", with_links=True)
    assert r.membership_source.startswith("velocity and links")
    assert r.transfer_events == 2 and r.wear_lower == 2 and r.wear_upper == -2
    # without them only the velocity decides: nothing moved, nothing transferred
    r0 = _linked_run(tmp_path / "b", with_links=False)
    assert r0.membership_source == "velocity" and r0.transfer_events == 0
