"""Shared fixtures: temporary working directory, RNG, LAMMPS skip-fixture, CLI runner."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
VENV_BIN = Path(sys.executable).parent


@pytest.fixture(autouse=True)
def _tmp_cwd(tmp_path, monkeypatch):
    """Run every test in its own directory: LAMMPS and workflows write files to the cwd."""
    monkeypatch.chdir(tmp_path)
    yield


@pytest.fixture
def rng():
    """Return a fixed-seed generator (tests never use global random state)."""
    return np.random.default_rng(12345)


@pytest.fixture(scope="session")
def lammps_available():
    """Skip when the LAMMPS module or a required package is missing (a missing optional engine)."""
    try:
        from tribolmp.lammps import capabilities

        caps = capabilities()
    except Exception as exc:  # noqa: BLE001
        pytest.skip(f"LAMMPS Python module not usable: {exc}")
    if caps["missing_packages"]:
        pytest.skip(f"LAMMPS lacks packages {caps['missing_packages']}")
    return caps


@pytest.fixture
def lmp(lammps_available, tmp_path):
    """Return an open LammpsSession logging to tmp_path/log.lammps."""
    from tribolmp.lammps import LammpsSession

    with LammpsSession(log=tmp_path / "log.lammps") as session:
        yield session


def mpiexec() -> Path:
    """Return the mpiexec shipped by the mpich wheel next to this interpreter."""
    path = VENV_BIN / "mpiexec"
    if not path.exists():
        pytest.skip("mpiexec from the mpich wheel is not installed in this environment")
    return path


class CLIResult:
    def __init__(self, proc: subprocess.CompletedProcess):
        self.returncode = proc.returncode
        self.stdout = proc.stdout
        self.stderr = proc.stderr

    def json(self):
        return json.loads(self.stdout)


@pytest.fixture
def cli():
    """Run ``python -m tribolmp ARGS`` in a subprocess with a clean environment."""

    def _run(*args: str, timeout: float = 600, env: dict | None = None) -> CLIResult:
        e = {k: v for k, v in os.environ.items() if k != "LD_LIBRARY_PATH"}
        e.update(env or {})
        proc = subprocess.run(
            [sys.executable, "-m", "tribolmp", *map(str, args)],
            capture_output=True,
            text=True,
            timeout=timeout,
            env=e,
        )
        return CLIResult(proc)

    return _run


def assert_one_line_error(res: CLIResult, *fragments: str, code: int = 2) -> None:
    """Return a user error: the expected exit code, exactly one line on stderr, no traceback."""
    assert res.returncode == code, (res.returncode, res.stdout, res.stderr)
    lines = [ln for ln in res.stderr.splitlines() if ln.strip()]
    assert len(lines) == 1, res.stderr
    assert "Traceback" not in res.stderr
    for frag in fragments:
        assert frag in lines[0], (frag, lines[0])
