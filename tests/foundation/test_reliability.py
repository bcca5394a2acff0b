"""Issue 12: output folders, locks, one-line errors and honest summaries.

Each test drives the real CLI (a subprocess, like a user) or the real chain,
and each reproduces a failure of the code before issue 12 (named in the
docstring), so it can fail.
"""

from __future__ import annotations

import json
import os
import signal
import stat
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

from tribolmp.locking import DirLock, FolderBusyError, prepare_dir
from tribolmp.scene import scene_path

#: A 3-stage scene that runs in ~1 s of CPU (rates given, MDR on a 32^2 map): these tests are
#: about folders, locks and messages, not physics, so they must not cost a full chain each.
TINY = str(Path(__file__).parent / "data" / "tiny.toml")


def cli(*args, cwd=None, timeout=120, stdin=None):
    """Run ``python -m tribolmp ARGS``; return the CompletedProcess."""
    return subprocess.run(
        [sys.executable, "-m", "tribolmp", *map(str, args)],
        capture_output=True,
        text=True,
        cwd=cwd,
        timeout=timeout,
        stdin=stdin,
    )


def assert_one_line(proc, code):
    """Exit ``code`` with exactly one line on stderr and no traceback."""
    assert proc.returncode == code, (proc.returncode, proc.stderr)
    lines = [ln for ln in proc.stderr.splitlines() if ln.strip()]
    assert len(lines) == 1, proc.stderr
    assert "Traceback" not in proc.stderr


# --- bad output folders: before issue 12 these were FileExistsError/NotADirectoryError tracebacks,
# or (--out "") a run written into the working folder.
@pytest.mark.parametrize(
    "kind",
    [
        "file",
        "under_file",
        "devnull",
        "empty",
        "cache_file",
        "cache_under_file",
        "cache_devnull",
        "cache_empty",
    ],
)
def test_bad_output_folder_is_one_line_exit_2(tmp_path, kind):
    afile = tmp_path / "afile"
    afile.write_text("x")
    args = {
        "file": ["--out", afile],
        "under_file": ["--out", afile / "sub"],
        "devnull": ["--out", os.devnull],
        "empty": ["--out", ""],
        "cache_file": ["--out", tmp_path / "o", "--cache-dir", afile],
        "cache_under_file": ["--out", tmp_path / "o", "--cache-dir", afile / "c"],
        "cache_devnull": ["--out", tmp_path / "o", "--cache-dir", os.devnull],
        "cache_empty": ["--out", tmp_path / "o", "--cache-dir", ""],
    }[kind]
    proc = cli("run", TINY, *args, "--quiet", cwd=tmp_path)
    assert_one_line(proc, 2)
    assert ("--cache-dir" if kind.startswith("cache") else "--out") in proc.stderr
    # nothing was written into the working folder (the "" case used to write report.md here)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["afile"]


def test_prepare_dir_names_the_field(tmp_path):
    f = tmp_path / "f"
    f.write_text("")
    with pytest.raises(Exception, match=r"^\[outputs\]\.dir: expected a folder"):
        prepare_dir(f, "[outputs].dir")
    assert prepare_dir(tmp_path / "a" / "b").is_dir()


# --- locks
HOLD = textwrap.dedent(
    """
    import sys, time
    from tribolmp.locking import DirLock
    lock = DirLock(sys.argv[1]).acquire()
    print("locked", flush=True)
    time.sleep(60)
    """
)


@pytest.fixture
def holder_of():
    """Start processes that take a folder's lock; kill and reap them afterwards."""
    procs = []

    def start(folder):
        proc = subprocess.Popen(
            [sys.executable, "-c", HOLD, str(folder)], stdout=subprocess.PIPE, text=True
        )
        procs.append(proc)
        assert proc.stdout.readline().strip() == "locked"
        return proc

    yield start
    for proc in procs:
        proc.kill()
        proc.wait()
        proc.stdout.close()


