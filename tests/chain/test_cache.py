"""Stage cache: keys follow inputs, commits are atomic, partial work survives."""

from __future__ import annotations

import json

from tribolmp.chain.cache import StageCache, atomic_write_json, canonical_json, hash_inputs


def test_key_depends_on_every_input(tmp_path):
    c = StageCache(tmp_path)
    base = {"sections": {"topography": {"dx": 1e-8}}, "upstream": {"nanoscale": "abc"}, "seed": [1, 1]}
    k = c.key("topography", base)
    assert k == c.key("topography", json.loads(json.dumps(base)))  # same content, new objects
    assert k != c.key("contact", base)
    assert k != c.key("topography", {**base, "upstream": {"nanoscale": "abd"}})
    assert k != c.key("topography", {**base, "seed": [1, 2]})
    assert k != c.key("topography", {**base, "sections": {"topography": {"dx": 1.0000001e-8}}})


def test_canonical_json_is_order_independent():
    assert canonical_json({"b": 1, "a": (1, 2)}) == canonical_json({"a": [1, 2], "b": 1})
    import math

    # Floats hash by their exact repr: the next representable number is a different input.
    assert hash_inputs({"x": 0.1}) != hash_inputs({"x": math.nextafter(0.1, 1.0)})


def test_commit_lookup_discard(tmp_path):
    c = StageCache(tmp_path)
    assert c.lookup("contact", "k1") is None
    work = c.workdir("contact", "k1")
    (work / "data.txt").write_text("42")
    # Before commit, the stage is not visible (an interrupt here loses nothing committed).
    assert c.lookup("contact", "k1") is None
    hit = c.commit("contact", "k1", {"values": {"k": 1.5}, "files": {"data": "data.txt"}})
    assert not work.exists() and hit.path.is_dir()
    again = c.lookup("contact", "k1")
    assert again.values == {"k": 1.5} and again.file("data").read_text() == "42"
    c.discard("contact", "k1")
    assert c.lookup("contact", "k1") is None


def test_incomplete_result_is_not_a_hit(tmp_path):
    c = StageCache(tmp_path)
    final = c.final_dir("contact", "k2")
    final.mkdir(parents=True)
    (final / "result.json").write_text('{"key": "k2"')  # truncated write
    assert c.lookup("contact", "k2") is None
    atomic_write_json(final / "result.json", {"key": "k2", "complete": False})
    assert c.lookup("contact", "k2") is None


def test_partial_workdir_is_reused_for_resume(tmp_path):
    c = StageCache(tmp_path)
    (c.workdir("nanoscale", "k3") / "restart.1000").write_text("x")
    assert (c.workdir("nanoscale", "k3") / "restart.1000").exists()
    assert not (c.workdir("nanoscale", "k3", fresh=True) / "restart.1000").exists()


def test_code_hash_is_stable_and_per_model():
    from tribolmp.chain.planner import STAGES, code_hash

    hashes = {s: code_hash(s) for s in STAGES}
    assert hashes == {s: code_hash(s) for s in STAGES}
    # Different models read different sources, so their code identities differ.
    assert len(set(hashes.values())) == len(STAGES)
