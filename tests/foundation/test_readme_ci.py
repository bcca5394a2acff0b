"""The README's two commands and CI stay in step (CI runs the test command verbatim)."""

from __future__ import annotations

import re

from tests.conftest import ROOT


def _quick_start_block() -> list[str]:
    text = (ROOT / "README.md").read_text()
    m = re.search(r"^```(?:sh|bash|console)?\s*\n(.*?)^```", text, re.S | re.M)
    assert m, "README has no fenced shell block"
    return [ln for ln in m.group(1).splitlines() if ln.strip() and not ln.lstrip().startswith("#")]


def test_readme_opens_with_two_commands():
    lines = _quick_start_block()
    assert len(lines) == 2, lines
    setup, tests = lines
    assert "pip install" in setup and "tribolmp " in setup
    assert "[test]" in tests and "pytest" in tests


def test_ci_runs_the_readme_test_command_verbatim():
    _, tests = _quick_start_block()
    ci = (ROOT / ".ci" / "run").read_text()
    assert tests in ci
    # exit code 5 (no tests collected) must fail: the script stops on any non-zero status
    assert "set -euo pipefail" in ci


def test_ci_runs_ruff_after_the_readme_test_command():
    _, tests = _quick_start_block()
    ci = (ROOT / ".ci" / "run").read_text()
    assert "ruff check" in ci and ci.index("ruff check") > ci.index(tests)
    import tomllib

    project = tomllib.loads((ROOT / "pyproject.toml").read_text())
    assert any(d.startswith("ruff") for d in project["project"]["optional-dependencies"]["test"])
    assert {"F", "E", "W", "D", "I"} <= set(project["tool"]["ruff"]["lint"]["select"])
    assert project["tool"]["ruff"]["lint"]["pydocstyle"]["convention"] == "numpy"
