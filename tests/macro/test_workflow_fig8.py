"""The Fig. 8 workflow: shape of the curve and the fitted length."""

import json
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def test_fig8_workflow_fits_about_50_nm(tmp_path):
    sys.path.insert(0, str(ROOT / "workflows"))
    try:
        import fig8_tribospectroscopy as wf
    finally:
        sys.path.pop(0)
    assert wf.main(["--out", str(tmp_path), "--seed", "7"]) == 0
    out = json.loads((tmp_path / "fig8_fit.json").read_text())
    assert out["model"] == "potential"
    # synthetic truth 50 nm per contact; 4 % relative noise on 26 points
    lo, hi = out["length_interval_m"]
    assert lo - 3 * out["length_std_m"] <= 50e-9 <= hi + 3 * out["length_std_m"]
    assert out["length_m"] == pytest.approx(50e-9, rel=0.2)
    # Fig. 8's shape: a fast drop up to 0.1 um (probe amplitude), then a slower one up to 0.5 um
    assert out["drop_to_0.1um"] > 0.5
    assert 0.2 < out["drop_0.1_to_0.5um"] < out["drop_to_0.1um"] + 0.2
    assert (tmp_path / "fig8_tribospectroscopy.png").stat().st_size > 5000
