"""The committed tiny dataset is current and the analyses reproduce its stored answers."""

from __future__ import annotations

import pytest

from tests import data
from tribolmp.analysis.friction import FrictionCoefficient
from tribolmp.analysis.outputs import open_trajectory, read_meta
from tribolmp.analysis.transfer import BondTurnover, MassTransfer


def test_committed_files_match_the_generator(tmp_path):
    answers = data.generate("tiny_transfer", tmp_path)
    assert answers == data.expected("tiny_transfer")
    for name in ("traj.lammpstrj", "meta.json", "friction.csv"):
        assert (tmp_path / name).read_bytes() == (data.path("tiny_transfer") / name).read_bytes(), (
            name
        )


def test_analyses_on_committed_data():
    folder = data.path("tiny_transfer")
    exp = data.expected("tiny_transfer")
    meta = read_meta(folder)
    u = open_trajectory(folder, meta)
    bt = BondTurnover(u, meta).run().results
    assert (bt.broken_total, bt.formed_total) == (
        exp["make_transfer"]["broken_total"],
        exp["make_transfer"]["formed_total"],
    )
    mt = MassTransfer(u, meta, window=1).run().results
    assert mt.transfer_events == exp["make_transfer"]["transfer_events"]
    assert mt.transfer_rate == pytest.approx(exp["make_transfer"]["transfer_rate"], rel=1e-4)
    fc = FrictionCoefficient(folder).run().results
    # 400 AR(1) samples (phi = 0.5): the stored exact standard error; 4 sigma
    assert abs(fc.mu - exp["make_friction"]["mu"]) < 4 * exp["make_friction"]["mu_err"]


def test_unknown_dataset_name():
    with pytest.raises(KeyError, match="tiny_transfer"):
        data.path("nope")
