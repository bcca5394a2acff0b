"""Exception hierarchy of tribolmp.

Two families are kept apart, as ASE does, because the command line and the
workflows treat them differently:

* :class:`SetupError` -- the user's input is wrong (a scene file, a surface
  file, a parameter out of range).  Raised *before* any expensive work starts.
  The CLI prints the one-line message and exits with code 2.
* :class:`RunError` -- a valid input failed while running (a LAMMPS error, a
  numerical blow-up, lost atoms).  The CLI prints the one-line message and
  exits with code 3; whatever was already written (checkpoints, restart
  files, finished stages) is kept.

Every message is a single line of the form ``where: expected ..., got ...``
so that it can be printed without a traceback.
"""

from __future__ import annotations

__all__ = [
    "TribolmpError",
    "SetupError",
    "ParameterError",
    "SceneError",
    "SurfaceFileError",
    "DataFileError",
    "MissingFeatureError",
    "RunError",
    "LammpsError",
    "ConvergenceError",
    "BlowUpError",
    "NoContactError",
    "StageError",
    "EXIT_SETUP",
    "EXIT_RUN",
]

#: CLI exit code for bad input.
EXIT_SETUP = 2
#: CLI exit code for a run failure.
EXIT_RUN = 3


def _one_line(text: str) -> str:
    return " ".join(str(text).split())


class TribolmpError(Exception):
    """Base class of all tribolmp errors; its ``str`` is always one line."""

    exit_code = EXIT_RUN

    def __str__(self) -> str:  # noqa: D105
        return _one_line(super().__str__())


class SetupError(TribolmpError, ValueError):
    """Bad input detected before a run starts (exit code 2)."""

    exit_code = EXIT_SETUP


class ParameterError(SetupError):
    """A parameter is missing, of the wrong type or out of range.

    Parameters
    ----------
    field : str
        Name of the offending field, e.g. ``"[materials].poisson_ratio"`` or
        ``"radius"``.
    expected : str
        What was expected, e.g. ``"a float in (-1, 0.5)"``.
    got : object
        The value received.
    source : str, optional
        File (or other origin) the value came from; prefixed to the message.
    """

    def __init__(self, field: str, expected: str, got: object, source: str | None = None):
        self.field = field
        self.expected = expected
        self.got = got
        self.source = source
        prefix = f"{source}: " if source else ""
        super().__init__(f"{prefix}{field}: expected {expected}, got {got!r}")


class SceneError(ParameterError):
    """A scene file is malformed (unknown key, wrong type, out of range...)."""


class SurfaceFileError(SetupError):
    """A height-map file cannot be used (wrong shape, non-finite values...)."""


class DataFileError(SetupError):
    """A measured-data file (CSV, dump) cannot be used."""


class MissingFeatureError(SetupError):
    """A required external capability (LAMMPS package or style, MPI) is missing."""


class RunError(TribolmpError, RuntimeError):
    """A valid input failed while running (exit code 3)."""

    exit_code = EXIT_RUN


class LammpsError(RunError):
    """LAMMPS reported an error.

    Attributes
    ----------
    message : str
        LAMMPS's own error text.
    line : str or None
        The input line that failed, when known.
    step : int or None
        The MD step at which it failed, when known.
    """

    def __init__(self, message: str, line: str | None = None, step: int | None = None):
        self.message = _one_line(message)
        self.line = line.strip() if line else None
        self.step = step
        text = f"LAMMPS error: {self.message}"
        if self.line:
            text += f" [input line: {self.line}]"
        if step is not None:
            text += f" [step {step}]"
        super().__init__(text)


class ConvergenceError(RunError):
    """An iterative solver did not converge."""


class BlowUpError(RunError):
    """A simulation produced NaN/inf or left its physical range."""


class NoContactError(RunError):
    """The bodies are not in contact where contact is required."""


class StageError(RunError):
    """A stage of the multiscale chain failed; names the stage and the cause."""

    def __init__(self, stage: str, cause: BaseException | str):
        self.stage = stage
        self.cause = cause
        super().__init__(f"stage '{stage}' failed: {cause}")
