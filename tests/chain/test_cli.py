"""`tribolmp run` / `tribolmp bench` command-line contracts: one-line errors, plan output, check."""

from __future__ import annotations

import pytest

from tests.conftest import assert_one_line_error
from tribolmp.scene import scene_path

EXAMPLES = ["default", "lubricated", "polishing", "rates_given"]


@pytest.mark.parametrize("name", EXAMPLES)
def test_check_accepts_every_example_scene(cli, name):
    res = cli("check", scene_path(name))
    assert res.returncode == 0, res.stderr


def test_plan_json_lists_every_stage(cli):
    res = cli("run", scene_path("lubricated"), "--plan", "--json")
    assert res.returncode == 0, res.stderr
    plan = {s["name"]: s for s in res.json()["plan"]}
    assert list(plan) == [
        "nanoscale",
        "topography",
        "contact",
        "lubrication",
        "macroscale",
        "tribospectroscopy",
    ]
    assert plan["lubrication"]["run"] and not plan["nanoscale"]["run"]


def _write(tmp_path, text):
    path = tmp_path / "scene.toml"
    path.write_text(text)
    return path


def test_contradictory_sections_one_line_error(cli, tmp_path):
    path = _write(tmp_path, "[nanoscale]\n[rates]\nmu = 0.2\n")
    res = cli("run", path, "--out", tmp_path / "o")
    assert_one_line_error(res, "[rates]", "not both")
    assert not (tmp_path / "o").exists(), "nothing may run for an invalid scene"


def test_missing_section_one_line_error(cli, tmp_path):
    path = _write(tmp_path, '[outputs]\nrequested = ["lubrication"]\n')
    assert_one_line_error(cli("run", path, "--out", tmp_path / "o"), "[lubricant]")


def test_snapshot_without_nanoscale_one_line_error(cli, tmp_path):
    path = _write(tmp_path, '[rates]\n[outputs]\nrequested = ["mca_snapshot"]\n')
    assert_one_line_error(cli("run", path, "--out", tmp_path / "o"), "[nanoscale]", "mca_snapshot")


def test_bad_value_one_line_error(cli, tmp_path):
    path = _write(tmp_path, "[contact]\ntolerance = -1\n")
    assert_one_line_error(cli("run", path), "[contact].tolerance")


def test_unknown_force_stage_one_line_error(cli):
    assert_one_line_error(cli("run", "--force", "bogus"), "--force")


def test_missing_scene_file_one_line_error(cli, tmp_path):
    assert_one_line_error(cli("run", tmp_path / "nope.toml"), "nope.toml")


def test_bench_collects_existing_tables(cli, tmp_path):
    bench = tmp_path / "benchmarks"
    (bench / "results").mkdir(parents=True)
    (bench / "toy.py").write_text("def main(argv=None):\n    return 0\n")
    (bench / "results" / "toy.csv").write_text("n,time_s,rel_error\n64,0.5,0.1\n128,2.0,0.025\n")
    (bench / "results" / "other.csv").write_text("n\n1\n")  # belongs to no script: not collected
    res = cli("bench", "--benchmarks", bench, "--out", tmp_path / "b", "--json")
    assert res.returncode == 0, res.stderr
    data = res.json()
    (entry,) = data["benchmarks"]
    assert entry["name"] == "toy" and entry["tables"][0]["rows"] == [
        ["64", "0.5", "0.1"],
        ["128", "2.0", "0.025"],
    ]
    md = (tmp_path / "b" / "bench.md").read_text()
    assert "| 128 | 2 | 0.025 |" in md  # numbers shortened to 4 significant digits in markdown
    long_rows = (tmp_path / "b" / "bench.csv").read_text().splitlines()
    assert (
        long_rows[0] == "benchmark,file,row,column,value"
        and "toy,toy.csv,1,rel_error,0.025" in long_rows
    )


def test_bench_run_reports_a_failing_benchmark(cli, tmp_path):
    bench = tmp_path / "benchmarks"
    bench.mkdir()
    (bench / "ok.py").write_text(
        "import pathlib\n"
        "def main(argv=None):\n"
        "    assert argv == ['--quick']\n"
        "    d = pathlib.Path(__file__).parent / 'results'; d.mkdir(exist_ok=True)\n"
        "    (d / 'ok.csv').write_text('n,err\\n8,0.5\\n')\n"
        "    return 0\n"
    )
    (bench / "bad.py").write_text("def main(argv=None):\n    raise RuntimeError('kaput')\n")
    res = cli("bench", "--run", "--benchmarks", bench, "--out", tmp_path / "b")
    # Progress lines go to stderr too; the failure itself is the last line, without a traceback.
    assert res.returncode == 3 and "Traceback" not in res.stderr
    assert "failed: bad" in res.stderr.strip().splitlines()[-1]
    md = (tmp_path / "b" / "bench.md").read_text()
    assert "| 8 | 0.5 |" in md and "kaput" in md


def test_workflow_script_plans_the_default_scene():
    import subprocess
    import sys
    from pathlib import Path

    script = Path(__file__).resolve().parents[2] / "workflows" / "multiscale_chain.py"
    proc = subprocess.run(
        [sys.executable, str(script), "--plan"], capture_output=True, text=True, timeout=120
    )
    assert proc.returncode == 0, proc.stderr
    lines = proc.stdout.splitlines()
    assert [ln.split()[0] for ln in lines] == [
        "nanoscale",
        "topography",
        "contact",
        "lubrication",
        "macroscale",
        "tribospectroscopy",
    ]
    assert lines[3].split()[1] == "skip" and lines[0].split()[1] == "RUN"
