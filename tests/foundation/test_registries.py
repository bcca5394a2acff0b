"""Every method registry's functions share one signature (issue 11: one contract per registry).

A registry of *functions* (solvers, schemes) must accept the same arguments
for every name, so that ``method=`` really is a choice.  A registry of
*classes* either shares one constructor signature (schemes) or registers
subclasses of one base class (parameterised laws such as the friction laws:
their constructors differ by design, their interface not).
"""

from __future__ import annotations

import importlib
import inspect
import pkgutil

import pytest

import tribolmp.models
from tribolmp.results import MethodRegistry


def _registries():
    found = {}
    for info in pkgutil.walk_packages(tribolmp.models.__path__, "tribolmp.models."):
        mod = importlib.import_module(info.name)
        for name, obj in vars(mod).items():
            if isinstance(obj, MethodRegistry) and id(obj) not in {id(r) for r in found.values()}:
                found[f"{info.name}.{name}"] = obj
    return found


REGISTRIES = _registries()


def contract_violation(reg: MethodRegistry) -> str:
    """Return why ``reg`` breaks the one-contract rule, or "" when it keeps it."""
    impls = {k: reg._methods[k] for k in reg}
    sigs = {k: str(inspect.signature(f)) for k, f in impls.items()}
    if len(set(sigs.values())) <= 1:
        return ""
    if all(inspect.isclass(f) for f in impls.values()):
        bases = [set(inspect.getmro(c)[1:]) - {object} for c in impls.values()]
        if set.intersection(*bases):
            return ""
        return f"classes with different constructors and no common base: {sigs}"
    return f"signatures differ: {sigs}"


def test_registries_were_found():
    # The walk must see the model registries (a broken walk would make the next test vacuous).
    kinds = {r.kind for r in REGISTRIES.values()}
    assert {"contact", "topography scheme", "stick-slip", "squeeze model"} <= kinds


@pytest.mark.parametrize("name", sorted(REGISTRIES))
def test_one_signature_per_registry(name):
    assert contract_violation(REGISTRIES[name]) == ""


def test_the_check_catches_a_mismatch():
    reg = MethodRegistry("toy")
    reg.register("a")(lambda params, *, rng=None: params)
    reg.register("b")(lambda params, extra, *, rng=None: params)
    assert "signatures differ" in contract_violation(reg)

    class A:
        def __init__(self, x): ...

    class B:
        def __init__(self, y): ...

    cls_reg = MethodRegistry("toy classes")
    cls_reg.register("a")(A)
    cls_reg.register("b")(B)
    assert "no common base" in contract_violation(cls_reg)
