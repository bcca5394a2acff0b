"""Classification of LAMMPS failures of an MCA run into one-line, actionable errors."""

from __future__ import annotations

import re

from ...errors import BlowUpError, LammpsError, RunError

__all__ = ["CAUSES", "RestartUnreadableError", "classify", "nonfinite_error"]

#: (pattern of LAMMPS's message, cause named to the user)
CAUSES = (
    (re.compile(r"lost atoms", re.IGNORECASE), "lost atoms (an automaton left the box)"),
    (
        re.compile(r"bond atoms? .*missing|atom missing in bpm bond", re.IGNORECASE),
        "a link stretched past the communication cutoff (bond atoms missing)",
    ),
    (
        re.compile(
            r"non-numeric atom|out of range "
            r"atoms|\bnan\b.*(force|coord|position)|non-numeric (pressure|box)",
            re.IGNORECASE,
        ),
        "non-finite positions or forces (NaN)",
    ),
)


class RestartUnreadableError(RunError):
    """LAMMPS could not set up from a restart file (cut, or written by another version)."""

    #: exit code of an MPI rank that hit it (the caller then drops the file and resumes earlier)
    rank_exit_code = 4


def classify(exc: LammpsError, step: int | None) -> RunError:
    """Return a :class:`BlowUpError` naming the step and cause, or ``exc`` itself (setup errors)."""
    for pattern, cause in CAUSES:
        if pattern.search(exc.message):
            where = step if step is not None else "?"
            return BlowUpError(
                f"MCA run failed at step {where}: {cause}; last restart kept; LAMMPS: {exc.message}"
            )
    return exc


def nonfinite_error(step: int, out) -> BlowUpError:
    """Return the error of a chunk that ended with non-finite energy or forces."""
    return BlowUpError(
        f"MCA run failed at step {step}: non-finite kinetic energy or forces (NaN); "
        f"last restart kept in {out}"
    )
