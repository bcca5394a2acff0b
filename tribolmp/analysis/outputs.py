"""Reading an MCA output directory: ``meta.json``, ``friction.csv`` and the dump.

This is the unit boundary of the analysis package.  The LAMMPS decks run in
``units nano``; the dump therefore holds positions in nm and velocities in
nm/ns (= m/s).  MDAnalysis keeps those raw numbers (its LAMMPS dump reader does
no unit conversion) and assumes 1 ps per MD step.  Here

* the time axis is set explicitly from ``meta.json`` (MDAnalysis ``ts.time`` is
  then the true time in ps, and every analysis reports seconds);
* positions are shifted back to the absolute LAMMPS frame (MDAnalysis moves the
  box origin to 0 in every frame, which would make heights jump when the box
  is shrink-wrapped along the normal);
* analyses convert lengths to metres when they store results.

The output-directory contract (written by :func:`tribolmp.lammps.mca.run_mca`):

``traj.lammpstrj``
    ``dump custom`` with columns ``id mol type x y z vx vy vz radius c_nbond``.
``friction.csv``
    columns ``time_s,friction_N,normal_N,top_x_m`` (SI).
``meta.json``
    units, timestep, dump interval (steps and seconds), molecule-id meaning
    (1 base, 2 lower body, 3 upper body, 4 rigid slider), box size (m),
    automaton diameter (m), sliding velocity (m/s), pressure (Pa).
"""

from __future__ import annotations

import json
import math
import warnings
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import DataFileError
from ..units import LAMMPS_NANO

__all__ = [
    "DUMP_COLUMNS",
    "FRICTION_COLUMNS",
    "MOL_BASE",
    "MOL_LOWER",
    "MOL_UPPER",
    "MOL_SLIDER",
    "MCAMeta",
    "read_meta",
    "read_friction_csv",
    "open_trajectory",
    "resume_frames",
    "FromOutput",
    "trajectory_path",
]

#: Per-atom columns of ``traj.lammpstrj`` (the contract with the simulation side).
DUMP_COLUMNS = ("id", "mol", "type", "x", "y", "z", "vx", "vy", "vz", "radius", "c_nbond")
#: Columns of ``friction.csv``.
FRICTION_COLUMNS = ("time_s", "friction_N", "normal_N", "top_x_m")
#: Molecule ids: fixed base, lower deformable body, upper deformable body, rigid slider.
MOL_BASE, MOL_LOWER, MOL_UPPER, MOL_SLIDER = 1, 2, 3, 4

#: Columns the analyses read besides positions and velocities.
_EXTRA_COLUMNS = ["mol", "radius", "c_nbond"]
#: Optional per-automaton columns of the mca law (contract C2, ``fix mca_state``): its links, and
#: its links to automata of another body.  Read when the dump has them (any of the spellings).
LINK_COLUMNS = {"n_links": ("f_mca_state[8]", "n_links"),
                "n_cross_body_links": ("f_mca_state[9]", "n_cross_body_links", "c_ncross")}
_EXTRA_COLUMNS += [name for names in LINK_COLUMNS.values() for name in names]

# meta.json key -> accepted spellings (first is canonical).  Both sides of the
# contract are written in parallel, so the reader accepts the obvious variants
# and fails with a message naming the canonical key.
_META_KEYS: dict[str, tuple[str, ...]] = {
    "dt_s": ("dt_s", "timestep_s", "dt"),
    "dump_interval_steps": (
        "dump_interval_steps",
        "dump_every_steps",
        "dump_every",
        "dump_interval",
    ),
    "dump_interval_s": ("dump_interval_s", "dump_every_s"),
    "velocity_m_s": ("velocity_m_s", "sliding_velocity_m_s", "velocity"),
    "pressure_Pa": ("pressure_Pa", "pressure_pa", "pressure"),
    "automaton_diameter_m": ("automaton_diameter_m", "diameter_m", "automaton_diameter"),
    "box_m": ("box_m", "box_size_m", "box"),
    "dimension": ("dimension", "dim"),
    "normal_axis": ("normal_axis",),
    "density_kg_m3": ("density_kg_m3", "density"),
    "atom_steps_per_s": ("atom_steps_per_s",),
    "time_s": ("time_s", "simulated_time_s"),
}


