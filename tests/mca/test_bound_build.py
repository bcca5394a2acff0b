"""The timing-only bound build (``benchmarks/_mca_bound_build.py``) still applies to the source.

The bound on the pair state's cost in docs/mca.md is reproducible only while the script's
anchored edits match the shipped pair loop; these tests fail as soon as the loop changes so
that an edit would no longer apply (or would apply twice), instead of the script silently
building something else.  No compilation here: the build itself is the benchmark's.
"""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest

from tribolmp.lammps.plugin import SOURCE_DIR

ROOT = Path(__file__).resolve().parents[2]


def _script():
    spec = importlib.util.spec_from_file_location(
        "mca_bound_build", ROOT / "benchmarks" / "_mca_bound_build.py"
    )
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def _assert_applied(out, edits):
    """Every anchor of ``edits`` replaced once in ``out``."""
    for anchor, replacement in edits:
        # (a replacement may keep its anchor's lines after an inserted one; "" removes a line)
        assert out.count(anchor) == replacement.count(anchor)
        assert replacement in out


def test_edits_apply_once_to_the_shipped_pair_loop():
    mod = _script()
    text = (SOURCE_DIR / "pair_mca.cpp").read_text()
    out = mod.bound_source(text)
    # every anchor replaced, nothing else touched
    for anchor, replacement in mod.EDITS:
        assert anchor not in out
        assert replacement in out
    assert out.count("bound_entry") == 2 and out.count("bound_sink") == 2
    # the general path keeps its own reads of the pair state
    assert out.count("psc + (eoff + jj) * NP - 1") == text.count("psc + (eoff + jj) * NP - 1") > 0


def test_no_partners_edits_apply_once():
    mod = _script()
    text = (SOURCE_DIR / "pair_mca.cpp").read_text()
    out = mod.bound_source(text, partners=False)
    _assert_applied(out, mod.EDITS + mod.PARTNER_EDITS)
    # the general path still adds into both automata (its own apply of j is the scatter's)
    assert "apply(i, true, -dx, -dy, -dz);" in out


@pytest.mark.parametrize("how", ["missing", "twice"])
def test_a_changed_pair_loop_is_refused(how):
    mod = _script()
    text = (SOURCE_DIR / "pair_mca.cpp").read_text()
    anchor = mod.EDITS[0][0]
    bad = text.replace(anchor, "") if how == "missing" else text.replace(anchor, anchor + anchor)
    with pytest.raises(mod.AnchorError, match="edit 0: expected the line"):
        mod.bound_source(bad)


@pytest.mark.parametrize("kind", ["store", "vstore", "load", "gather", "add", "nop"])
def test_probe_inserts_its_operations_once_per_pair(kind):
    mod = _script()
    text = (SOURCE_DIR / "pair_mca.cpp").read_text()
    out = mod.probe_source(text, kind, 7)
    # inserted right after the pair is taken into the batch, before its first copy into it
    start = out.index(mod.PROBE_ANCHOR + "      // TIMING PROBE: 7 x " + kind) + len(
        mod.PROBE_ANCHOR
    )
    end = out.index("      B.i[ip] = i;", start)
    block = out[start:end]
    op = {
        "store": "] = R0;",
        "vstore": "_mm256_storeu_pd(",
        "load": "+= mca_probe_buf[",
        "gather": "_mm256_i32gather_pd(",
        "add": "+= 1.0;",
        "nop": "nop\\n",
    }[kind]
    assert block.count(op) == 7
    # without the probe's block and globals, the source is the shipped one (same numbers)
    assert (out[:start] + out[end:]).replace(mod.PROBE_GLOBALS, "", 1) == text


def test_probe_refuses_a_changed_loop_and_bad_arguments():
    mod = _script()
    text = (SOURCE_DIR / "pair_mca.cpp").read_text()
    with pytest.raises(mod.AnchorError, match="PROBE_ANCHOR"):
        mod.probe_source(text.replace(mod.PROBE_ANCHOR, ""), "store", 4)
    with pytest.raises(ValueError, match="expected a kind"):
        mod.probe_source(text, "fma", 4)
    with pytest.raises(ValueError, match="1-512"):
        mod.probe_source(text, "store", 0)


def test_no_staging_edits_apply_once():
    mod = _script()
    text = (SOURCE_DIR / "pair_mca.cpp").read_text()
    out = mod.bound_source(text, staging=False)
    _assert_applied(out, mod.EDITS + mod.STAGING_EDITS)
    # the batch is filled once; the lanes pass 2a reads are no longer written per pair
    assert out.count("bound_staged = true;") == 1
    assert "B.oa0[ip] =" not in out and "B.D5[ip] =" not in out and "B.pn[ip] =" not in out
    # what the bound still stages: indices, geometry, kind, and rp = R (EDITS)
    assert "B.kind[ip] = sl[FS::S_KIND];" in out and "B.rp0[ip] = R0;" in out
    # it combines with --no-partners
    both = mod.bound_source(text, partners=False, staging=False)
    assert "TIMING BOUND: no partner row" in both and "bound_staged" in both
