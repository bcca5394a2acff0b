"""Write the fixture of tests/mca/test_law_restart_layout.py with a given build of the plugin.

The fixture is a restart file of the sheared 2D block (``mca_block.in``, drive ramp) written by
a plugin that keeps the automaton rows in the order used before 2026-12-06, and the state that
plugin reaches when it continues the file for ``STEPS`` steps (positions, velocities, the ten
per-automaton output columns ``f_mca_state``, the seven tallies).  The shipped fixture was made
with the plugin of main@2f3eac9::

    git worktree add /tmp/old 2f3eac9
    (build its tribolmp/lammps/plugin_src into OLD.so with the package's flags)
    python tests/data/generate_mca_restart_fixture.py OLD.so

Run from the repository root.
"""

from __future__ import annotations

import json
import subprocess
import sys
import tempfile
from pathlib import Path

from tribolmp.lammps.decks import deck_path
from tribolmp.lammps.law_mca import McaLaw
from tribolmp.lammps.material_test import block_setup

HERE = Path(__file__).parent / "mca_restart_layout1"
N = 8  # lattice repeats (64 automata: a small file)
FIRST = 500  # steps before the restart (through yield, rupture and welding)
STEPS = 300  # steps of the continuation

SCRIPT = """
import json, sys
import numpy as np
from tribolmp.lammps.session import LammpsSession
v = json.loads(sys.argv[1]); deck = sys.argv[2]; out = sys.argv[3]
with LammpsSession(log=None, variables=v, require=()) as s:
    s.file(deck)
    g = lambda k, n: np.ctypeslib.as_array(s.lmp.gather_atoms(k, 1, n)).reshape(-1, n).copy()
    ids = np.ctypeslib.as_array(s.lmp.gather_atoms("id", 0, 1)).copy()
    st = np.ctypeslib.as_array(s.lmp.gather("f_mca_state", 1, 10)).reshape(-1, 10).copy()
    t = [s.lmp.extract_compute("t", 0, 1)[k] for k in range(7)]
    lo, hi = s.lmp.extract_box()[:2]
    np.savez(out, id=ids, x=g("x", 3), v=g("v", 3), omega=g("omega", 3), state=st,
             tallies=np.array(t), box=np.array(hi) - np.array(lo))
"""


def variables(workdir: Path, plugin: str | None = None) -> dict:
    """Deck variables of the fixture's block (the default, damped and viscous 2D law)."""
    v = block_setup("mca", 2, workdir, n=N, params=McaLaw(dim=2))
    v.update(drive="ramp", vshear=100.0, print_every=100)
    if plugin:
        v["plugin"] = plugin
    return {k: str(x) for k, x in v.items()}


def run(v: dict, out: Path) -> None:
    cmd = [sys.executable, "-c", SCRIPT, json.dumps(v), str(deck_path("mca_block")), str(out)]
    proc = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    if proc.returncode != 0:
        raise SystemExit(proc.stderr[-2000:])


def main(plugin: str) -> None:
    HERE.mkdir(exist_ok=True)
    with tempfile.TemporaryDirectory() as tmp:
        v = variables(Path(tmp), str(Path(plugin).resolve()))
        rst = HERE / "block.restart"
        run(dict(v, steps=str(FIRST), write="1", restart_out=str(rst)), Path(tmp) / "a.npz")
        run(dict(v, steps=str(STEPS), resume="1", restart_in=str(rst)), HERE / "reference.npz")
    print("wrote", rst, HERE / "reference.npz")


if __name__ == "__main__":
    main(sys.argv[1])