def test_second_run_into_a_held_folder_exits_2_naming_the_pid(tmp_path, holder_of):
    """Before issue 12 two runs into one --out both ran and poisoned the folder."""
    out = tmp_path / "out"
    out.mkdir()
    holder = holder_of(out)
    proc = cli("run", TINY, "--out", out, "--quiet")
    assert_one_line(proc, 2)
    assert f"PID {holder.pid}" in proc.stderr
    assert not (out / "report.json").exists()


def test_lock_of_a_killed_process_is_taken_over(tmp_path, holder_of):
    """SIGKILL leaves the lock file behind; the kernel has released the flock, so it is free."""
    holder = holder_of(tmp_path)
    with pytest.raises(FolderBusyError, match=str(holder.pid)):
        DirLock(tmp_path).acquire()
    holder.send_signal(signal.SIGKILL)
    holder.wait()
    assert (tmp_path / ".lock").exists()
    with DirLock(tmp_path):
        assert (tmp_path / ".lock").read_text().split()[0] == str(os.getpid())


def test_waiting_lock_gets_it_when_the_holder_ends(tmp_path, holder_of):
    holder = holder_of(tmp_path)
    t0 = time.monotonic()
    killer = subprocess.Popen(["sh", "-c", f"sleep 1; kill {holder.pid}"])
    with DirLock(tmp_path, wait=True, timeout=30, quiet=True):
        waited = time.monotonic() - t0
    killer.wait()
    assert waited >= 0.8  # it really waited for the holder, it did not just break the lock


