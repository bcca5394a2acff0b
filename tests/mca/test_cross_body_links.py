"""Issue 13: the smoke preset's rates.json counts links formed between the bodies (> 0 at 150 MPa).

The mca law's C2 tallies are printed into friction.csv (extra columns after the four SI ones)
and read by the analysis.  Before this, friction.csv had four columns and rates.json reported
``cross_body_links_formed = null``.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

TALLIES = ("links_total", "cross_body_links_current", "cross_body_links_formed",
           "cross_body_links_broken", "links_broken", "welds_formed")
SI_COLUMNS = ["time_s", "friction_N", "normal_N", "top_x_m"]
CUMULATIVE = ("cross_body_links_formed", "cross_body_links_broken", "links_broken", "welds_formed")


@pytest.mark.lammps
def test_smoke_at_150_MPa_welds_across_the_interface(cli, lammps_available, tmp_path):
    out = tmp_path / "run"
    res = cli("mca", "run", "--preset", "smoke", "--bond-style", "mca", "--pressure", "150e6",
              "--out", out, "--json", timeout=300)
    assert res.returncode == 0, res.stderr
    title = (out / "friction.csv").read_text().splitlines()[0].split(",")
    assert title[:4] == SI_COLUMNS and tuple(title[4:]) == TALLIES
    table = np.loadtxt(out / "friction.csv", delimiter=",", skiprows=1, ndmin=2)
    # cumulative tallies never decrease (they survive the driver's restart chunks)
    for name in CUMULATIVE:
        col = table[:, title.index(name)]
        assert np.all(np.diff(col) >= 0), name
    rates = json.loads(Path(res.json()["rates_json"]).read_text())
    cond = rates["conditions"]
    assert cond["law"] == "mca" and cond["pressure_Pa"] == pytest.approx(150e6)
    formed = rates["cross_body_links_formed"]
    assert isinstance(formed, int) and formed > 0, rates.get("cross_body_links_formed_reason")
    assert formed == int(table[-1, title.index("cross_body_links_formed")])