def _lookup(raw: Mapping[str, Any], key: str) -> Any:
    for alias in _META_KEYS[key]:
        if alias in raw:
            return raw[alias]
    # nested sections such as {"run": {...}} or {"material": {...}}; never the "units" block,
    # which maps every field (also one a running job has not written yet) to its unit string
    for section, value in raw.items():
        if isinstance(value, Mapping) and section != "units":
            for alias in _META_KEYS[key]:
                if alias in value:
                    return value[alias]
    return None


@dataclass(frozen=True)
class MCAMeta:
    """The parts of ``meta.json`` the analyses need, in SI units.

    Attributes
    ----------
    dt_s : float
        MD timestep (s).
    dump_interval_steps : int
        MD steps between dump frames.
    dump_interval_s : float
        Time between dump frames (s).
    velocity_m_s : float
        Sliding velocity of the rigid top layer (m/s).
    automaton_diameter_m : float
        Automaton diameter d (m).
    dimension : int
        2 or 3.
    normal_axis : int
        Index (0, 1, 2) of the axis normal to the sliding interface; ``y`` (1)
        unless ``meta.json`` says otherwise.
    box_lengths_m : tuple of float
        Box edge lengths (m).
    pressure_Pa : float or None
        Normal pressure (Pa).
    density_kg_m3 : float or None
        Mass density of the automata (kg/m^3), if recorded.
    atom_steps_per_s : float or None
        Measured throughput of the run, if recorded.
    time_s : float or None
        Simulated time (s), if recorded.
    raw : dict
        The whole ``meta.json``.
    """

    dt_s: float
    dump_interval_steps: int
    dump_interval_s: float
    velocity_m_s: float
    automaton_diameter_m: float
    dimension: int = 2
    normal_axis: int = 1
    box_lengths_m: tuple[float, ...] = ()
    pressure_Pa: float | None = None
    density_kg_m3: float | None = None
    atom_steps_per_s: float | None = None
    time_s: float | None = None
    raw: dict = field(default_factory=dict, repr=False, compare=False)

    @property
    def lateral_axes(self) -> tuple[int, ...]:
        """Axes in the sliding plane: ``(0,)`` in 2D, the two non-normal axes in 3D."""
        if self.dimension == 2:
            return (0,)
        return tuple(a for a in range(3) if a != self.normal_axis)

    @classmethod
    def from_dict(cls, raw: Mapping[str, Any], source: str = "meta.json") -> MCAMeta:
        """Build from the parsed ``meta.json``; missing or bad keys raise :class:`DataFileError`."""

        def need(key: str) -> Any:
            value = _lookup(raw, key)
            if value is None:
                raise DataFileError(f"{source}: {key}: expected a value, got nothing (missing key)")
            return value

        def num(key: str, value: Any, positive: bool = True) -> float:
            try:
                v = float(value)
            except (TypeError, ValueError):
                raise DataFileError(f"{source}: {key}: expected a number, got {value!r}") from None
            if not math.isfinite(v) or (positive and v <= 0):
                raise DataFileError(
                    f"{source}: {key}: expected a finite positive number, got {value!r}"
                )
            return v

        dt = num("dt_s", need("dt_s"))
        every = _lookup(raw, "dump_interval_steps")
        every_s = _lookup(raw, "dump_interval_s")
        if every is None and every_s is None:
            raise DataFileError(
                f"{source}: dump_interval_s: expected a value, got nothing (missing key)"
            )
        if every is None:
            every = round(num("dump_interval_s", every_s) / dt)
        every = int(num("dump_interval_steps", every))
        every_s = num("dump_interval_s", every_s) if every_s is not None else every * dt
        if not math.isclose(every_s, every * dt, rel_tol=1e-6):
            raise DataFileError(
                f"{source}: dump_interval_s: expected "
                f"dump_interval_steps*dt_s = {every * dt:g} s, got {every_s!r}"
            )
        dim = int(_lookup(raw, "dimension") or 2)
        if dim not in (2, 3):
            raise DataFileError(f"{source}: dimension: expected 2 or 3, got {dim!r}")
        axis = _lookup(raw, "normal_axis")
        if axis is None:
            axis = 1
        if isinstance(axis, str):
            axis = "xyz".index(axis.lower()) if axis.lower() in ("x", "y", "z") else -1
        if axis not in (0, 1, 2) or (dim == 2 and axis == 2):
            raise DataFileError(
                f"{source}: normal_axis: expected 'y' (or 'z' "
                f"in 3D), got {_lookup(raw, 'normal_axis')!r}"
            )
        box = _lookup(raw, "box_m")
        lengths: tuple[float, ...] = ()
        if box is not None:
            arr = np.asarray(box, dtype=float)
            if arr.ndim == 2:  # [[lo, hi], ...]
                arr = arr[:, 1] - arr[:, 0]
            elif isinstance(box, Mapping):
                arr = np.asarray([float(box[k]) for k in sorted(box)])
            lengths = tuple(float(v) for v in np.ravel(arr))

        def opt(key: str) -> float | None:
            value = _lookup(raw, key)
            return None if value is None else num(key, value, positive=False)

        pressure = _lookup(raw, "pressure_Pa")
        return cls(
            dt_s=dt,
            dump_interval_steps=every,
            dump_interval_s=every_s,
            velocity_m_s=num("velocity_m_s", need("velocity_m_s")),
            automaton_diameter_m=num("automaton_diameter_m", need("automaton_diameter_m")),
            dimension=dim,
            normal_axis=int(axis),
            box_lengths_m=lengths,
            pressure_Pa=None if pressure is None else num("pressure_Pa", pressure, positive=False),
            density_kg_m3=opt("density_kg_m3"),
            atom_steps_per_s=opt("atom_steps_per_s"),
            time_s=opt("time_s"),
            raw=dict(raw),
        )


