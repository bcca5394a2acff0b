"""The global virial of pair mca: the inline sums equal LAMMPS's per-atom tallies.

``pair_style mca`` forms the global virial, -sum over pairs of R (x) F, inside its pair loop when
only the global virial is asked for (thermo, ``compute pressure``, ``fix deform/pressure``, or
any ``fix ave/time`` every step), and goes through ``ev_tally_xyz_full`` -- which forms the
global sums from the per-atom halves -- only when per-atom energy or virial is asked for
(``compute stress/atom``).  The two are independent code paths over the same pair forces, so:

* the same state (two runs with identical trajectories, one with ``compute stress/atom`` on the
  compared step, one without) must give the same global virial; they differ only by the order
  of the floating-point sums (the per-atom path adds two halves per local pair), i.e. by a few
  ulp of the largest term, so the tolerance is 1e-9 of the largest component -- a wrong sign,
  a factor 1/2 on local pairs (-0.5 instead of -1) or a missing component is of order 1;
* the global virial times the volume equals minus the sum of ``compute stress/atom`` (the
  definition of the per-atom stress in LAMMPS), within the same rounding.

The state is the sheared periodic block of ``mca_block.in`` through link rupture and welding,
in 2D and 3D, so links, welds, contacts and ghost (periodic) partners all contribute.
"""

from __future__ import annotations

import json
import subprocess
import sys
import textwrap

import numpy as np
import pytest

from tribolmp.lammps.decks import deck_path
from tribolmp.lammps.material_test import block_setup

pytestmark = pytest.mark.lammps

_SCRIPT = textwrap.dedent(
    """
    import json, sys
    import numpy as np
    from tribolmp.lammps.session import LammpsSession
    v = json.loads(sys.argv[1]); deck = sys.argv[2]; out = sys.argv[3]; peratom = sys.argv[4] == "1"
    with LammpsSession(log=None, variables=v, require=()) as s:
        s.file(deck)
        vir = " ".join(f"c_vir[{k}]" for k in range(1, 7))
        cols = vir
        if peratom:
            s.command("compute sa all stress/atom NULL virial")
            s.command("compute sr all reduce sum " + " ".join(f"c_sa[{k}]" for k in range(1, 7)))
            cols += " " + " ".join(f"c_sr[{k}]" for k in range(1, 7))
        s.command("thermo 200")
        s.command("thermo_style custom step " + cols)
        s.command("run 200")
        lmp = s.lmp
        w = np.array([lmp.extract_compute("vir", 0, 1)[k] for k in range(6)])
        sr = (np.array([lmp.extract_compute("sr", 0, 1)[k] for k in range(6)])
              if peratom else np.full(6, np.nan))
        vol = lmp.get_thermo("vol")  # (the area in 2D, as compute pressure divides by)
        x = np.ctypeslib.as_array(lmp.gather_atoms("x", 1, 3)).reshape(-1, 3).copy()
        np.savez(out, vir=w, sr=sr, vol=vol, x=x)
    """
)


def _run(tmp_path, dim, n, peratom):
    name = f"pa{int(peratom)}"
    v = block_setup("mca", dim, tmp_path / name, n=n)
    v.update(vshear=100.0, steps=400, print_every=400)
    v = {k: str(val) for k, val in v.items()}
    out = tmp_path / f"{name}.npz"
    cmd = [sys.executable, "-c", _SCRIPT, json.dumps(v), str(deck_path("mca_block")), str(out),
           "1" if peratom else "0"]
    proc = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr[-2000:]
    return np.load(out)


@pytest.mark.parametrize(("dim", "n"), [(2, 12), (3, 4)], ids=["2d", "3d"])
def test_inline_virial_equals_per_atom_tallies(lammps_available, tmp_path, dim, n):
    inline = _run(tmp_path, dim, n, peratom=False)
    tallied = _run(tmp_path, dim, n, peratom=True)
    # the computes do not act on the dynamics: the same state is compared
    assert np.array_equal(inline["x"], tallied["x"])
    comps = [0, 1, 3] if dim == 2 else list(range(6))
    a, b = inline["vir"][comps], tallied["vir"][comps]
    scale = np.max(np.abs(b))
    assert scale > 0.0, "no virial: the block carries no stress"
    # rounding of the sums only (module docstring)
    np.testing.assert_allclose(a, b, rtol=0.0, atol=1e-9 * scale)
    # LAMMPS's definition: volume * virial pressure = -sum of the per-atom stress
    np.testing.assert_allclose(-tallied["sr"][comps] / tallied["vol"], b, rtol=0.0,
                               atol=1e-9 * scale)
