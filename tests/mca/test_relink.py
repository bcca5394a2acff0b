"""Re-linking of the bpm laws is not capped.

Two automata pulled apart and pushed together re-link every cycle.

``fix bond/create ... iparam maxbond`` counts the links it created and never decrements the count
when a BPM link breaks, so any finite quota caps re-links per automaton per run (issue 13: 455
automata of the 382 MPa run had used their quota of 6 by 6 ns).  The law fragments use no quota;
geometry bounds the links an automaton holds.  This test runs the real fragment
(``lammps_inputs/laws/<keyword>.in``) with the mapped coefficients.
"""

from __future__ import annotations

import pytest

from tribolmp.lammps.decks import laws_dir
from tribolmp.lammps.laws import get_law
from tribolmp.lammps.mca import deck_variables, preset_params

pytestmark = pytest.mark.lammps

CYCLES = 12


def _two_automata(tmp_path, vars_: dict) -> str:
    d_c = float(vars_["rebond_r"]) / 0.99  # contact diameter
    data = tmp_path / "two.data"
    data.write_text(
        "two automata\n\n2 atoms\n3 atom types\n0 bonds\n3 bond types\n\n"
        "-20 20 xlo xhi\n-20 20 ylo yhi\n-1.25 1.25 zlo zhi\n\nAtoms # bpm/sphere\n\n"
        f"1 2 1 {d_c} 1.0 0 0 0\n2 2 1 {d_c} 1.0 2.45 0 0\n"
    )
    return str(data)


@pytest.mark.parametrize("law", ["bpm/spring/plastic", "bpm/rotational"])
def test_two_automata_relink_every_cycle(law, tmp_path, lammps_available):
    from tribolmp.lammps.session import LammpsSession

    params = preset_params("smoke", bond_style=law)
    info = {"lx_nm": 50.0, "lz_nm": 2.5, "sink_lo_nm": -1e9, "sink_hi_nm": 1e9}
    v = deck_variables(params, data="x", out=str(tmp_path), seed=1, geom_info=info)
    v = {k: v[k] for k in get_law(law).deck_variables(get_law(law).map_material(params.material()))}
    full = deck_variables(params, data="x", out=str(tmp_path), seed=1, geom_info=info)
    v.update(
        {k: full[k] for k in ("kc", "gc", "muc", "rebond_r", "rebond_factor", "dt", "comm_cut")}
    )
    v.update(
        lawdir=str(laws_dir()), bond=get_law(law).keyword, smooth="no", resume=0, rebond_every=20
    )
    data = _two_automata(tmp_path, v)
    rebond_r = float(v["rebond_r"])
    # atom 2 oscillates along x between 0.92 and 1.12 rebond_r: it links when pushed below rebond_r
    # and the link ruptures (strain > 5 %) when it is pulled out again
    centre, amp = 1.02 * rebond_r, 0.10 * rebond_r
    period_steps = 4000
    with LammpsSession(log=None, variables=v) as lmp:
        lmp.commands(
            f"""
units nano
dimension 2
boundary p p p
atom_style bpm/sphere
newton on off
comm_modify vel yes cutoff {v['comm_cut']}
special_bonds lj 0 1 1 coul 1 1 1
timestep {v['dt']}
read_data {data} extra/bond/per/atom 4 extra/special/per/atom 8
group mobile type 1
variable mca_context string friction
include {v['lawdir']}/{v['bond']}.in
include {v['lawdir']}/bpm_relink.in
neighbor 0.5 bin
neigh_modify every 1 delay 0 check yes
group moving id 2
displace_atoms moving move {centre - 2.45} 0 0
fix wiggle moving move wiggle {amp} 0 0 $({period_steps}*dt)
fix twod all enforce2d
thermo_style custom step bonds f_relink[2]
run {CYCLES * period_steps}
"""
        )
        created = int(lmp.lmp.extract_fix("relink", 0, 1, 1))
        bonds_now = int(lmp.thermo("bonds"))
    # one re-link per compression phase: CYCLES of them (the first phase may start linked or not);
    # CYCLES > the 4 free bond slots per atom, so the slots of broken links are reused as well
    assert created >= CYCLES - 1, created
    assert created > 6  # the old quota (maxbond 6) allowed at most 6
    # never more than the one possible link between the pair (duplicates
    # excluded by the special list)
    assert bonds_now <= 1
