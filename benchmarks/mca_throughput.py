"""Throughput of the MCA interaction laws and of the friction deck's interfaces.

Laws compared: mca and bpm/spring/plastic (the goal of issue 13 is stated against it), and
bpm/rotational, LAMMPS's own link law with a tangential and rotational history (normal, shear,
bending and twisting springs): the nearest native counterpart of an MCA link, which also
carries plasticity and a many-body stress (``--no-rotational`` leaves it out).

Default (law comparison, issue 13): the same periodic lattice block (2D hexagonal and 3D FCC,
d = 2.5 nm steel, thermal noise, sheared at a constant tilt velocity through yield) runs
``lammps_inputs/mca_block.in`` with the ``mca`` plugin law and with today's
``bpm/spring/plastic`` links (granular hooke contacts, unlimited ``fix bond/create``), each for a
loop of >= 10 s of LAMMPS time (calibrated by a short first run, with a margin; every row of a
system then runs the same number of steps, the largest calibrated one, so that all cover the
same phase of the shear), on 1 rank.  Automaton-steps per second come from LAMMPS's
``Loop time``; ``ratio`` is mca / bpm on the same system (goal >= 0.7).
Each law runs at its own stable timestep (both 0.1 sqrt(m/k) of their stiffest spring), so the
table also gives simulated ns per wall hour.

``--interfaces`` (the former benchmark):

For three system sizes (~2k, ~10k, ~40k automata, 2D, d = 2.5 nm, steel) the
same deck ``lammps_inputs/mca_friction.in`` with the same data file and
variables is run

* through :class:`tribolmp.lammps.LammpsSession` (the Python interface), 1 rank;
* with the wheel's ``lmp`` launcher, 1 rank;
* through the Python interface under ``mpiexec -n 2``.

Atom-steps per second come from LAMMPS's own ``Loop time`` (setup excluded),
so the three are compared on the time-stepping alone.  The "error" column is
the largest relative difference of the friction.csv rows of the run against
the 1-rank Python run: 0 means bit-identical output (expected for the
``lmp`` binary, which runs the same code; 2 ranks sum forces in another order,
so they drift apart over the run -- statistical equality of mu is a slow test).

The runs start from the built state, i.e. while the slider approaches and
starts sliding (little bond turnover); heavy turnover later in a run lowers
throughput by up to ~2.5x (issue 7's feasibility numbers).

The machine is shared: ``uptime``'s load average is recorded next to each row.

``--reference-plugin SO [--reference-label NAME]`` adds a third row per system: the mca law
with another build of the plugin (e.g. the sources of an older commit compiled into another
cache folder), timed in the same run, so that a before/after ratio shares the machine's load.
``--reference-settings old`` runs that row with the block deck's settings before the plugin had
its own integrator (``fix nve/bpm/sphere``, ghost cutoff 3 d, ``newton on``), which a plugin
older than ``fix nve/mca`` needs; ``current`` (default) with today's.

``--friction``: the same two laws (and the reference build, if given) on the friction deck's
system of the ``default`` preset (2D and 3D: slider, two rough bodies, base), prepared as
``tribolmp mca run`` prepares it and run from the built state; CSV
``mca_throughput_friction.csv``.

``--repeat N`` (default 3): the timed runs of a system are repeated N times, interleaved
across its rows (bpm, mca, reference, bpm, mca, ...), and each row reports its fastest run
(``loop_s``; ``loop_s_median`` beside it): on the shared machine other jobs take memory
bandwidth for minutes at a time, and one run per row compared different minutes.

Usage: ``python benchmarks/mca_throughput.py [--quick] [--out CSV]`` (laws),
``python benchmarks/mca_throughput.py --friction [--reference-plugin SO]``,
``python benchmarks/mca_throughput.py --interfaces [--quick]``.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

from tribolmp.benchmarking import write_csv

#: (label, box_length m, body_height m, steps)
SIZES = (("2k", 150e-9, 30e-9, 6000), ("10k", 400e-9, 62e-9, 1500), ("40k", 800e-9, 125e-9, 400))
QUICK = (("2k", 150e-9, 30e-9, 1500), ("10k", 400e-9, 62e-9, 300))

_LOOP = re.compile(r"Loop time of ([0-9.eE+-]+) on (\d+) procs for (\d+) steps with (\d+) atoms")
_CPU = re.compile(r"([0-9.]+)% CPU use with")
#: The short calibration run includes the first neighbour build and the first touch of the
#: arrays, so it underestimates a law's steady rate: session 20 measured loops of 9.4 s and
#: 9.3 s for a 12 s target (rate 1.28-1.29x the calibrated one).  The step counts are scaled by
#: this margin so that every timed loop is >= MIN_LOOP_S; _short_loops names any that is not.
_CAL_MARGIN = 1.3
#: shortest timed loop that means something (issue 13: >= 10 s each)
MIN_LOOP_S = 10.0


def _short_loops(rows: list[dict]) -> None:
    """Print one warning line per row whose fastest loop is below MIN_LOOP_S."""
    for r in rows:
        if r["loop_s"] < MIN_LOOP_S:
            how = f" with {r['integrator']}" if r.get("integrator") else ""
            print(
                f"warning: {r['dim']}D {r['law']}{how} ({r['automata']} automata): loop "
                f"{r['loop_s']:.1f} s < {MIN_LOOP_S:.0f} s; rerun with a larger --loop"
            )


def _load() -> float:
    return os.getloadavg()[0]


def _loop(log: Path) -> tuple[float, int, int, int]:
    matches = _LOOP.findall(log.read_text())
    if not matches:
        raise RuntimeError(f"no 'Loop time' line in {log}")
    t, p, n, a = matches[-1]
    return float(t), int(p), int(n), int(a)


def _worker(out: str) -> int:
    """Run the deck in this process (possibly one rank of mpiexec) through LammpsSession."""
    from tribolmp.lammps.decks import deck_path
    from tribolmp.lammps.session import LammpsSession

    variables = json.loads((Path(out) / "vars.json").read_text())
    with LammpsSession(log=None, variables=variables) as lmp:
        lmp.file(deck_path("mca_friction"))
    return 0


def _run(kind: str, variables: dict, out: Path) -> dict:
    out.mkdir(parents=True, exist_ok=True)
    v = dict(variables, out=str(out))
    (out / "vars.json").write_text(json.dumps(v))
    bindir = Path(sys.executable).parent
    env = {k: val for k, val in os.environ.items() if k != "LD_LIBRARY_PATH"}
    if kind == "lmp":
        from tribolmp.lammps.decks import deck_path

        cmd = [
            str(bindir / "lmp"),
            "-in",
            str(deck_path("mca_friction")),
            "-screen",
            "none",
            "-nocite",
        ]
        for k, val in v.items():
            cmd += ["-var", k, str(val)]
    else:
        cmd = [sys.executable, __file__, "--worker", str(out)]
        if kind == "python-2":
            cmd = [str(bindir / "mpiexec"), "-n", "2"] + cmd
    load = _load()
    proc = subprocess.run(cmd, capture_output=True, text=True, env=env, check=False)
    if proc.returncode != 0:
        raise RuntimeError(f"{kind} failed: {(proc.stderr or proc.stdout)[-500:]}")
    t, procs, steps, atoms = _loop(out / "run.log")
    fr = np.loadtxt(out / "friction.csv", delimiter=",", skiprows=1, ndmin=2)
    return {
        "loop_s": t,
        "ranks": procs,
        "steps": steps,
        "atoms": atoms,
        "rate": atoms * steps / t,
        "load": load,
        "fr": fr,
    }


#: (dim, lattice repeats) of the law comparison: ~1600 (2D) and ~2000 (3D) automata
LAW_SYSTEMS = ((2, 40), (3, 8))
LAW_SYSTEMS_QUICK = ((2, 16), (3, 4))


def _blocks(text: str) -> tuple[tuple[int, int], ...]:
    """Parse ``--blocks`` (``DIM:REPEATS,...``); one line naming the field on a bad value."""
    out = []
    for item in text.split(","):
        try:
            dim, n = (int(x) for x in item.split(":"))
        except ValueError:
            raise argparse.ArgumentTypeError(
                f"--blocks: expected DIM:REPEATS,... (e.g. 2:40,3:17), got {item!r}"
            ) from None
        if dim not in (2, 3) or not 2 <= n <= 200:
            raise argparse.ArgumentTypeError(
                f"--blocks: DIM must be 2 or 3 and REPEATS 2-200, got {item!r}"
            )
        out.append((dim, n))
    return tuple(out)


def _block_worker(out: str) -> int:
    from tribolmp.lammps.decks import deck_path
    from tribolmp.lammps.session import LammpsSession

    variables = json.loads((Path(out) / "vars.json").read_text())
    with LammpsSession(log=None, variables=variables, require=()) as lmp:
        lmp.file(deck_path("mca_block"))
    return 0


def _block_run(variables: dict, out: Path, steps: int) -> dict:
    v = dict(variables, out=str(out), steps=str(steps), print_every=str(max(1, steps // 10)))
    out.mkdir(parents=True, exist_ok=True)
    (out / "vars.json").write_text(json.dumps(v))
    load = _load()
    cmd = [sys.executable, __file__, "--block-worker", str(out)]
    proc = subprocess.run(cmd, capture_output=True, text=True, check=False)
    if proc.returncode != 0:
        log = out / "block.log"
        tail = log.read_text()[-800:] if log.exists() else ""
        raise RuntimeError(
            f"block run failed (exit {proc.returncode}, {out}): "
            f"{(proc.stderr or proc.stdout or tail)[-800:]}"
        )
    t, procs, nsteps, atoms = _loop(out / "block.log")
    cpu = _CPU.findall((out / "block.log").read_text())
    # share of a core the run got (LAMMPS's "% CPU use"); the machine is shared, so the rate per
    # CPU second is the steadier figure when other jobs take turns on the cores
    cpu_pct = float(cpu[-1]) if cpu else float("nan")
    return {
        "loop_s": t,
        "steps": nsteps,
        "atoms": atoms,
        "rate": atoms * nsteps / t,
        "cpu_pct": cpu_pct,
        "rate_cpu": atoms * nsteps / (t * cpu_pct / 100.0),
        "load": load,
    }


def _best_of(runs: dict, repeat: int) -> dict:
    """Run every row ``repeat`` times, interleaved (a, b, c, a, b, c, ...); keep each row's best.

    ``runs`` maps a row's name to a function of no arguments returning its result dict (with
    ``loop_s``).  The machine is shared: other jobs take memory bandwidth and cache for minutes
    at a time, so one run per row compares different minutes (seen: the same build 7.6 s and
    13.7 s for the same steps).  Interleaving puts the rows' repetitions in the same minutes,
    and the fastest repetition is the one least disturbed (as ``timeit`` reports its minimum);
    the median is kept beside it.
    """
    best, loops = {}, {name: [] for name in runs}
    for _ in range(max(1, repeat)):
        for name, fn in runs.items():
            r = fn()
            loops[name].append(r["loop_s"])
            if name not in best or r["loop_s"] < best[name]["loop_s"]:
                best[name] = r
    for name, r in best.items():
        r["repeats"] = len(loops[name])
        r["loop_s_median"] = float(np.median(loops[name]))
    return best


def _integrator(law: str, reference_settings: str) -> str:
    """Integrator a benchmark row ran with (the block deck's default unless the row names one)."""
    if "+" in law:
        return law.split("+", 1)[1]
    if law.startswith("bpm") or ("@" in law and reference_settings == "old"):
        return "nve/bpm/sphere"
    return "nve/mca"


def _diameter_nm(v: dict) -> float:
    """Automaton diameter (nm) of a block's data file (the first atom's diameter column)."""
    lines = Path(v["data"]).read_text().splitlines()
    k = next(i for i, ln in enumerate(lines) if ln.startswith("Atoms"))
    row = next(ln for ln in lines[k + 1 :] if ln.strip())
    return float(row.split()[3])


def laws_main(
    quick: bool,
    csv_path: Path,
    loop_s: float,
    reference: str | None = None,
    reference_label: str = "reference",
    reference_settings: str = "current",
    repeat: int = 3,
    reference_ghost_vel: str = "yes",
    systems: tuple[tuple[int, int], ...] | None = None,
    rotational: bool = True,
) -> int:
    """Mca vs the bpm laws on the same 2D and 3D blocks; print and write the CSV.

    ``reference``: path of another build of the mca plugin (e.g. of an older commit), run on
    the same blocks in the same loop, so that before/after ratios share the machine's load.
    ``systems``: (dim, lattice repeats) of the blocks (default ``LAW_SYSTEMS``; a 3D block of
    17 repeats has 19 652 automata, the size of the default preset's friction system).
    """
    from tribolmp.lammps.material_test import block_setup

    # "bpm/spring/plastic+nve/mca": the bpm law with the plugin's integrator, which skips the
    # quaternion update that neither law reads: the like-for-like comparison of the two laws'
    # force calculations (as shipped, the bpm law integrates with nve/bpm/sphere)
    laws = (
        ["bpm/spring/plastic", "bpm/spring/plastic+nve/mca"]
        + (["bpm/rotational"] if rotational else [])
        + ["mca"]
        + (["mca@" + reference_label] if reference else [])
    )
    rows = []
    print(
        f"{'dim':>3} {'law':>26} {'automata':>8} {'steps':>7} {'loop_s':>7} "
        f"{'automaton-steps/s':>17} {'dt_ns':>9} {'ns/h':>7} {'ratio':>6} {'like':>5} "
        f"{'/rot':>5} {'cpu%':>5} {'ratio/cpu-s':>11} {'load':>5}"
    )
    with tempfile.TemporaryDirectory(prefix="mca_laws_") as tmp:
        for dim, n in systems or (LAW_SYSTEMS_QUICK if quick else LAW_SYSTEMS):
            cals = {}
            for law in laws:
                out = Path(tmp) / f"{dim}d_{re.sub(r'[/@+]', '_', law)}"
                base = law.split("@")[0].split("+")[0]
                v = {k: str(x) for k, x in block_setup(base, dim, out, n=n).items()}
                if "+" in law:
                    from tribolmp.lammps.plugin import plugin_path

                    v.update(
                        integrator=law.split("+")[1], load_plugin="yes", plugin=str(plugin_path())
                    )
                if "@" in law:
                    v["plugin"] = str(Path(reference).resolve())
                    # a build before 2026-12-02 asks for LAMMPS's ghost velocities
                    v["mca_ghost_vel"] = reference_ghost_vel
                    if reference_settings == "old":
                        # the block deck's mca settings before fix nve/mca (main at 3c1f250)
                        d = _diameter_nm(v)
                        v.update(
                            integrator="nve/bpm/sphere",
                            pair_newton="on",
                            comm_cut=f"{3.0 * d:.10g}",
                        )
                v.update(drive="deform", vshear="5.0")
                cal = _block_run(v, out / "cal", 200 if quick else 500)
                cals[law] = (
                    v,
                    out,
                    max(200, int(_CAL_MARGIN * loop_s * cal["rate"] / cal["atoms"])),
                )
            # one step count for every row (the longest calibrated one: each loop >= loop_s), so
            # that the rows cover the same phase of the shear (elastic, yield, rupture), whose
            # cost per step differs
            steps = max(n for _, _, n in cals.values())
            res = _best_of(
                {
                    law: (lambda v=v, out=out: _block_run(v, out / "run", steps))
                    for law, (v, out, _) in cals.items()
                },
                repeat,
            )
            for law, (v, _, _) in cals.items():
                res[law]["dt_ns"] = float(v["dt"])
            like = res["bpm/spring/plastic+nve/mca"]
            for law, r in res.items():
                ratio = r["rate"] / res["bpm/spring/plastic"]["rate"]
                ratio_cpu = r["rate_cpu"] / res["bpm/spring/plastic"]["rate_cpu"]
                ratio_like = r["rate"] / like["rate"]
                # (against LAMMPS's own link law with a tangential and rotational history)
                ratio_rot = r["rate"] / res["bpm/rotational"]["rate"] if rotational else math.nan
                ns_h = r["rate"] / r["atoms"] * r["dt_ns"] * 3600.0
                row = {
                    "dim": dim,
                    "law": law.split("@")[0].split("+")[0],
                    "integrator": _integrator(law, reference_settings),
                    "plugin": (law.split("@", 1)[1] if "@" in law else "current")
                    if law.startswith("mca")
                    else "",
                    "deck_settings": reference_settings if "@" in law else "current",
                    "automata": r["atoms"],
                    "steps": r["steps"],
                    "loop_s": r["loop_s"],
                    "repeats": r["repeats"],
                    "loop_s_median": r["loop_s_median"],
                    "automaton_steps_per_s": r["rate"],
                    "dt_ns": r["dt_ns"],
                    "simulated_ns_per_hour": ns_h,
                    "ratio_vs_bpm": ratio,
                    "ratio_vs_bpm_same_integrator": ratio_like,
                    "ratio_vs_bpm_rotational": ratio_rot,
                    "cpu_use_pct": r["cpu_pct"],
                    "automaton_steps_per_cpu_s": r["rate_cpu"],
                    "ratio_vs_bpm_per_cpu_s": ratio_cpu,
                    "load_avg_1min": r["load"],
                }
                rows.append(row)
                print(
                    f"{dim:>3} {law:>26} {r['atoms']:>8} {r['steps']:>7} {r['loop_s']:>7.1f} "
                    f"{r['rate']:>17.4g} {r['dt_ns']:>9.3g} {ns_h:>7.3g} {ratio:>6.2f} "
                    f"{ratio_like:>5.2f} {ratio_rot:>5.2f} {r['cpu_pct']:>5.0f} {ratio_cpu:>11.2f} "
                    f"{r['load']:>5.1f}"
                )
    if not quick:
        _short_loops(rows)
    write_csv(csv_path, rows)
    print(f"wrote {csv_path}")
    return 0


#: (dim, preset) of the friction comparison: the default preset's friction system
FRICTION_SYSTEMS = ((2, "default"), (3, "default"))
FRICTION_SYSTEMS_QUICK = ((2, "smoke"), (3, "smoke"))


def friction_main(
    quick: bool,
    csv_path: Path,
    loop_s: float,
    reference: str | None = None,
    reference_label: str = "reference",
    repeat: int = 3,
    reference_ghost_vel: str = "yes",
    ranks: int = 1,
    rotational: bool = True,
) -> int:
    """Mca vs the bpm laws on the friction deck's system; print and write the CSV.

    The system of a preset (rigid slider, two rough bodies, fixed base; ``mca_friction.in``
    with ``drive deck``: the slider presses and slides from the built state) is prepared once
    per law, as ``tribolmp mca run`` would, and run for a loop of about ``loop_s`` of LAMMPS
    time (calibrated by a short first run; all laws then run the same number of steps, the
    largest calibrated one, so that the rows cover the same phase of the run) on ``ranks`` MPI
    ranks (1 or 2; the rate is automaton-steps per second of wall time).
    Unlike the block, this deck asks for the global virial on every step (its ``fix ave/time
    1 N N``), and its bodies are bounded by free surfaces and rigid layers.
    """
    from tribolmp.lammps import mca
    from tribolmp.lammps.mca.prepare import prepare as mca_prepare

    laws = (
        ["bpm/spring/plastic"]
        + (["bpm/rotational"] if rotational else [])
        + ["mca"]
        + (["mca@" + reference_label] if reference else [])
    )
    rows = []
    print(
        f"{'dim':>3} {'preset':>7} {'law':>20} {'automata':>8} {'steps':>6} {'loop_s':>7} "
        f"{'automaton-steps/s':>17} {'ratio':>6} {'/rot':>5} {'load':>5}"
    )
    with tempfile.TemporaryDirectory(prefix="mca_friction_") as tmp:
        for dim, preset in FRICTION_SYSTEMS_QUICK if quick else FRICTION_SYSTEMS:
            runs = {}
            for law in laws:
                params = mca.preset_params(
                    preset,
                    dim=dim,
                    bond_style=law.split("@")[0],
                    dump_interval=1e-6,
                    restart_interval=1e-6,
                )
                prep = Path(tmp) / f"{dim}d_{re.sub(r'[/@+]', '_', law)}"
                variables = {k: str(v) for k, v in mca_prepare(params, prep, 1, {}).items()}
                if "@" in law:
                    variables["mca_plugin"] = str(Path(reference).resolve())
                    variables["mca_ghost_vel"] = reference_ghost_vel  # (as in laws_main)

                def timed(steps: int, name: str, variables=variables, prep=prep) -> dict:
                    v = dict(
                        variables,
                        drive="deck",
                        steps=str(steps),
                        thermo_every=str(steps),
                        restart_every=str(10 * steps),
                    )
                    return _run(f"python-{ranks}", v, prep / name)

                cal = timed(300, "cal")
                runs[law] = (
                    timed,
                    max(400, int(_CAL_MARGIN * loop_s * cal["rate"] / cal["atoms"])),
                )
            # one step count for every law (the longest calibrated one, so each loop is >= loop_s):
            # the rate depends on the phase of the run (approach, first contact, sliding), so the
            # rows must cover the same steps from the same built state
            steps = max(n for _, n in runs.values())
            res = _best_of(
                {law: (lambda t=timed: t(steps, "run")) for law, (timed, _) in runs.items()}, repeat
            )
            for law, r in res.items():
                ratio = r["rate"] / res["bpm/spring/plastic"]["rate"]
                ratio_rot = r["rate"] / res["bpm/rotational"]["rate"] if rotational else math.nan
                rows.append(
                    {
                        "dim": dim,
                        "preset": preset,
                        "law": law.split("@")[0],
                        "plugin": (law.split("@", 1)[1] if "@" in law else "current")
                        if law.startswith("mca")
                        else "",
                        "automata": r["atoms"],
                        "ranks": r["ranks"],
                        "steps": r["steps"],
                        "loop_s": r["loop_s"],
                        "repeats": r["repeats"],
                        "loop_s_median": r["loop_s_median"],
                        "automaton_steps_per_s": r["rate"],
                        "ratio_vs_bpm": ratio,
                        "ratio_vs_bpm_rotational": ratio_rot,
                        "load_avg_1min": r["load"],
                    }
                )
                print(
                    f"{dim:>3} {preset:>7} {law:>20} {r['atoms']:>8} {r['steps']:>6} "
                    f"{r['loop_s']:>7.1f} {r['rate']:>17.4g} {ratio:>6.2f} {ratio_rot:>5.2f} "
                    f"{r['load']:>5.1f}"
                )
    if not quick:
        _short_loops(rows)
    write_csv(csv_path, rows)
    print(f"wrote {csv_path}")
    return 0


def main(argv: list[str] | None = None) -> int:
    """Run the benchmark; print the table and write the CSV."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="small systems, short loops")
    ap.add_argument(
        "--interfaces", action="store_true", help="Python vs lmp vs 2 ranks (friction deck)"
    )
    ap.add_argument(
        "--friction",
        action="store_true",
        help="mca vs the bpm laws on the friction deck's default-preset system",
    )
    ap.add_argument("--loop", type=float, default=12.0, help="target loop time per law run (s)")
    ap.add_argument(
        "--reference-plugin",
        default=None,
        help="another build of the mca plugin (mcaplugin.so) timed on the same blocks, same run",
    )
    ap.add_argument(
        "--reference-label",
        default="reference",
        help="name of the reference build in the table and CSV (e.g. main@abc1234)",
    )
    ap.add_argument(
        "--reference-settings",
        choices=("current", "old"),
        default="current",
        help="deck settings of the reference row: today's, or those before fix nve/mca "
        "(nve/bpm/sphere, 3 d ghost cutoff, newton on), which an older plugin needs",
    )
    ap.add_argument(
        "--reference-ghost-vel",
        choices=("yes", "no"),
        default="yes",
        help="LAMMPS's ghost velocities for the reference row: yes for a plugin built before "
        "2026-12-02 (it needs them), no for a later one (it sends them itself)",
    )
    ap.add_argument(
        "--blocks",
        type=_blocks,
        default=None,
        help="blocks of the law comparison as DIM:REPEATS,... (default 2:40,3:8: 1 600 and "
        "2 048 automata; 3:17 is 19 652)",
    )
    ap.add_argument(
        "--ranks",
        type=int,
        choices=(1, 2),
        default=1,
        help="MPI ranks of each run of the friction comparison (--friction; default 1)",
    )
    ap.add_argument(
        "--repeat",
        type=int,
        default=3,
        help="timed runs per row, interleaved across the rows; the fastest is reported (default 3)",
    )
    ap.add_argument(
        "--no-rotational",
        action="store_true",
        help="leave out the bpm/rotational rows (law comparisons; they run the most steps' "
        "worth of the slowest law, so they take the longest)",
    )
    ap.add_argument("--block-worker", default=None, help=argparse.SUPPRESS)
    ap.add_argument(
        "--out",
        default=None,
        help="CSV path (default benchmarks/results/mca_throughput[_quick].csv)",
    )
    ap.add_argument("--worker", default=None, help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.worker:
        return _worker(args.worker)
    if args.block_worker:
        return _block_worker(args.block_worker)
    # (each option belongs to one comparison: refuse it elsewhere rather than ignore it)
    if args.blocks and args.friction:
        ap.error("--blocks: the blocks of the law comparison; not with --friction")
    if args.ranks != 1 and not args.friction:
        ap.error("--ranks: the friction comparison's ranks (with --friction); expected 1 here")
    if args.friction or not args.interfaces:
        # the law comparisons: on the friction system, or on the block
        kind = "friction" if args.friction else "laws"
        name = f"mca_throughput_{kind}{'_quick' if args.quick else ''}.csv"
        csv_path = Path(args.out) if args.out else Path(__file__).parent / "results" / name
        common = (args.quick, csv_path, 2.0 if args.quick else args.loop)
        ref = (args.reference_plugin, args.reference_label)
        if args.friction:
            return friction_main(
                *common,
                *ref,
                repeat=args.repeat,
                reference_ghost_vel=args.reference_ghost_vel,
                ranks=args.ranks,
                rotational=not args.no_rotational,
            )
        return laws_main(
            *common,
            *ref,
            args.reference_settings,
            repeat=args.repeat,
            reference_ghost_vel=args.reference_ghost_vel,
            systems=args.blocks,
            rotational=not args.no_rotational,
        )

    from tribolmp.lammps import mca
    from tribolmp.lammps.mca.prepare import prepare as mca_prepare

    sizes = QUICK if args.quick else SIZES
    default_csv = (
        Path(__file__).parent / "results" / f"mca_throughput{'_quick' if args.quick else ''}.csv"
    )
    csv_path = Path(args.out) if args.out else default_csv
    csv_path.parent.mkdir(parents=True, exist_ok=True)
    rows = []
    print(
        f"{'size':>5} {'atoms':>6} {'mode':>9} {'ranks':>5} "
        f"{'steps':>6} {'loop_s':>8} {'Matom-steps/s':>13} "
        f"{'vs py-1':>7} {'max rel diff':>12} {'load':>5}"
    )
    with tempfile.TemporaryDirectory(prefix="mca_bench_") as tmp:
        for label, length, height, steps in sizes:
            params = mca.preset_params(
                "smoke",
                box_length=length,
                body_height=height,
                duration=1e-9,
                dump_interval=1e-6,
                restart_interval=1e-6,
                print_interval=1e-12 * 50,
            )
            prep = Path(tmp) / label
            variables = mca_prepare(params, prep, 1, {})
            variables = {k: str(v) for k, v in variables.items()}
            variables.update(
                drive="deck",
                steps=str(steps),
                thermo_every=str(steps),
                restart_every=str(10 * steps),
            )
            results = {}
            for kind in ("python-1", "lmp", "python-2"):
                results[kind] = _run(kind, variables, prep / kind)
            ref = results["python-1"]
            for kind, r in results.items():
                n = min(len(ref["fr"]), len(r["fr"]))
                a, b = ref["fr"][:n, 1:3], r["fr"][:n, 1:3]
                diff = (
                    float(np.max(np.abs(a - b) / np.maximum(np.abs(a), 1e-30)))
                    if n
                    else float("nan")
                )
                row = {
                    "size": label,
                    "atoms": r["atoms"],
                    "mode": kind,
                    "ranks": r["ranks"],
                    "steps": r["steps"],
                    "loop_s": r["loop_s"],
                    "atom_steps_per_s": r["rate"],
                    "ratio_vs_python_1rank": r["rate"] / ref["rate"],
                    "max_rel_diff_friction": diff,
                    "load_avg_1min": r["load"],
                }
                rows.append(row)
                print(
                    f"{label:>5} {row['atoms']:>6} {kind:>9} {row['ranks']:>5} "
                    f"{row['steps']:>6} {row['loop_s']:>8.2f} "
                    f"{row['atom_steps_per_s'] / 1e6:>13.2f} "
                    f"{row['ratio_vs_python_1rank']:>7.2f} {diff:>12.2e} "
                    f"{row['load_avg_1min']:>5.1f}"
                )
    write_csv(csv_path, rows)
    print(f"wrote {csv_path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
