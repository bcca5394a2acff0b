"""Stage cache: keys follow inputs, commits are atomic, partial work survives."""

from __future__ import annotations

import json

from tribolmp.chain.cache import StageCache, atomic_write_json, canonical_json, hash_inputs


def test_key_depends_on_every_input(tmp_path):
    c = StageCache(tmp_path)
    base = {
        "sections": {"topography": {"dx": 1e-8}},
        "upstream": {"nanoscale": "abc"},
        "seed": [1, 1],
    }
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
    from tribolmp.chain.registry import REGISTRY
    from tribolmp.chain.stage import code_hash

    hashes = {s.name: code_hash(s) for s in REGISTRY}
    assert hashes == {s.name: code_hash(s) for s in REGISTRY}
    # Different models read different sources, so their code identities differ.
    assert len(set(hashes.values())) == len(REGISTRY)


def test_code_closure_is_computed_from_the_imports():
    # The closure is the import graph, not a hand-kept list: the foundations MODEL_SOURCES missed
    # (scene fields, units, rng) are in, the lazily imported lubrication damper of the macroscale
    # model is in, and no stage sees another stage's file or the registry.
    from tribolmp.chain.registry import REGISTRY
    from tribolmp.chain.stage import PACKAGE_ROOT, code_closure

    rel = {
        s.name: {str(p.relative_to(PACKAGE_ROOT)) for p in code_closure(type(s).__module__, s.data)}
        for s in REGISTRY
    }
    assert {"params.py", "scene/schema.py", "rng.py", "models/topography/spde.py"} <= rel[
        "topography"
    ]
    assert any(p.startswith("models/lubrication/") for p in rel["macroscale"])
    assert any(p.startswith("lammps/") for p in rel["nanoscale"])
    assert any(p.startswith("analysis/") for p in rel["nanoscale"])
    assert any(p.startswith("data/lammps_inputs/") for p in rel["nanoscale"])
    for name, files in rel.items():
        assert f"chain/stages/{name}.py" in files
        others = {f"chain/stages/{o}.py" for o in rel if o != name}
        assert not files & others, (name, files & others)
        assert (
            "chain/registry.py" not in files
            and "chain/planner.py" not in files
            and "chain/runner.py" not in files
        )


def test_code_hash_changes_with_an_imported_source(tmp_path, monkeypatch):
    # A stage's key must change when any module it imports changes: the BEM solver's source,
    # as read by the hash, gains a line.
    from tribolmp.chain import stage as stage_mod
    from tribolmp.chain.registry import REGISTRY

    before = stage_mod.code_hash(REGISTRY["contact"])
    target = stage_mod.PACKAGE_ROOT / "models" / "contact" / "bem.py"
    real = type(target).read_bytes

    def read_bytes(self):
        data = real(self)
        return data + b"# edited" if self == target else data

    monkeypatch.setattr(type(target), "read_bytes", read_bytes)
    assert stage_mod.code_hash(REGISTRY["contact"]) != before