def read_meta(out_dir: str | Path) -> MCAMeta:
    """Read and check ``out_dir/meta.json``.

    Parameters
    ----------
    out_dir : str or Path
        An MCA output directory (or the ``meta.json`` path itself).

    Returns
    -------
    MCAMeta
        The run's metadata in SI units.
    """
    path = Path(out_dir)
    if path.is_dir():
        path = path / "meta.json"
    try:
        raw = json.loads(path.read_text())
    except FileNotFoundError:
        raise DataFileError(f"{path}: expected an MCA meta.json, got no such file") from None
    except json.JSONDecodeError as exc:
        raise DataFileError(
            f"{path}: expected valid JSON, got {exc.msg} at line {exc.lineno}"
        ) from None
    if not isinstance(raw, Mapping):
        raise DataFileError(f"{path}: expected a JSON object, got {type(raw).__name__}")
    return MCAMeta.from_dict(raw, source=str(path))


def read_friction_csv(path: str | Path) -> dict[str, np.ndarray]:
    """Read ``friction.csv`` (columns ``time_s,friction_N,normal_N,top_x_m``, SI).

    Parameters
    ----------
    path : str or Path
        The CSV file or the output directory holding it.

    Returns
    -------
    dict of str to ndarray
        One float array per column; rows with non-finite values are an error.
    """
    path = Path(path)
    if path.is_dir():
        path = path / "friction.csv"
    if not path.exists():
        raise DataFileError(f"{path}: expected a friction.csv, got no such file")
    with path.open() as fh:
        header = [h.strip() for h in fh.readline().split(",")]
    missing = [c for c in FRICTION_COLUMNS if c not in header]
    if missing:
        raise DataFileError(
            f"{path}: header: expected columns {list(FRICTION_COLUMNS)}, got {header}"
        )
    data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    if data.shape[0] < 2:
        raise DataFileError(f"{path}: expected at least 2 rows, got {data.shape[0]}")
    if not np.all(np.isfinite(data)):
        row = int(np.argwhere(~np.isfinite(data))[0, 0]) + 2
        raise DataFileError(f"{path}: line {row}: expected finite numbers, got NaN/inf")
    t = data[:, header.index("time_s")]
    # A resumed run appends from its last restart, repeating the rows written
    # after it: keep, for every time, the row of the latest (resumed) segment.
    keep = _last_segment_mask(t)
    out = {name: data[keep, header.index(name)].copy() for name in header if name}
    return out


