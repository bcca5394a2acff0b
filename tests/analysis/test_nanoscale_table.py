"""The nanoscale table never mixes dimensions: a 3D run is another experiment, not another seed."""

from __future__ import annotations

import csv

import pytest

from tribolmp.analysis.nanoscale_table import build_table


def _write(path, rows):
    keys = ["run", "pressure_Pa", "sliding_velocity_m_s", "seed", "dim", "law", "mu", "mu_err",
            "mu_steady"]
    with path.open("w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=keys)
        w.writeheader()
        w.writerows(dict(zip(keys, r)) for r in rows)


def test_a_3d_run_is_not_combined_with_the_2d_seeds(tmp_path):
    """Two 2D seeds and one 3D run at the same (P, V): the 2D table holds the two seeds only."""
    path = tmp_path / "campaign.csv"
    _write(path, [("a", 150e6, 5.0, 1, 2, "mca", 0.30, 0.01, "True"),
                  ("b", 150e6, 5.0, 2, 2, "mca", 0.40, 0.01, "True"),
                  ("c", 150e6, 5.0, 1, 3, "mca", 0.90, 0.01, "True")])
    two = build_table(path, law="mca")["rows"]
    assert len(two) == 1 and two[0]["n_runs"] == 2 and two[0]["runs"] == ["a", "b"]
    # exact mean of the two 2D values (0.35); with the 3D run mixed in it would be 0.533
    assert two[0]["mu"] == pytest.approx(0.35, rel=1e-12)
    three = build_table(path, law="mca", dim=3)
    assert three["rows"][0]["runs"] == ["c"] and three["provenance"]["dims"] == ["3"]
    with pytest.raises(ValueError, match="no finished 2D run"):
        build_table(path, law="bpm/spring/plastic")
