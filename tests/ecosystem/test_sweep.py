"""``tribolmp sweep`` on dask.distributed (issue 16 item 2).

The scenes are tiny (rates given or a measured surface, 16-32 point grids), so
each point costs well under a second; the cluster is a LocalCluster of 2
worker processes on 127.0.0.1.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from tribolmp.campaign import Vary, expand_points, parse_vary, point_id
from tribolmp.cli import main
from tribolmp.errors import ParameterError

pytest.importorskip("distributed")

RATES_SCENE = """
[scene]
name = "tiny rates-given"
seed = 11
[geometry]
profile = "rough"
[roughness]
grid_points = 16
pixel_size = 2e-6
short_cutoff_wavelength = 8e-6
realizations = 2
[load]
normal_force = 10.0
pressures = [1e6, 1e7]
[kinematics]
sliding_velocity = 0.01
duration = 0.005
[rates]
mu = 0.16
diffusion_m2_s = 5.3e-11
transfer_rate = 4.2e6
wear_rate = 2.1e7
layer_depth_m = 4.3e-9
step_length_m = 4.3e-9
step_time_s = 3.5e-7
sliding_velocity_m_s = 5.0
pressure_Pa = 150e6
[topography]
dim = 2
grid_points = 16
pixel_size = 2.5e-9
steps = 20
[tribospectroscopy]
frequency = 65e3
[outputs]
requested = ["rates", "topography", "stiffness", "stick_slip", "tribospectroscopy"]
figures = false
"""


def _measured_scene(tmp_path: Path) -> Path:
    """Return a scene whose contact reads [roughness].surface_file.

    A good x3p, or a corrupt .npy for a failing point.
    """
    from tribolmp.models.topography.measured import write_surface

    h = np.random.default_rng(5).normal(size=(16, 16)) * 0.2e-6
    write_surface(tmp_path / "good.x3p", h, 2e-6)
    (tmp_path / "bad.npy").write_bytes(b"not numpy at all\n")
    scene = tmp_path / "measured.toml"
    scene.write_text(
        '[geometry]\nprofile = "rough"\n'
        '[roughness]\nsurface_file = "good.x3p"\npixel_size = '
        '2e-6\nshort_cutoff_wavelength = 8e-6\nrealizations = 2\n'
        "[load]\nnormal_force = 10.0\npressures = [1e6, 1e7]\n"
        '[outputs]\nrequested = ["stiffness"]\nfigures = false\n'
    )
    return scene


def test_vary_parsing_and_the_point_product():
    v = parse_vary("nanoscale.pressure=50e6,150e6,382e6")
    assert v == Vary("nanoscale", "pressure", (50e6, 150e6, 382e6))
    assert parse_vary("nanoscale.bond_style=mca,plastic").values == ("mca", "plastic")
    pts = expand_points(
        {"scene": {"seed": 3}}, [v, parse_vary("kinematics.sliding_velocity=1,5")], seeds=2
    )
    assert len(pts) == 3 * 2 * 2
    assert {p["seed"] for p in pts} == {3, 4}
    assert len({p["id"] for p in pts}) == len(pts)
    assert point_id({"a.b": 1.0}, 3) == point_id({"a.b": 1.0}, 3) != point_id({"a.b": 1.0}, 4)
    for bad in ("pressure=1,2", "nanoscale.pressure", "nanoscale.pressure="):
        with pytest.raises(ParameterError, match="--vary"):
            parse_vary(bad)
    with pytest.raises(ParameterError, match="--seeds"):
        expand_points({}, [v], seeds=0)


def test_sweep_on_two_workers_json_contract_failing_point_and_figures(tmp_path, capsys):
    scene = _measured_scene(tmp_path)
    out = tmp_path / "sw"
    code = main(
        [
            "sweep",
            str(scene),
            "--vary",
            "load.normal_force=5,10",
            "--vary",
            'roughness.surface_file="good.x3p","bad.npy"',
            "--workers",
            "2",
            "--out",
            str(out),
            "--json",
            "--map",
            "contact.surface_rms_m",
        ]
    )
    captured = capsys.readouterr()
    assert code == 3, captured.err  # some points failed: exit 3, the rest are in the table
    res = json.loads(captured.out)
    assert res["workers"] == 2 and res["wall_time_s"] > 0 and Path(res["table"]).exists()
    pts = res["points"]
    assert len(pts) == 4
    for p in pts:
        assert set(p) >= {"vary", "seed", "status", "values", "message"}
        bad = p["vary"]["roughness.surface_file"] == "bad.npy"
        assert p["status"] == ("failed" if bad else "ok"), p
        if bad:
            assert "\n" not in p["message"] and "bad.npy" in p["message"]
        else:
            # The measured surface's rms, read through SurfaceTopography in each worker.
            assert p["values"]["contact.surface_rms_m"] == pytest.approx(0.2e-6, rel=0.2)
    rows = (out / "sweep.csv").read_text().strip().splitlines()
    assert len(rows) == 1 + 4 and "contact.surface_rms_m [m]" in rows[0]
    table = json.loads((out / "sweep.json").read_text())
    assert len(table["summary"]) == 2  # the two combinations that finished
    assert Path(res["figures"]["map_contact_surface_rms_m"]).stat().st_size > 1000
    # Progress: one line per submitted/finished point and an overall count.
    assert "4/4" in captured.err


def test_sweep_of_a_rates_given_scene_with_seeds_gives_errors_and_mu_figure(tmp_path, capsys):
    scene = tmp_path / "rates.toml"
    scene.write_text(RATES_SCENE)
    out = tmp_path / "sw"
    # The tribospectroscopy frequency is read by that stage only: the points of
    # one force and seed share their topography, contact and macroscale stages.
    code = main(
        [
            "sweep",
            str(scene),
            "--vary",
            "load.normal_force=5,10",
            "--vary",
            "tribospectroscopy.frequency=65e3,130e3",
            "--seeds",
            "2",
            "--workers",
            "2",
            "--out",
            str(out),
            "--json",
            "--quiet",
        ]
    )
    captured = capsys.readouterr()
    assert code == 0, captured.err
    res = json.loads(captured.out)
    assert len(res["points"]) == 8 and all(p["status"] == "ok" for p in res["points"])
    assert {p["seed"] for p in res["points"]} == {11, 12}
    summary = json.loads((out / "sweep.json").read_text())["summary"]
    assert len(summary) == 4 and all(s["n_seeds"] == 2 for s in summary)
    for s in summary:
        assert s["mean"]["macroscale.mu"] == pytest.approx(0.16)  # given in [rates]
        assert s["sem"]["topography.rq"] > 0  # two seeds, two surfaces: a measured spread
    assert Path(res["figures"]["mu_vs_pressure"]).exists()
    # Shared stages are computed once: across the 8 points' reports, every
    # stage key that appears was "computed" by exactly one point, the others
    # that need it report it "cached" (two workers, concurrent).
    computed: dict[str, int] = {}
    users: dict[str, int] = {}
    for p in res["points"]:
        rep = json.loads(
            (out / "points" / point_id(p["vary"], p["seed"]) / "report.json").read_text()
        )
        for name, d in rep["stage_details"].items():
            if d["status"] in ("computed", "cached"):
                computed.setdefault(f"{name}-{d['key']}", 0)
                computed[f"{name}-{d['key']}"] += d["status"] == "computed"
                users[f"{name}-{d['key']}"] = users.get(f"{name}-{d['key']}", 0) + 1
    assert computed and all(n == 1 for n in computed.values()), computed
    assert max(users.values()) > 1, (
        users
    )  # the sweep did share stages (else the check above is empty)


def test_a_killed_sweep_resumes_and_a_second_sweep_reuses_shared_points(tmp_path):
    scene = tmp_path / "rates.toml"
    scene.write_text(RATES_SCENE)
    out = tmp_path / "sw"
    cmd = [
        sys.executable,
        "-m",
        "tribolmp",
        "sweep",
        str(scene),
        "--vary",
        "kinematics.sliding_velocity=0.01,0.02,0.03",
        "--workers",
        "1",
        "--out",
        str(out),
        "--no-figures",
    ]
    proc = subprocess.Popen(
        cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True
    )
    deadline = time.time() + 240
    try:
        while time.time() < deadline and not list((out / "points").glob("*/point.json")):
            time.sleep(0.05)
            assert proc.poll() is None, "the sweep ended before it could be killed"
    finally:
        os.killpg(proc.pid, signal.SIGKILL)  # our own process group: the sweep and its Dask workers
        proc.wait(30)
    done_before = {p.parent.name for p in (out / "points").glob("*/point.json")}
    assert 1 <= len(done_before) < 3, "the kill came too late to test a resume"
    stamps = {p.parent.name: p.stat().st_mtime_ns for p in (out / "points").glob("*/point.json")}

    res = subprocess.run(cmd + ["--json", "--quiet"], capture_output=True, text=True, timeout=300)
    assert res.returncode == 0, res.stderr
    data = json.loads(res.stdout)
    assert data["resumed"] == len(done_before) and all(p["status"] == "ok" for p in data["points"])
    for pid, ns in stamps.items():  # finished points were not run again
        assert (out / "points" / pid / "point.json").stat().st_mtime_ns == ns

    # A second sweep sharing the cache and one velocity: that point's stages come from the cache.
    res2 = subprocess.run(
        [
            sys.executable,
            "-m",
            "tribolmp",
            "sweep",
            str(scene),
            "--vary",
            "kinematics.sliding_velocity=0.02,0.05",
            "--workers",
            "1",
            "--out",
            str(tmp_path / "sw2"),
            "--cache-dir",
            str(out / "cache"),
            "--no-figures",
            "--json",
            "--quiet",
        ],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert res2.returncode == 0, res2.stderr
    for p in json.loads(res2.stdout)["points"]:
        rep = json.loads(
            (
                tmp_path / "sw2" / "points" / point_id(p["vary"], p["seed"]) / "report.json"
            ).read_text()
        )
        statuses = {
            n: d["status"]
            for n, d in rep["stage_details"].items()
            if d["status"] in ("computed", "cached")
        }
        shared = p["vary"]["kinematics.sliding_velocity"] == 0.02
        assert set(statuses.values()) == ({"cached"} if shared else {"computed"}), statuses


def _one() -> int:
    return 1


def test_local_cluster_listens_on_loopback_only_and_serves_resource_tasks():
    """No network: the scheduler, the workers and their HTTP endpoints bind 127.0.0.1.

    On free ports, not a fixed 8787.

    A task that reserves resources (--resources MPI=2, for [nanoscale].ranks = 2) runs on the local
    workers (they are given those resources; without them such a task would wait forever).
    """
    import psutil

    from tribolmp.campaign import make_client

    me = psutil.Process()

    def listening_sockets():
        pids = {me.pid} | {p.pid for p in me.children(recursive=True)}
        return {(c.pid, c.laddr) for c in psutil.net_connections(kind="inet")
                if c.status == psutil.CONN_LISTEN and c.pid in pids}

    # Sockets that earlier tests left in this process tree are not the cluster's: MPICH's
    # singleton init (an in-process LAMMPS session) forks an mpiexec that listens on the host's
    # address until the interpreter exits.  Only the sockets the cluster opens are checked.
    before = listening_sockets()
    client, cluster = make_client(1, resources={"MPI": 2})
    try:
        listening = [laddr for _pid, laddr in listening_sockets() - before]
        assert listening, "found no listening socket of the cluster"
        assert all(laddr.ip == "127.0.0.1" for laddr in listening), listening
        assert client.submit(_one, resources={"MPI": 2}, pure=False).result(timeout=120) == 1
    finally:
        client.close()
        cluster.close()
