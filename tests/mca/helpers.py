"""Shared runs of the sheared periodic block (``mca_block.in``) for the law's identity tests."""

from __future__ import annotations

import json
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np

from tribolmp.lammps.decks import deck_path

#: Runs the deck in a fresh interpreter and saves x, v, omega, the law's seven tallies and the
#: number of pairs its fused kernel evaluated on the last step (``fused``, a diagnostic).
_SCRIPT = textwrap.dedent(
    """
    import json, sys
    import numpy as np
    from tribolmp.lammps.session import LammpsSession
    v = json.loads(sys.argv[1]); deck = sys.argv[2]; out = sys.argv[3]
    with LammpsSession(log=None, variables=v, require=()) as s:
        s.file(deck)
        g = {k: np.ctypeslib.as_array(s.lmp.gather_atoms(k, 1, 3)).reshape(-1, 3).copy()
             for k in ("x", "v", "omega")}
        t = [s.lmp.extract_compute("t", 0, 1)[k] for k in range(7)]
        fused = s.lmp.extract_compute("t", 0, 1)[7] if v.get("law", "mca") == "mca" else 0.0
        np.savez(out, tallies=np.array(t), fused=fused, **g)
    """
)


def run_block(variables: dict, out: Path):
    """Run ``mca_block.in`` with ``variables``; return the saved arrays (``np.load`` of ``out``)."""
    v = {k: str(val) for k, val in variables.items()}
    cmd = [sys.executable, "-c", _SCRIPT, json.dumps(v), str(deck_path("mca_block")), str(out)]
    proc = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr[-2000:]
    return np.load(out)