def _last_segment_mask(values: np.ndarray) -> np.ndarray:
    """Return True where ``values[i]`` is smaller than every later value.

    This drops rows superseded by a resume.
    """
    values = np.asarray(values, dtype=float)
    later_min = np.minimum.accumulate(values[::-1])[::-1]
    later_min = np.append(later_min[1:], np.inf)
    return values < later_min


def resume_frames(universe) -> tuple[np.ndarray, np.ndarray]:
    """Frames of a dump to analyse and their MD steps, dropping those superseded by a resume.

    A run resumed from a restart file appends to the dump from the restart
    step on, so the frames written between that restart and the interruption
    appear twice; only the later copy is kept.

    Parameters
    ----------
    universe : MDAnalysis.Universe
        From :func:`open_trajectory`.

    Returns
    -------
    frames : ndarray of int
        Frame indices with strictly increasing steps.
    steps : ndarray of int
        Their MD step numbers.
    """
    reader = universe.trajectory
    n = reader.n_frames
    steps = np.empty(n, dtype=np.int64)
    with open(reader.filename) as fh:
        for i, off in enumerate(reader._offsets):
            fh.seek(off)
            fh.readline()
            steps[i] = int(fh.readline())
    keep = np.nonzero(_last_segment_mask(steps))[0]
    return keep, steps[keep]


def trajectory_path(out_dir: str | Path) -> Path:
    """Path of the dump in an output directory (``traj.lammpstrj``)."""
    return Path(out_dir) / "traj.lammpstrj"


def _reader_class():
    """Define (once) the MDAnalysis reader subclass; MDAnalysis is imported lazily."""
    global _READER
    if _READER is not None:
        return _READER
    from MDAnalysis.coordinates.LAMMPS import DumpReader

    class MCADumpReader(DumpReader):
        """LAMMPS ``dump custom`` reader that keeps absolute positions.

        Parses each frame with numpy (one call instead of a Python loop over
        atoms) and stores, besides MDAnalysis's usual ``positions`` and
        ``velocities`` (raw dump units: nm and nm/ns), ``ts.data["box_lo"]``
        (nm) and the additional columns.  Positions are *not* shifted to the
        box origin, so heights are comparable between frames.
        """

        format = "MCADUMP"
        #: MD timestep (ps), set by :func:`open_trajectory`; the reader's
        #: ``dt`` is the time between frames.
        md_dt_ps = None

        def _read_next_timestep(self):
            f = self._file
            ts = self.ts
            ts.frame += 1
            if ts.frame >= len(self):
                raise EOFError
            f.readline()
            step = int(f.readline())
            f.readline()
            n = int(f.readline())
            if n != self.n_atoms:
                raise DataFileError(
                    f"{self.filename}: frame {ts.frame}: expected "
                    f"{self.n_atoms} atoms (atoms lost?), got {n}"
                )
            f.readline()
            bounds = np.array([f.readline().split()[:2] for _ in range(3)], dtype=float)
            names = f.readline().split()[2:]
            lines = [f.readline() for _ in range(n)]
            try:
                table = np.array(" ".join(lines).split(), dtype=float).reshape(n, len(names))
            except ValueError:
                raise DataFileError(
                    f"{self.filename}: frame {ts.frame}: expected {n} rows of {len(names)} numbers"
                ) from None
            col = {name: i for i, name in enumerate(names)}
            for needed in ("id", "x", "y", "z"):
                if needed not in col:
                    raise DataFileError(
                        f"{self.filename}: ATOMS: expected column {needed!r}, got {names}"
                    )
            order = np.argsort(table[:, col["id"]], kind="stable")
            table = table[order]
            ts.data["step"] = step
            # ts.time (ps) from the MD step and the MD timestep; ts.dt stays the time between frames
            ts.data["time"] = step * (self.md_dt_ps if self.md_dt_ps is not None else ts.dt)
            ts.data["box_lo"] = bounds[:, 0].copy()
            ts.dimensions = [*(bounds[:, 1] - bounds[:, 0]), 90.0, 90.0, 90.0]
            ts.positions = table[:, [col["x"], col["y"], col["z"]]]
            if all(c in col for c in ("vx", "vy", "vz")):
                ts.has_velocities = True
                ts.velocities = table[:, [col["vx"], col["vy"], col["vz"]]]
            ts.data["id"] = table[:, col["id"]].astype(np.int64)
            extra = self._additional_columns or []
            for name in extra:
                if name in col:
                    ts.data[name] = table[:, col[name]].copy()
            return ts

    _READER = MCADumpReader
    return _READER


