"""The ``tribolmp`` command line.

Subcommands live in their own modules, ``tribolmp/cli/<name>.py``, each with

* ``HELP``: one-line summary;
* ``configure(parser)``: add arguments (or nested subparsers) to ``parser``;
* ``run(args) -> int``: compose library calls and return an exit code.

Modules are imported only when their command is used, so ``tribolmp contact``
never loads LAMMPS.  Errors map to exit codes: bad input (``SetupError`` and
argument errors) -> 2, run failures (``RunError``) -> 3; each prints one line
on stderr, never a traceback.
"""

from __future__ import annotations

import argparse
import importlib
import math
import sys
from collections.abc import Sequence
from typing import Any, NoReturn

from ..errors import EXIT_RUN, EXIT_SETUP, RunError, SetupError, TribolmpError
from ..jsonio import dumps

__all__ = ["COMMANDS", "OneLineParser", "emit_json", "float_list", "main", "seed_type"]

#: command -> (module, one-line help); the module is imported only when its command runs.
COMMANDS: dict[str, tuple[str, str]] = {
    "info": (
        "tribolmp.cli.info",
        "versions of tribolmp, LAMMPS (packages), numpy, ase, MDAnalysis, MPI",
    ),
    "check": ("tribolmp.cli.check", "validate a scene file"),
    "run": (
        "tribolmp.cli.run",
        "run a scene through the multiscale chain (default: the embedded scene)",
    ),
    "sweep": (
        "tribolmp.cli.sweep",
        "parameter campaign over a scene on Dask (LocalCluster or --scheduler)",
    ),
    "bench": ("tribolmp.cli.bench", "gather the speed-against-error tables of every model"),
    "contact": ("tribolmp.cli.contact", "contact mechanics: MDR and half-space BEM"),
    "lubrication": (
        "tribolmp.cli.lubrication",
        "reduced lubrication forces and the Reynolds reference",
    ),
    "topography": (
        "tribolmp.cli.topography",
        "stochastic surface evolution (Eq. 23); measured topography files",
    ),
    "tribospec": ("tribolmp.cli.tribospec", "tribospectroscopy: simulate and fit F(amplitude)"),
    "macro": ("tribolmp.cli.macro", "rigid body on contact springs: stick-slip and oscillation"),
    "mca": ("tribolmp.cli.mca", "movable cellular automata friction on LAMMPS"),
    "analysis": (
        "tribolmp.cli.analysis",
        "measurements on MCA outputs (Eq. 23 fit of a surface profile)",
    ),
}


class OneLineParser(argparse.ArgumentParser):
    """ArgumentParser whose errors are one line on stderr and exit code 2."""

    def error(self, message: str) -> NoReturn:  # noqa: D102
        self.exit(EXIT_SETUP, f"{self.prog}: error: {' '.join(message.split())}\n")


def build_parser(command: str | None = None) -> OneLineParser:
    """Build the top-level parser; configure only ``command``'s subparser."""
    from .. import __version__

    parser = OneLineParser(
        prog="tribolmp", description="Multiscale simulation of friction, lubrication and wear."
    )
    parser.add_argument("--version", action="version", version=f"tribolmp {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=OneLineParser)
    for name, (module, help_) in COMMANDS.items():
        p = sub.add_parser(name, help=help_, description=help_)
        if name == command:
            importlib.import_module(module).configure(p)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``tribolmp`` console script.

    Parameters
    ----------
    argv : sequence of str, optional
        Arguments (default ``sys.argv[1:]``).

    Returns
    -------
    int
        Exit code: 0 success, 2 bad input, 3 run failure, 130 interrupted.
    """
    argv = list(sys.argv[1:] if argv is None else argv)
    command = next((a for a in argv if not a.startswith("-")), None)
    parser = build_parser(command if command in COMMANDS else None)
    try:
        args = parser.parse_args(argv)
    except SystemExit as exc:  # argparse's own exit (help, version, errors)
        return int(exc.code or 0)
    if args.command is None:
        parser.print_help()
        return EXIT_SETUP
    module = importlib.import_module(COMMANDS[args.command][0])
    try:
        return int(module.run(args) or 0)
    except BrokenPipeError:
        # The reader went away (``tribolmp check --json | head``): stop quietly, as
        # coreutils do, and keep Python from complaining again when it flushes stdout at exit.
        import os

        try:
            os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        except OSError:
            pass
        return 141
    except SetupError as exc:
        print(f"tribolmp {args.command}: {exc}", file=sys.stderr)
        return EXIT_SETUP
    except (RunError, TribolmpError) as exc:
        print(f"tribolmp {args.command}: {exc}", file=sys.stderr)
        return EXIT_RUN
    except KeyboardInterrupt:
        print(
            f"tribolmp {args.command}: interrupted; finished results and checkpoints are kept",
            file=sys.stderr,
        )
        return 130
    except OSError as exc:
        # A file system failure while running (disk full, a folder made read-only meanwhile):
        # a run failure, said in one line with the path; user-given paths are checked up front
        # and exit 2 before this can happen.
        name = getattr(exc, "filename", None)
        what = f"cannot write or read {name}: " if name else "file system error: "
        print(f"tribolmp {args.command}: {what}{exc.strerror or exc}", file=sys.stderr)
        return EXIT_RUN


def emit_json(obj: Any, stream=None) -> None:
    """Print ``obj`` as strict JSON (numpy types converted, NaN/inf as null)."""
    print(dumps(obj), file=stream or sys.stdout)


def seed_type(text: str) -> int:
    """Parse a random seed, an integer >= 0 (argparse type).

    Numpy's SeedSequence refuses negatives.
    """
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected an integer >= 0, got {text!r}") from None
    if value < 0:
        raise argparse.ArgumentTypeError(f"expected an integer >= 0, got {value}")
    return value


def float_list(text: str) -> list[float]:
    """Parse comma-separated floats (argparse type), e.g. ``1e5,1e6``."""
    try:
        values = [float(t) for t in text.split(",") if t.strip()]
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"expected comma-separated numbers, got {text!r}"
        ) from None
    if not values or not all(math.isfinite(v) for v in values):
        raise argparse.ArgumentTypeError(f"expected comma-separated finite numbers, got {text!r}")
    return values