def test_two_runs_sharing_a_cache_compute_each_entry_once(tmp_path):
    """Concurrent runs with one --cache-dir: one computes, the other reuses; both succeed."""
    cache = tmp_path / "cache"
    procs = [
        subprocess.Popen(
            [
                sys.executable,
                "-m",
                "tribolmp",
                "run",
                TINY,
                "--out",
                str(tmp_path / f"o{i}"),
                "--cache-dir",
                str(cache),
                "--no-figures",
                "--json",
                "--quiet",
            ],
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        for i in range(2)
    ]
    outs = [p.communicate(timeout=300) for p in procs]
    assert [p.returncode for p in procs] == [0, 0], [o[1] for o in outs]
    statuses = []
    for i in range(2):
        report = json.loads((tmp_path / f"o{i}" / "report.json").read_text())
        statuses.append({s["name"]: s["reason"] for s in report["stages"] if s["ran"]})
    names = statuses[0].keys()
    assert names == statuses[1].keys() and names
    for name in names:
        reused = ["reused from cache" in statuses[i][name] for i in range(2)]
        assert reused.count(True) <= 1  # never both "fresh" results written over each other...
    committed = [p for p in cache.iterdir() if p.is_dir()]
    assert len(committed) == len(names)  # ...and exactly one committed entry per stage
    assert not [p for p in cache.iterdir() if p.name.endswith(".partial")]


# --- the cache never trusts a damaged hand-off file
def test_truncated_cached_file_is_recomputed(tmp_path):
    out = tmp_path / "o"
    assert cli("run", TINY, "--out", out, "--quiet", "--no-figures").returncode == 0
    report = json.loads((out / "report.json").read_text())
    stage_dir = next(
        p for p in (out / "cache").iterdir() if p.name.startswith("contact-") and p.is_dir()
    )
    files = json.loads((stage_dir / "result.json").read_text())["files"]
    victim = stage_dir / sorted(files.values())[0]
    victim.write_bytes(victim.read_bytes()[: victim.stat().st_size // 2])
    proc = cli("run", TINY, "--out", out, "--no-figures")
    assert proc.returncode == 0, proc.stderr
    again = json.loads((out / "report.json").read_text())
    row = next(s for s in again["stages"] if s["name"] == "contact")
    assert "reused from cache" not in row["reason"]  # recomputed, not trusted
    assert len(report["stages"]) == len(again["stages"])


# --- the summary says what was computed and what came from the cache
def test_cached_rerun_says_from_the_cache(tmp_path):
    """Before issue 12 a fully cached rerun printed '3 stage(s) ran'."""
    out = tmp_path / "o"
    first = cli("run", TINY, "--out", out, "--quiet", "--no-figures")
    second = cli("run", TINY, "--out", out, "--quiet", "--no-figures")
    assert first.returncode == second.returncode == 0
    assert "0 stage(s) computed" in second.stdout and "3 from the cache" in second.stdout
    assert "3 stage(s) computed" in first.stdout


# --- files readable by others (normal umask), not mkstemp's 0600
def test_results_are_readable_by_others(tmp_path):
    out = tmp_path / "o"
    env = dict(os.environ)
    proc = subprocess.run(
        [
            "sh",
            "-c",
            f"umask 022 && {sys.executable} -m tribolmp run {TINY} --out {out} "
            "--quiet --no-figures",
        ],
        capture_output=True,
        text=True,
        env=env,
    )
    assert proc.returncode == 0, proc.stderr
    for f in [out / "report.json", *(out / "cache").rglob("result.json")]:
        assert f.stat().st_mode & stat.S_IROTH, f


# --- scene files
def test_empty_scene_file_is_refused(tmp_path):
    """Before issue 12 an empty file (or /dev/null) ran the default of every section."""
    empty = tmp_path / "s.toml"
    empty.write_text("# nothing here\n")
    assert_one_line(cli("check", empty), 2)
    assert_one_line(cli("check", os.devnull), 2)


def test_scene_with_byte_order_mark_is_read(tmp_path):
    """Before issue 12 a UTF-8 BOM gave 'Invalid statement (at line 1, column 1)'."""
    text = Path(TINY).read_text()
    bom = tmp_path / "bom.toml"
    bom.write_bytes(b"\xef\xbb\xbf" + text.encode())
    proc = cli("check", bom)
    assert proc.returncode == 0, proc.stderr


# --- a closed pipe is not a traceback
def test_closed_stdout_pipe_is_quiet():
    """``tribolmp check --json | head`` raised BrokenPipeError before issue 12.

    The read end is closed before the interpreter has even imported tribolmp,
    so the JSON write always meets a closed pipe (no race with a fast reader).
    """
    proc = subprocess.Popen([sys.executable, "-m", "tribolmp", "check", TINY, "--json"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    proc.stdout.close()
    err = proc.stderr.read()
    proc.stderr.close()
    proc.wait(timeout=60)
    assert "Traceback" not in err and "BrokenPipe" not in err, err
    assert proc.returncode == 141  # as a coreutils tool killed by SIGPIPE reports it


# --- bad numbers and absurd physics: one line, never a traceback, never a silent exit 0
@pytest.mark.parametrize(
    "args, code, field",
    [
        # ValueError traceback from numpy's SeedSequence before issue 12
        (
            [
                "contact",
                "rough",
                "--seed=-1",
                "--surface",
                "x.npy",
                "--modulus",
                "1e11",
                "--pressures",
                "1e6",
            ],
            2,
            "--seed",
        ),
        (
            ["tribospec", "simulate", "--contact-stiffness", "0"],
            2,
            "--contact-stiffness",
        ),  # was "not given"
        # a 1 m indentation of a 1 cm sphere gave a contact radius of 10 R with exit 0
        (
            [
                "contact",
                "axisymmetric",
                "--radius",
                "0.01",
                "--modulus",
                "1e11",
                "--indentation",
                "1",
            ],
            2,
            "indentation",
        ),
        # a 1e-30 m gap gave 1.9e21 N with exit 0
        (
            [
                "lubrication",
                "squeeze",
                "--radius",
                "1e-3",
                "--viscosity",
                "0.1",
                "--gap",
                "1e-30",
                "--velocity",
                "1e-3",
            ],
            2,
            "--gap",
        ),
        # the explicit scheme ended at a gap of -0.53 m with status -1 and exit 0
        (
            [
                "lubrication",
                "approach",
                "--radius",
                "1e-3",
                "--viscosity",
                "0.1",
                "--load",
                "10",
                "--gap",
                "1e-6",
                "--duration",
                "1",
                "--steps",
                "10",
                "--scheme",
                "explicit",
                "--json",
            ],
            3,
            "explicit",
        ),
    ],
)
def test_absurd_input_is_one_line_with_the_right_exit_code(tmp_path, args, code, field):
    proc = cli(*args, cwd=tmp_path)
    assert_one_line(proc, code)
    assert field in proc.stderr


def test_plot_path_checked_before_the_fit(tmp_path):
    """``tribospec fit --plot /nonexistent/x.png`` was a traceback after the whole bootstrap."""
    afile = tmp_path / "f"
    afile.write_text("")
    data = tmp_path / "d.csv"
    data.write_text("amplitude_m,force_N\n1e-9,1.0\n2e-9,0.9\n4e-9,0.7\n8e-9,0.5\n1.6e-8,0.3\n3.2e-8,0.2\n")
    proc = cli("tribospec", "fit", data, "--plot", afile / "x.png", cwd=tmp_path)
    assert_one_line(proc, 2)
    assert "--plot" in proc.stderr


def test_doubtful_sphere_contact_warns_but_runs(tmp_path):
    """a/R = 0.45: Hertz's paraboloid is doubtful, not impossible: exit 0 with one warning line."""
    proc = cli(
        "contact",
        "axisymmetric",
        "--radius",
        "0.01",
        "--modulus",
        "1e11",
        "--indentation",
        "2e-3",
        "--json",
    )
    assert proc.returncode == 0
    assert proc.stderr.count("warning:") == 1
    assert json.loads(proc.stdout)["warnings"]
    quiet = cli(
        "contact", "axisymmetric", "--radius", "0.01", "--modulus", "1e11", "--indentation", "2e-6"
    )
    assert quiet.returncode == 0 and quiet.stderr == ""  # a/R = 0.014: no warning


# --- check refuses what run would refuse later
@pytest.mark.parametrize(
    "text, field",
    [
        # failed after ~35 s of LAMMPS before issue 12
        ("[load]\npressures = []\n", "[load].pressures"),
        # a 2^20-point side: the contact stage ran out of memory (MDR reads the whole
        # map; auto's BEM would resample a generated surface to its measured mesh)
        (
            '[geometry]\nprofile = "rough"\n[roughness]\ngrid_points '
            '= 1048576\n[contact]\nmethod = "mdr"\n',
            "[roughness].grid_points",
        ),
        ("[topography]\ndim = 2\ngrid_points = 65536\n", "[topography].grid_points"),
    ],
)
def test_check_refuses_what_run_would(tmp_path, text, field):
    scene = tmp_path / "s.toml"
    scene.write_text(text)
    proc = cli("check", scene)
    assert_one_line(proc, 2)
    assert field in proc.stderr


def test_check_reads_the_surface_file_a_scene_names(tmp_path):
    """A corrupted height map used to pass check and fail in the contact stage."""
    bad = tmp_path / "bad.npy"
    bad.write_bytes(b"\x93NUMPY this is not an array")
    scene = tmp_path / "s.toml"
    scene.write_text(
        '[geometry]\nprofile = "rough"\n[roughness]\nsurface_file = "bad.npy"\npixel_size = 1e-6\n'
    )
    proc = cli("check", scene)
    assert_one_line(proc, 2)
    assert "[roughness].surface_file" in proc.stderr
    for name in ("default", "lubricated", "polishing", "rates_given"):
        assert cli("check", scene_path(name)).returncode == 0, name


# --- long loops show progress
def test_progress_is_silent_for_short_jobs_and_gives_an_eta_for_long_ones(monkeypatch):
    import io

    from tribolmp import progress as prog

    clock = iter([0.0, 0.5, 1.0])  # construction, then two calls within the first interval
    monkeypatch.setattr(prog.time, "monotonic", lambda: next(clock))
    out = io.StringIO()
    p = prog.Progress("job", total=10, stream=out)
    p(0.5)
    p(1.0)
    assert out.getvalue() == ""
    clock = iter([0.0, 3.0, 6.0])
    p = prog.Progress("job", total=10, stream=out)
    p(0.25)
    p(1.0)
    lines = out.getvalue().splitlines()
    assert lines[0] == "job:  25 % (2/10 steps), ETA 9 s"  # 3 s for a quarter: 9 s to go
    assert lines[1].startswith("job: 100 %") and "done in 6 s" in lines[1]


def test_eq23_evolve_reports_progress_to_the_end():
    import numpy as np

    from tribolmp.models.topography import TopographyParams, evolve

    seen = []
    p = TopographyParams(
        dim=1,
        grid_points=64,
        pixel_size=1e-9,
        d0=1e-12,
        dx_noise=1e-30,
        dz=1e-30,
        mu=1.0,
        dt=1e-3,
        steps=1000,
    )
    evolve(p, rng=np.random.default_rng(0), progress=lambda f, what="": seen.append(f))
    assert 100 <= len(seen) <= 1001 and seen[-1] == 1.0 and seen == sorted(seen)


# --- surfaces no contact model can treat, and sidecars that lie
def _surface(tmp_path, name, h, meta):
    import numpy as np

    np.save(tmp_path / f"{name}.npy", h)
    if meta is not None:
        (tmp_path / f"{name}.json").write_text(json.dumps(meta))
    return tmp_path / f"{name}.npy"


@pytest.mark.parametrize("method", ["bem", "mdr"])
def test_overflowing_heights_are_refused(tmp_path, method):
    """Heights x 1e300 (overflow).

    Before issue 12: ZeroDivisionError (BEM) or a stiffness of 0 with exit 0 (MDR).
    """
    import numpy as np

    h = np.random.default_rng(0).standard_normal((32, 32)) * 1e-6
    f = _surface(tmp_path, "big", h * 1e300, {"pixel_size_m": 1e-6})
    proc = cli(
        "contact",
        "rough",
        "--surface",
        f,
        "--modulus",
        "1e11",
        "--pressures",
        "1e6",
        "--method",
        method,
    )
    assert_one_line(proc, 2)
    assert "surface" in proc.stderr
    ok = _surface(tmp_path, "ok", h, {"pixel_size_m": 1e-6})
    good = cli(
        "contact",
        "rough",
        "--surface",
        ok,
        "--modulus",
        "1e11",
        "--pressures",
        "1e6",
        "--method",
        method,
    )
    assert good.returncode == 0, good.stderr  # the same surface at its real scale is fine


def test_sidecar_with_another_shape_is_refused(tmp_path):
    """A sidecar saying 128^2 on a 32^2 array was silently used before issue 12."""
    import numpy as np

    f = _surface(tmp_path, "s", np.zeros((32, 32)), {"pixel_size_m": 1e-6, "shape": [128, 128]})
    proc = cli("contact", "rough", "--surface", f, "--modulus", "1e11", "--pressures", "1e6")
    assert_one_line(proc, 2)
    assert "shape" in proc.stderr


def test_scene_surface_without_sidecar_says_where_its_pixel_size_comes_from(tmp_path):
    import numpy as np

    _surface(tmp_path, "s", np.random.default_rng(1).standard_normal((32, 32)) * 1e-7, None)
    scene = tmp_path / "scene.toml"
    scene.write_text(
        '[geometry]\nprofile = "rough"\n[roughness]\nsurface_file = "s.npy"\npixel_size = 1e-6\n'
    )
    proc = cli("check", scene)
    assert proc.returncode == 0, proc.stderr
    assert "no sidecar" in proc.stdout and "[roughness].pixel_size = 1e-06 m" in proc.stdout


# --- a full disk: one line, exit 3, and a rerun finishes (nothing poisoned)
def test_full_disk_is_one_line_and_the_folder_recovers(tmp_path):
    """RLIMIT_FSIZE makes every write past 4 kB fail with EFBIG, as a full disk fails with ENOSPC.

    (CPython ignores SIGXFSZ, so the write raises instead of killing the process.)
    """
    import resource

    def small_files():
        resource.setrlimit(resource.RLIMIT_FSIZE, (4000, 4000))

    out = tmp_path / "o"
    cmd = [
        sys.executable,
        "-m",
        "tribolmp",
        "run",
        TINY,
        "--out",
        str(out),
        "--quiet",
        "--no-figures",
    ]
    proc = subprocess.run(cmd, preexec_fn=small_files, capture_output=True, text=True, timeout=300)
    assert_one_line(proc, 3)
    assert str(out) in proc.stderr  # names the file it could not write
    again = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    assert again.returncode == 0, again.stderr
    report = json.loads((out / "report.json").read_text())
    ran = {s["name"] for s in report["stages"] if s["ran"]}
    assert report["complete"] and ran == {"contact", "macroscale", "tribospectroscopy"}


def _can_mount_tmpfs(path) -> bool:
    probe = subprocess.run(
        ["mount", "-t", "tmpfs", "-o", "size=1m", "tmpfs", str(path)], capture_output=True
    )
    if probe.returncode == 0:
        subprocess.run(["umount", str(path)], check=True)
        return True
    return False


def test_read_only_cache_dir_is_one_line(tmp_path):
    """A cache folder on a read-only file system (a root user ignores chmod, so mount one)."""
    ro = tmp_path / "ro"
    ro.mkdir()
    if not _can_mount_tmpfs(ro):
        pytest.skip("needs permission to mount a read-only tmpfs (root with CAP_SYS_ADMIN)")
    subprocess.run(["mount", "-t", "tmpfs", "-o", "size=1m,ro", "tmpfs", str(ro)], check=True)
    try:
        proc = cli("run", TINY, "--out", tmp_path / "o", "--cache-dir", ro / "cache", "--quiet")
        assert_one_line(proc, 2)
        assert "--cache-dir" in proc.stderr
    finally:
        subprocess.run(["umount", str(ro)], check=True)


# --- the nanoscale stage says what it will cost before LAMMPS starts
def test_nanoscale_cost_estimate_matches_the_built_system(tmp_path, monkeypatch):
    """Steps exactly, automata within 25 % of the system prepare() builds.

    A measured rate is used next time.
    """
    from tribolmp.chain.stages import nanoscale as stage
    from tribolmp.lammps import mca
    from tribolmp.lammps.mca.prepare import prepare
    from tribolmp.scene import default_scene

    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    scene = default_scene()
    est = stage.estimate_wall_time(scene)
    assert "shipped" in est["rate_source"]
    prepare(mca.params_from_scene(scene), tmp_path / "run", 1, {})
    meta = json.loads((tmp_path / "run" / "meta.json").read_text())
    assert abs(est["steps"] - meta["steps"]) <= 1
    # the count is the bodies' area over the close-packed cell: it misses the rough edges (~15 %)
    assert abs(est["atoms"] / meta["n_atoms"] - 1) < 0.25
    # a run measured 2e6 automaton-steps/s over 40 s: the next estimate of
    # the same scene is that run
    meta.update(atom_steps_per_s=2e6, wall_time_s=meta["n_atoms"] * meta["steps"] / 2e6)
    (tmp_path / "run" / "meta.json").write_text(json.dumps(meta))
    stage._remember_throughput(scene, tmp_path / "run" / "meta.json")
    again = stage.estimate_wall_time(scene)
    assert "measured" in again["rate_source"]
    assert again["seconds"] == pytest.approx(
        meta["wall_time_s"], rel=0.02
    )  # 2 %: steps rounded vs exact
    notes = stage.STAGE.preflight(scene, None)
    assert len(notes) == 1 and "estimated wall time" in notes[0]
