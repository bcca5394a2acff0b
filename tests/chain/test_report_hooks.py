"""The report composes what each stage says about itself; it holds no stage-specific code.

A stage publishes top-level report.json fields (``report_keys`` / ``report_fields``) and the
lines of report.md's narrative (``summary``).  A toy stage with both hooks, added to a copy of
the registry, must appear in both files with no edit of the report; the generic report module
must not name any registered stage or a stage's field.
"""

from __future__ import annotations

import json
import re
import tokenize
from pathlib import Path

from tests.chain.test_runner import _scene, calls  # noqa: F401  (fixture: counting stage functions)
from tests.chain.test_toy_stage import Toy
from tribolmp.chain import planner as planner_mod
from tribolmp.chain import runner as runner_mod
from tribolmp.chain.registry import REGISTRY
from tribolmp.chain.stage import Decision, Demand

NARRATIVE = "## What ran, from which inputs, under which assumptions"


class Noting(Toy):
    """The toy stage, telling the report about itself."""

    name = "noting"
    figures = ()
    report_keys = ("toy_bytes",)

    def report_fields(self, values):
        """Publish the number of bytes the toy read as a top-level field."""
        return {"toy_bytes": values.get("bytes")}

    def summary(self, values):
        """Say how many bytes the toy read."""
        return [f"- **Toy**: read {values['bytes']} bytes of the stiffness hand-off."]


class Silent(Toy):
    """A toy stage with report hooks that its plan always skips."""

    name = "silent"
    figures = ()
    report_keys = ("silent_field",)

    def plan(self, scene, demand: Demand) -> Decision:
        """Never run."""
        return self.skip("silent: never runs")

    def summary(self, values):
        """Say something that must not appear: the stage has no results."""
        return ["- **Silent**: this line must not be in the report."]


def test_stage_report_hooks_reach_report_json_and_md(tmp_path, calls):  # noqa: F811
    out = tmp_path / "run"
    registry = planner_mod.REGISTRY.inserted(Noting(), after="macroscale").inserted(
        Silent(), after="noting"
    )
    run = runner_mod.run_chain(_scene(), out, quiet=True, figures=False, registry=registry)
    assert run.entries["noting"].status == "computed"
    rep = json.loads((out / "report.json").read_text())
    n = rep["results"]["noting"]["values"]["bytes"]
    assert n > 0 and rep["toy_bytes"] == n
    # A stage that did not run publishes its keys as null (a stable report.json shape) and
    # says nothing in the narrative.
    assert "silent" not in rep["results"] and rep["silent_field"] is None
    md = (out / "report.md").read_text()
    head, _, narrative = md.partition(NARRATIVE)
    assert narrative, "no narrative section although a stage has something to say"
    assert f"- **Toy**: read {n} bytes of the stiffness hand-off." in narrative.split("## ")[0]
    assert "**Silent**" not in md
    # The existing top-level fields are unchanged by the new stage.
    base = runner_mod.run_chain(_scene(), tmp_path / "base", quiet=True, figures=False)
    assert base.complete
    keys = list(json.loads((tmp_path / "base" / "report.json").read_text()))
    assert [k for k in rep if k not in ("toy_bytes", "silent_field")] == keys


def test_skipped_stage_publishes_null(tmp_path, calls):  # noqa: F811
    registry = planner_mod.REGISTRY.inserted(Silent(), after="macroscale")
    runner_mod.run_chain(_scene(), tmp_path, quiet=True, figures=False, registry=registry)
    rep = json.loads((tmp_path / "report.json").read_text())
    assert "silent_field" in rep and rep["silent_field"] is None


def test_topography_publishes_the_running_in_contract_field():
    topo = REGISTRY["topography"]
    series = {"rq_m": [1e-6, 9e-7]}
    assert topo.report_fields({"running_in": series}) == {"running_in": series}
    assert topo.report_fields({}) == {"running_in": None}  # issue 15: the key is always there


def code_text(path: Path) -> str:
    """Return the names and string literals of a Python file (its comments left out)."""
    with open(path) as fh:
        toks = tokenize.generate_tokens(fh.readline)
        return " ".join(t.string for t in toks if t.type in (tokenize.NAME, tokenize.STRING))


def test_report_module_names_no_stage():
    # Everything stage-specific lives in the stage files: the report only composes.
    src = code_text(Path(runner_mod.__file__).parent / "report.py")
    names = set(REGISTRY.names) | {k for s in REGISTRY for k in s.report_keys}
    found = sorted(n for n in names if re.search(rf"\b{re.escape(n)}\b", src))
    assert not found, f"report.py names stages or their fields: {found}"
