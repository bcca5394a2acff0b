"""The MCA plugin's batched loops compile to vector code.

The pair loop's geometry and common-case passes (``batch_geometry``, ``batch_common``) and the
per-automaton stress update (``automata_update``) are written as straight-line loops with
selects so that the compiler can vectorise them.  Whether it does depends on the build flags
(without ``-fno-trapping-math`` GCC keeps a select over a square root or a division scalar) and
on the code (one branch the compiler cannot turn into a select keeps the whole loop scalar).
Either failure changes no number -- only the speed, by 1.2-1.4x on the 3D friction system
(docs/mca.md, "The batched loops vectorised") -- so no physics test can see it; this test reads
GCC's own vectorisation report of the plugin source, compiled exactly as the plugin is.

Each such loop carries the marker ``vectorised xN (tests/mca/test_law_vectorised.py)``, N the
number of template instances that must each be reported vectorised.
"""

from __future__ import annotations

import re
import shutil
import subprocess

import pytest

from tribolmp.errors import MissingFeatureError
from tribolmp.lammps import plugin as plug

pytestmark = pytest.mark.lammps

_MARK = re.compile(r"//\s*vectorised x(\d+) \(tests/mca/test_law_vectorised\.py\)")


def _is_gcc() -> bool:
    try:
        cxx = shutil.which(plug._compiler())
    except MissingFeatureError:  # no compiler: the plugin's own build tests report it
        return False
    out = subprocess.run([cxx, "--version"], capture_output=True, text=True).stdout
    return "Free Software Foundation" in out and "clang" not in out.lower()


def _marked_loops(source: str) -> dict[int, int]:
    text = (plug.SOURCE_DIR / source).read_text().splitlines()
    return {n: int(m.group(1)) for n, line in enumerate(text, 1) if (m := _MARK.search(line))}


def _vectorised_counts(report: str, source: str) -> dict[int, int]:
    counts: dict[int, int] = {}
    for m in re.finditer(rf"{re.escape(source)}:(\d+):\d+: optimized: loop vectorized", report):
        counts[int(m.group(1))] = counts.get(int(m.group(1)), 0) + 1
    return counts


def test_the_batched_loops_are_marked():
    # the three loops named in the module docstring: a marker lost in an edit would make the
    # next test pass vacuously
    loops = _marked_loops("pair_mca.cpp")
    assert sorted(loops.values()) == [2, 4, 4], loops


@pytest.mark.skipif(not _is_gcc(), reason="needs GCC on PATH (the report is GCC's -fopt-info-vec)")
def test_every_marked_loop_is_vectorised_in_every_instance():
    loops = _marked_loops("pair_mca.cpp")
    counts = _vectorised_counts(plug.vectorisation_report("pair_mca.cpp"), "pair_mca.cpp")
    # GCC reports each vectorised loop once per template instance (plus once per vectorised
    # epilogue), so at least N reports for a loop of N instances; fewer means an instance runs
    # scalar.  (Without -fno-trapping-math: batch_geometry 1 of 4, the other two 0.)
    short = {line: (counts.get(line, 0), n) for line, n in loops.items() if counts.get(line, 0) < n}
    assert not short, f"loops (line: (reports, instances)) not vectorised everywhere: {short}"
