"""Deck location (package data) and the Python <-> deck variable contract, tested as text."""

from __future__ import annotations

import re

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
    assert declared - set(v) == {"restart", "resume", "smooth"}
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