_READER = None


def open_trajectory(
    out_dir: str | Path, meta: MCAMeta | None = None, dump: str | Path | None = None
):
    """Open the dump of an MCA run as an MDAnalysis Universe.

    Parameters
    ----------
    out_dir : str or Path
        The output directory (holds ``meta.json`` and ``traj.lammpstrj``).
    meta : MCAMeta, optional
        Already-read metadata (default: read ``out_dir/meta.json``).
    dump : str or Path, optional
        Dump file to use instead of ``out_dir/traj.lammpstrj``.

    Returns
    -------
    MDAnalysis.Universe
        Positions in nm (absolute LAMMPS frame), velocities in nm/ns (= m/s),
        ``u.trajectory.dt`` the time between dump frames (ps), ``ts.time``
        the true time of each frame (ps, MD step x MD timestep), and per frame
        ``ts.data`` with ``mol``, ``radius`` (nm), ``c_nbond``, ``step`` and
        ``box_lo`` (nm).
    """
    import MDAnalysis as mda

    meta = meta or read_meta(out_dir)
    path = Path(dump) if dump is not None else trajectory_path(out_dir)
    if not path.exists():
        raise DataFileError(f"{path}: expected a LAMMPS dump, got no such file")
    with path.open() as fh:
        head = [fh.readline() for _ in range(9)]
    if not head[0].startswith("ITEM: TIMESTEP") or not head[8].startswith("ITEM: ATOMS"):
        raise DataFileError(
            f"{path}: expected a LAMMPS dump custom file, got first line {head[0].strip()!r}"
        )
    names = head[8].split()[2:]
    missing = [c for c in DUMP_COLUMNS if c not in names]
    if missing:
        raise DataFileError(f"{path}: ATOMS: expected columns {list(DUMP_COLUMNS)}, got {names}")
    _reader_class()
    # MDAnalysis's time unit is ps.  u.trajectory.dt must be the time between frames (what an MSD or
    # any per-frame analysis divides by), and ts.time the true time of the frame: the dump interval
    # in ps is the reader's dt, and ts.time = step x MD timestep (so resumed or irregular dumps keep
    # their true times).
    with warnings.catch_warnings():
        # The topology has no masses (all 1.0) and no elements; that is intended.
        warnings.simplefilter("ignore")
        u = mda.Universe(
            str(path),
            topology_format="LAMMPSDUMP",
            format="MCADUMP",
            additional_columns=_EXTRA_COLUMNS,
            dt=meta.dump_interval_s / 1e-12,
        )
    u.trajectory.md_dt_ps = meta.dt_s / 1e-12
    u.trajectory.rewind()  # re-read frame 0 with the MD timestep known
    return u


class FromOutput:
    """Mixin of the trajectory analyses: ``Class.from_output(out_dir, **options)``."""

    @classmethod
    def from_output(cls, out_dir, **kwargs):
        """Open the MCA output directory ``out_dir`` and build the analysis on it."""
        meta = read_meta(out_dir)
        return cls(open_trajectory(out_dir, meta), meta, **kwargs)


#: Conversion factor from dump lengths (nm) to metres.
NM = LAMMPS_NANO["length"]
