"""The import graph of ``tribolmp/`` runs downward only (issue 11).

Layers, bottom to top (STYLE: foundations <- scene <- models <- analysis/lammps
<- chain <- cli)::

    0 foundations   tribolmp/__init__, errors, units, rng, params, jsonio, results, records,
                    environment, benchmarking, locking, progress, resources
    1 scene         tribolmp.scene
    2 models        tribolmp.models
    3 analysis, lammps  (lammps may call the analysis; the analysis imports neither lammps
                        nor the models)
    4 chain         tribolmp.chain
    5 cli           tribolmp.cli, tribolmp.__main__

A module may import its own layer or lower ones.  The graph is built from the
source (every ``import``/``from ... import``, at module level or inside
functions, including ``TYPE_CHECKING`` blocks), so lazy imports count too.  The
chain must not use ``importlib`` (stages import their models with plain imports,
so the import graph, IDEs and the cache key see every dependency), and only
``tribolmp.lammps`` imports the third-party ``lammps`` module.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2] / "tribolmp"

FOUNDATIONS = {
    "tribolmp",
    "errors",
    "units",
    "rng",
    "params",
    "jsonio",
    "results",
    "records",
    "environment",
    "benchmarking",
    "locking",
    "progress",
    "resources",
}
LAYER = {"scene": 1, "models": 2, "analysis": 3, "lammps": 3, "chain": 4, "cli": 5, "__main__": 5,
         # eco (issue 16): campaigns (Dask sweep) and the notebook API
         # compose the chain, like the CLI.
         "campaign": 5, "notebook": 5}
#: Downward pairs that are still forbidden (importer package, imported package): the analysis reads
#: LAMMPS output files only and validates with the foundations, not with the models.
FORBIDDEN_PAIRS = {("analysis", "lammps"), ("analysis", "models")}


def _module_name(path: Path, root: Path) -> str:
    parts = list(path.relative_to(root.parent).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(parts)


def _top(module: str) -> str:
    """First package below ``tribolmp`` (``"tribolmp"`` itself for the top-level package)."""
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else "tribolmp"


def _layer(module: str) -> int:
    top = _top(module)
    if top in FOUNDATIONS:
        return 0
    try:
        return LAYER[top]
    except KeyError:
        raise AssertionError(
            f"{module}: package {top!r} has no layer; add it to this test's table"
        ) from None


def imports_of(path: Path, root: Path) -> list[tuple[int, str]]:
    """Return ``(line, imported module)`` of every import in ``path`` (relative ones resolved)."""
    mod = _module_name(path, root)
    package = mod if path.name == "__init__.py" else mod.rpartition(".")[0]
    out = []
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            out += [(node.lineno, a.name) for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[: len(package.split(".")) - (node.level - 1)]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            out.append((node.lineno, target))
            for a in node.names:  # "from . import x" imports the submodule x, when x is one
                sub = root.parent.joinpath(*f"{target}.{a.name}".split("."))
                if sub.with_suffix(".py").is_file() or (sub / "__init__.py").is_file():
                    out.append((node.lineno, f"{target}.{a.name}"))
    return out


def violations(root: Path) -> list[str]:
    """List upward imports, importlib in the chain, ``lammps`` imports outside tribolmp.lammps."""
    found = []
    for path in sorted(root.rglob("*.py")):
        mod = _module_name(path, root)
        where = f"{path.relative_to(root.parent)}"
        for line, target in imports_of(path, root):
            if target == "lammps" or target.startswith("lammps."):
                if _top(mod) != "lammps":
                    found.append(
                        f"{where}:{line}: imports the lammps module outside tribolmp/lammps"
                    )
                continue
            if _top(mod) == "chain" and (target == "importlib" or target.startswith("importlib.")):
                found.append(f"{where}:{line}: importlib in the chain (use a plain import)")
                continue
            if not (target == "tribolmp" or target.startswith("tribolmp.")):
                continue
            a, b = _top(mod), _top(target)
            if a == b:
                continue
            if _layer(target) > _layer(mod) or (a, b) in FORBIDDEN_PAIRS:
                found.append(
                    f"{where}:{line}: {mod} (layer {_layer(mod)}) imports {target} "
                    f"(layer {_layer(target)})"
                )
        if _top(mod) == "chain":
            text = path.read_text()
            for i, row in enumerate(text.splitlines(), 1):
                if "__import__(" in row or "import_module(" in row:
                    found.append(f"{where}:{i}: dynamic import in the chain")
    return found


def test_tribolmp_imports_run_downward_only():
    bad = violations(ROOT)
    assert not bad, "upward or dynamic imports:\n" + "\n".join(bad)


def _fake_tree(tmp_path: Path, files: dict[str, str]) -> Path:
    root = tmp_path / "tribolmp"
    for rel, text in {"__init__.py": "", "errors.py": "", **files}.items():
        p = root / rel
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_text(text)
        # every folder is a package
        for parent in p.relative_to(root).parents:
            init = root / parent / "__init__.py"
            if not init.exists():
                init.write_text("")
    return root


@pytest.mark.parametrize(
    ("files", "expected"),
    [
        (
            {"scene/fields.py": "from ..models.base import describe_range\n"},
            "imports tribolmp.models.base",
        ),
        ({"chain/cache.py": "def f():\n    from ..cli import _clean\n"}, "imports tribolmp.cli"),
        ({"analysis/x.py": "import tribolmp.models.base\n"}, "imports tribolmp.models.base"),
        ({"models/m.py": "from ..chain import runner\n"}, "imports tribolmp.chain"),
        ({"models/m.py": "from ..lammps import session\n"}, "imports tribolmp.lammps"),
        ({"analysis/y.py": "from ..lammps import mca\n"}, "imports tribolmp.lammps"),
        ({"chain/s.py": "import importlib\n"}, "importlib in the chain"),
        ({"chain/s.py": "m = __import__('tribolmp.models')\n"}, "dynamic import in the chain"),
        ({"models/m.py": "import lammps\n"}, "lammps module outside"),
    ],
)
def test_checker_catches_each_kind_of_violation(tmp_path, files, expected):
    # The checker itself must be able to fail: each planted violation is reported.
    bad = violations(_fake_tree(tmp_path, files))
    assert any(expected in b for b in bad), bad


def test_checker_accepts_downward_imports(tmp_path):
    ok = {
        "scene/s.py": "from ..params import param\n",
        "models/m.py": "from ..scene import Scene\nfrom ..records import Rates\n",
        "lammps/l.py": "import lammps\nfrom ..analysis import rates\nfrom ..models import base\n",
        "chain/c.py": "from ..models import m\nfrom ..lammps import l\n",
        "cli/k.py": "import importlib\nfrom ..chain import c\n",
        "params.py": "",
        "records.py": "",
    }
    assert violations(_fake_tree(tmp_path, ok)) == []
