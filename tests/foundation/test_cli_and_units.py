"""The CLI skeleton (info, errors, exit codes), units and RNG helpers."""

from __future__ import annotations

import numpy as np
import pytest

from tests.conftest import assert_one_line_error
from tribolmp.errors import LammpsError, ParameterError, SetupError
from tribolmp.models.base import MethodRegistry, Result, check_range
from tribolmp.rng import as_generator, lammps_seed, spawn
from tribolmp.units import LAMMPS_NANO, from_lammps, to_lammps


@pytest.mark.lammps
def test_info_lists_bpm_and_granular(cli):
    res = cli("info", "--json")
    assert res.returncode == 0, res.stderr
    info = res.json()
    pk = info["lammps"]["packages"]
    assert {"BPM", "GRANULAR", "MOLECULE"} <= set(pk)
    assert info["lammps"]["missing_styles"] == []
    assert info["mpi"]["ranks"] == 1
    assert info["lammps"]["version"] == 20250722
    text = cli("info")
    assert (
        text.returncode == 0
        and "BPM" in text.stdout
        and "GRANULAR" in text.stdout
        and "MPICH" in text.stdout
    )


def test_unknown_command_and_option_are_one_line(cli):
    assert_one_line_error(cli("frobnicate"), "invalid choice")
    assert_one_line_error(cli("check", "--no-such-flag", "x.toml"), "unrecognized arguments")


def test_units_nano_round_trip():
    # 1 nm/ns is exactly 1 m/s; 1 MPa is one nano pressure unit (ag / (nm ns^2)).
    assert to_lammps(5.0, "velocity") == 5.0
    assert to_lammps(150e6, "pressure") == pytest.approx(150.0)
    assert from_lammps(2.5, "length") == pytest.approx(2.5e-9)
    # consistency of derived units: force = mass * length / time^2, pressure = force / length^2
    L = LAMMPS_NANO
    assert L["force"] == pytest.approx(L["mass"] * L["length"] / L["time"] ** 2)
    assert L["pressure"] == pytest.approx(L["force"] / L["length"] ** 2)
    assert L["energy"] == pytest.approx(L["force"] * L["length"])
    assert L["density"] == pytest.approx(L["mass"] / L["length"] ** 3)
    assert L["stiffness"] == pytest.approx(L["force"] / L["length"])
    assert L["viscosity"] == pytest.approx(L["pressure"] * L["time"])
    assert L["damping"] == pytest.approx(L["force"] / L["velocity"])
    assert L["diffusion"] == pytest.approx(L["length"] ** 2 / L["time"])


def test_rng_helpers_are_explicit_and_reproducible():
    a, b = as_generator(7), as_generator(7)
    assert a.random() == b.random()
    g = np.random.default_rng(1)
    assert as_generator(g) is g
    s = lammps_seed(np.random.default_rng(3))
    assert 1 <= s < 900_000_000 and s == lammps_seed(np.random.default_rng(3))
    kids = spawn(np.random.default_rng(5), 3)
    draws = [k.random() for k in kids]
    assert len(set(draws)) == 3
    with pytest.raises(TypeError):
        as_generator("seed")


def test_registry_and_validators():
    reg = MethodRegistry("demo")

    @reg.register("a")
    def _a():
        return 1

    assert reg.get("a")() == 1
    with pytest.raises(ParameterError, match=r"method: expected one of \['a'\], got 'b'"):
        reg.get("b")
    assert check_range("x", 1, 0, 2) == 1.0
    with pytest.raises(ParameterError, match=r"x: expected a number in \(0, inf\) m, got -1"):
        check_range("x", -1, 0, None, lo_open=True, unit="m")
    with pytest.raises(ParameterError, match="finite"):
        check_range("x", float("nan"))
    r = Result(force=np.float64(2.0), arr=np.arange(3))
    assert r.force == 2.0 and r.status == 0 and r.success
    assert r.to_json_dict()["arr"] == [0, 1, 2]


def test_error_types_and_exit_codes():
    assert issubclass(ParameterError, SetupError)
    err = LammpsError("Lost atoms:\n original 10 current 9", "run 100", step=42)
    assert (
        str(err)
        == "LAMMPS error: Lost atoms: original 10 current 9 [input line: run 100] [step 42]"
    )
    assert err.exit_code == 3 and ParameterError("a", "b", 1).exit_code == 2
