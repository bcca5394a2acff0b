"""Measured topographies.

Instrument files through SurfaceTopography, tribolmp's own formats natively.

SurfaceTopography (the ContactEngineering reader) reads some 40 instrument
formats (x3p, sur, opd/opdx, datx, gwy, MetroPro, plu/plux, vk, zon, di/spm,
ibw, nc, ...).  This module turns any of them, and tribolmp's own ``.npy`` +
JSON, ESRI ``.asc`` and ``x [y] z`` tables, into one :class:`Surface`: heights
in m on a uniform grid with square pixels, plus where the units and the pixel
size came from (``unit_source``), so that reports can say which was used.

Conventions
-----------
* Arrays are ``h[iy, ix]`` (rows along y), as everywhere in tribolmp;
  SurfaceTopography stores ``heights()[ix, iy]``, so it is transposed here.
* Units and the physical size come from the file's metadata.  An explicit
  override (``pixel_size=``, ``unit=``) replaces them only when given, and
  is then recorded as the source.  A file without a size or unit and no
  override is refused (one line), never guessed.
* Detrending is an explicit option (``detrend="none"`` by default):
  ``"mean"``, ``"plane"`` (rms-minimising tilt) or ``"curvature"``.
* Model inputs need a uniform grid with finite heights: nonuniform line scans
  are refused (one line) and missing data points are refused unless
  ``missing="fill"`` (SurfaceTopography's harmonic imputation).  ``info``
  handles both (statistics over the measured points).

SurfaceTopography is an optional dependency (extra ``surfaces``; installed
by the README's commands): :func:`require_surfacetopography` gives the one
line that says how to install it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ...errors import MissingFeatureError, SurfaceFileError

__all__ = [
    "Surface",
    "read_surface",
    "topography_info",
    "write_surface",
    "to_surfacetopography",
    "require_surfacetopography",
    "rms_values",
    "surface_provenance",
    "LENGTH_UNITS",
    "DETREND_MODES",
]

#: Length units accepted as overrides (factor to m).  "um" is the ASCII spelling of µm.
LENGTH_UNITS = {
    "m": 1.0,
    "mm": 1e-3,
    "um": 1e-6,
    "µm": 1e-6,
    "μm": 1e-6,
    "nm": 1e-9,
    "A": 1e-10,
    "Å": 1e-10,
    "pm": 1e-12,
}

#: tribolmp detrend names -> SurfaceTopography detrend modes.
DETREND_MODES = {"none": None, "mean": "center", "plane": "height", "curvature": "curvature"}

#: Suffixes read by tribolmp's own readers (io.py); everything else goes to SurfaceTopography.
NATIVE_SUFFIXES = (".npy", ".json")


@dataclass(frozen=True)
class Surface:
    """A height map in SI units with its provenance.

    Attributes
    ----------
    h : ndarray
        Heights (m), shape ``(n,)`` (line scan) or ``(ny, nx)`` (map, rows along y).
    pixel_size : float
        Grid spacing (m), the same along x and y.
    format : str
        Reader that read the file (``"tribolmp-npy"``, ``"esri-asc"``, ``"xyz"``
        or SurfaceTopography's format name such as ``"x3p"``).
    unit_source : str
        Where units and pixel size came from: ``"file metadata"``,
        ``"override"`` or ``"file metadata + override (...)"``.
    detrend : str
        Detrending applied (``"none"``, ``"mean"``, ``"plane"``, ``"curvature"``).
    path : str
        The file.
    periodic : bool
        Whether the file declares the map periodic.
    notes : tuple of str
        What was done to the data (filled points, ...).
    """

    h: np.ndarray
    pixel_size: float
    format: str
    unit_source: str
    detrend: str = "none"
    path: str = ""
    periodic: bool = False
    notes: tuple[str, ...] = field(default_factory=tuple)

    @property
    def grid(self) -> list[int]:
        """``[nx, ny]`` (``[n, 1]`` for a line scan)."""
        return [int(self.h.shape[-1]), int(self.h.shape[0]) if self.h.ndim == 2 else 1]

    @property
    def size_m(self) -> list[float]:
        """Physical size ``[Lx, Ly]`` in m (``Ly = 0`` for a line scan)."""
        nx, ny = self.grid
        return [nx * self.pixel_size, ny * self.pixel_size if self.h.ndim == 2 else 0.0]

    def describe(self) -> str:
        """One line for reports: file, format, grid, pixel size and where they came from."""
        nx, ny = self.grid
        grid = f"{nx}x{ny}" if self.h.ndim == 2 else f"{nx} points"
        return (
            f"{self.path} ({self.format}, {grid}, pixel "
            f"{self.pixel_size:.4g} m from {self.unit_source}, "
            f"detrend {self.detrend})"
        )


def require_surfacetopography(why: str):
    """Import SurfaceTopography or raise one line saying how to install it."""
    try:
        import SurfaceTopography  # noqa: F401
        from SurfaceTopography import open_topography  # noqa: F401
    except ImportError:
        raise MissingFeatureError(
            f"{why}: expected the SurfaceTopography package "
            "(pip install 'tribolmp[surfaces]'), got ImportError"
        ) from None
    import SurfaceTopography

    return SurfaceTopography


def _unit_factor(unit: str, name: str) -> float:
    u = str(unit).strip()
    if u not in LENGTH_UNITS:
        raise SurfaceFileError(
            f"{name}: expected a length unit from {sorted(LENGTH_UNITS)}, got {unit!r}"
        )
    return LENGTH_UNITS[u]


def _check_override(pixel_size, unit):
    if pixel_size is not None and not (
        isinstance(pixel_size, (int, float))
        and not isinstance(pixel_size, bool)
        and math.isfinite(pixel_size)
        and pixel_size > 0
    ):
        raise SurfaceFileError(f"pixel_size: expected a finite number > 0 (m), got {pixel_size!r}")
    if unit is not None:
        _unit_factor(unit, "unit")


def _is_native(path: Path) -> bool:
    suffix = path.suffix.lower()
    if suffix in NATIVE_SUFFIXES:
        return True
    if suffix == ".asc":
        # An ESRI grid (our writer and GIS tools) starts with "ncols"; other
        # .asc files are instrument text exports.
        try:
            with path.open("r", errors="replace") as fh:
                first = fh.readline().split()
        except OSError:
            return False
        return bool(first) and first[0].lower() == "ncols"
    if suffix == ".xyz":
        return True
    if suffix in (".txt", ".csv", ".dat"):
        # x z / x y z columns are ours; a wider matrix is an instrument text
        # export (SurfaceTopography's reader).
        try:
            with path.open("r", errors="replace") as fh:
                for line in fh:
                    if line.strip() and not line.lstrip().startswith("#"):
                        return len(line.replace(",", " ").split()) <= 3
        except OSError:
            return False
        return True
    return False


def read_surface(
    path,
    *,
    pixel_size: float | None = None,
    unit: str | None = None,
    detrend: str = "none",
    missing: str = "refuse",
    channel: int | None = None,
) -> Surface:
    """Read a height map from any supported file into SI units.

    Parameters
    ----------
    path : str or Path
        tribolmp ``.npy`` (+ ``.json`` sidecar), ESRI ``.asc``, ``x [y] z``
        text (``.xyz``/``.txt``), or any file SurfaceTopography reads.
    pixel_size : float, optional
        Grid spacing (m).  Overrides the file's value only when given; required
        when the file has none.
    unit : str, optional
        Length unit of the file's numbers (``"m"``, ``"mm"``, ``"um"``, ``"nm"``, ...),
        for files that state none; overrides the file's unit when given.
    detrend : {"none", "mean", "plane", "curvature"}
        Detrending applied after reading (SurfaceTopography's ``center``,
        ``height`` and ``curvature`` modes).
    missing : {"refuse", "fill"}
        Missing data points: refuse the file (one line) or fill them by
        SurfaceTopography's harmonic interpolation.
    channel : int, optional
        Data channel of a multi-channel instrument file (default: its default channel).

    Returns
    -------
    Surface

    Raises
    ------
    SurfaceFileError
        One line: unreadable file, no size/unit and no override, nonuniform
        line scan, missing data, non-square pixels.
    MissingFeatureError
        An instrument file without SurfaceTopography installed.
    """
    path = Path(path)
    _check_override(pixel_size, unit)
    if detrend not in DETREND_MODES:
        raise SurfaceFileError(f"detrend: expected one of {list(DETREND_MODES)}, got {detrend!r}")
    if missing not in ("refuse", "fill"):
        raise SurfaceFileError(f"missing: expected 'refuse' or 'fill', got {missing!r}")
    _check_exists(path)
    if _is_native(path):
        from .io import read_native

        h, px, fmt, source = read_native(path, pixel_size=pixel_size, unit=unit)
        surf = Surface(
            h=h,
            pixel_size=px,
            format=fmt,
            unit_source=source,
            path=str(path),
            periodic=fmt == "tribolmp-npy",
        )
        if detrend != "none":
            top = to_surfacetopography(surf).detrend(detrend_mode=DETREND_MODES[detrend])
            surf = Surface(
                h=_heights(top),
                pixel_size=px,
                format=fmt,
                unit_source=source,
                detrend=detrend,
                path=str(path),
                periodic=False,
            )
        return surf
    top, fmt, source = _read_st(path, pixel_size=pixel_size, unit=unit, channel=channel)
    notes: list[str] = []
    if not top.is_uniform:
        raise SurfaceFileError(
            f"{path}: expected a uniformly sampled map or line scan, "
            f"got a nonuniform line scan of {top.nb_grid_pts[0]} "
            "points (tribolmp topography info reads it; resample it to a uniform grid for a model)"
        )
    if top.has_undefined_data:
        n_bad = int(np.count_nonzero(np.ma.getmaskarray(top.heights())))
        if missing == "refuse":
            raise SurfaceFileError(
                f"{path}: expected a complete height map, got {n_bad} missing data points "
                "(fill them with missing='fill' / --fill-missing, harmonic interpolation)"
            )
        top = top.interpolate_undefined_data("harmonic")
        notes.append(f"{n_bad} missing points filled (harmonic interpolation)")
    mode = DETREND_MODES[detrend]
    if mode is not None:
        top = top.detrend(detrend_mode=mode)
    sizes = np.atleast_1d(np.asarray(top.physical_sizes, dtype=float))
    pts = np.atleast_1d(np.asarray(top.nb_grid_pts, dtype=int))
    pixels = sizes / pts
    # Square pixels: the models take one spacing.  1e-6 relative allows for
    # float32 sizes in NetCDF files.
    if pixels.size == 2 and abs(pixels[0] - pixels[1]) > 1e-6 * max(pixels):
        raise SurfaceFileError(
            f"{path}: expected square pixels, got {pixels[0]:.4g} "
            f"m along x and {pixels[1]:.4g} m along y "
            "(resample the map to one spacing)"
        )
    h = _heights(top)
    if h.ndim == 2 and min(h.shape) < 2 or h.size < 2:
        raise SurfaceFileError(f"{path}: expected >= 2 points per side, got grid {list(pts)}")
    return Surface(
        h=h,
        pixel_size=float(pixels[0]),
        format=fmt,
        unit_source=source,
        detrend=detrend,
        path=str(path),
        periodic=bool(top.is_periodic),
        notes=tuple(notes),
    )


def surface_provenance(path, fallback_pixel_size: float | None = None, **options) -> str:
    """One line for reports.

    The file, its format and grid, and where units and pixel size came from.

    ``fallback_pixel_size`` is the scene's ``[roughness].pixel_size``, which is
    used (and so named) only for files that state no pixel size; ``options``
    are those of :func:`read_surface` (overrides, detrend, missing).
    """
    path = Path(path)
    try:
        return read_surface(path, **options).describe()
    except SurfaceFileError:
        if fallback_pixel_size is None or options.get("pixel_size") is not None:
            raise
    surf = read_surface(path, **{**options, "pixel_size": fallback_pixel_size})
    return surf.describe().replace(
        f"from {surf.unit_source}", "from [roughness].pixel_size (the file has none)"
    )


def _check_exists(path: Path) -> None:
    if not path.exists() and not (
        path.suffix.lower() in NATIVE_SUFFIXES and path.with_suffix(".npy").exists()
    ):
        raise SurfaceFileError(f"{path}: expected an existing height-map file, got no such file")
    if path.is_dir():
        raise SurfaceFileError(f"{path}: expected a height-map file, got a folder")


def _heights(top) -> np.ndarray:
    h = np.asarray(np.ma.filled(top.heights(), np.nan), dtype=float)
    return h.T.copy() if h.ndim == 2 else h.copy()


def _st_unit(unit: str) -> str:
    # SurfaceTopography spells micrometre and angstrom with their symbols.
    return {"um": "µm", "μm": "µm", "A": "Å"}.get(unit, unit)


def _read_st(path: Path, *, pixel_size, unit, channel):
    """Open ``path`` with SurfaceTopography.

    Returns (topography in m, in memory, format, unit_source).
    """
    require_surfacetopography(f"{path}")
    # Our own handle, closed here: some readers (NetCDF) otherwise leave the
    # file open until garbage collection.
    with open(path, "rb") as fh:
        return _read_st_open(fh, path, pixel_size=pixel_size, unit=unit, channel=channel)


def _read_st_open(fh, path: Path, *, pixel_size, unit, channel):
    from SurfaceTopography import NonuniformLineScan, Topography, UniformLineScan, open_topography
    from SurfaceTopography.Exceptions import ReadFileError

    try:
        reader = open_topography(fh)
    except (ReadFileError, ValueError, OSError) as exc:
        raise SurfaceFileError(
            f"{path}: expected a height-map file SurfaceTopography can read, got {_line(exc)}"
        ) from None
    try:
        ch = reader.default_channel if channel is None else reader.channels[channel]
    except IndexError:
        raise SurfaceFileError(
            f"{path}: channel expected in 0..{len(reader.channels) - 1}, got {channel}"
        ) from None
    file_unit = ch.unit
    sizes = ch.physical_sizes
    uniform = ch.is_uniform is not False
    # A nonuniform line scan carries its positions: no size needed.
    has_size = not uniform or (
        sizes is not None and all(v is not None for v in np.atleast_1d(sizes))
    )
    if file_unit is None and unit is None:
        raise SurfaceFileError(
            f"{path}: expected a length unit in the file or an override "
            "(unit=, --unit, [roughness].surface_unit), got none"
        )
    if not has_size and pixel_size is None:
        raise SurfaceFileError(
            f"{path}: expected a physical size in the file or "
            "a pixel size override (pixel_size=, --pixel-size, "
            "[roughness].surface_pixel_size, m), got none"
        )
    kwargs: dict[str, Any] = {}
    if file_unit is None:
        kwargs["unit"] = _st_unit(unit)
    if not has_size:
        # Provisional size in pixels; replaced by the override below.
        kwargs["physical_sizes"] = tuple(float(n) for n in ch.nb_grid_pts)
    try:
        top = reader.topography(channel_index=ch.index, **kwargs)
    except (ReadFileError, ValueError, KeyError) as exc:
        raise SurfaceFileError(
            f"{path}: expected a readable topography channel, got {_line(exc)}"
        ) from None
    parts = []
    if unit is not None:
        parts.append(
            f"unit {unit} (override)"
            if file_unit is None
            else f"unit {unit} (override of the file's {file_unit})"
        )
    if pixel_size is not None:
        parts.append(
            "pixel size (override)" if not has_size else "pixel size (override of the file's)"
        )
    if not parts:
        source = "file metadata"
    elif file_unit is None and not has_size:
        source = "override (" + ", ".join(p.replace(" (override)", "") for p in parts) + ")"
    else:
        source = "file metadata + " + ", ".join(parts)
    if not top.is_uniform:
        if unit is not None and file_unit is not None:
            raise SurfaceFileError(
                f"{path}: a unit override of a nonuniform line "
                f"scan is not supported (file unit {file_unit})"
            )
        x, h = top.to_unit("m").positions_and_heights()
        return (
            NonuniformLineScan(np.array(x), np.array(h), unit="m", info=top.info),
            str(reader.format()),
            source,
        )
    # Rebuild in m: heights and lateral axes scaled by the unit (the
    # override, or the file's), the pixel by the override.
    fac = _unit_factor(
        unit if unit is not None else ("um" if str(top.unit) in ("µm", "μm") else str(top.unit)),
        "unit",
    )
    h = np.ma.array(top.heights(), copy=True) * fac
    n = [int(v) for v in np.atleast_1d(top.nb_grid_pts)]
    if pixel_size is not None:
        new_sizes = [k * pixel_size for k in n]
    else:
        new_sizes = [float(v) * fac for v in np.atleast_1d(top.physical_sizes)]
    if top.dim == 2:
        out = Topography(h, tuple(new_sizes), unit="m", periodic=top.is_periodic, info=top.info)
    else:
        out = UniformLineScan(h, new_sizes[0], unit="m", periodic=top.is_periodic, info=top.info)
    return out, str(reader.format()), source


def _line(exc: BaseException) -> str:
    return " ".join(str(exc).split()) or type(exc).__name__


def to_surfacetopography(surface: Surface):
    """Return the :class:`Surface` as a SurfaceTopography ``Topography``/``UniformLineScan``.

    Heights in m.
    """
    require_surfacetopography("SurfaceTopography export")
    from SurfaceTopography import Topography, UniformLineScan

    h = np.asarray(surface.h, dtype=float)
    if h.ndim == 1:
        return UniformLineScan(h, h.size * surface.pixel_size, unit="m", periodic=surface.periodic)
    ny, nx = h.shape
    return Topography(h.T.copy(), (nx * surface.pixel_size, ny * surface.pixel_size), unit="m",
                      periodic=surface.periodic)


def write_surface(path, h, pixel_size: float, *, periodic: bool = True) -> Path:
    """Write heights (m) with SurfaceTopography's writer.

    ``.x3p`` (2D, ISO 25178-72) or ``.nc`` (NetCDF, 1D/2D).

    Both are read by SurfaceTopography and Gwyddion.  Heights are stored as
    64-bit floats, so a read-back is exact; NetCDF stores the physical size
    as a 32-bit attribute (relative error <= 6e-8).
    """
    path = Path(path)
    h = np.asarray(h, dtype=float)
    suffix = path.suffix.lower()
    if suffix not in (".x3p", ".nc"):
        raise SurfaceFileError(f"{path}: expected a .x3p or .nc target, got {suffix!r}")
    if suffix == ".x3p" and h.ndim != 2:
        raise SurfaceFileError(f"{path}: x3p holds 2D maps only, got shape {h.shape}; use .nc")
    top = to_surfacetopography(
        Surface(h=h, pixel_size=float(pixel_size), format="", unit_source="", periodic=periodic)
    )
    path.parent.mkdir(parents=True, exist_ok=True)
    if suffix == ".x3p":
        top.to_x3p(str(path))
    else:
        top.to_netcdf(str(path))
    return path


def rms_values(h, pixel_size: float, periodic: bool) -> tuple[float, float]:
    """Rms height (m) and rms gradient (1) of a map by plain finite differences.

    Computed by tribolmp itself.

    The gradient uses forward differences, wrapped for a periodic map and over
    the ``(ny-1) x (nx-1)`` interior otherwise; for a line scan the second value
    is the rms slope.  The round-trip test compares these with SurfaceTopography's.
    """
    h = np.asarray(h, dtype=float)
    rms_h = float(np.sqrt(np.mean((h - h.mean()) ** 2)))
    if h.ndim == 1:
        g = (np.roll(h, -1) - h) if periodic else np.diff(h)
        return rms_h, float(np.sqrt(np.mean(g**2)) / pixel_size)
    if periodic:
        gx, gy = np.roll(h, -1, 1) - h, np.roll(h, -1, 0) - h
    else:
        gx, gy = np.diff(h, axis=1)[:-1, :], np.diff(h, axis=0)[:, :-1]
    return rms_h, float(np.sqrt(np.mean(gx**2) + np.mean(gy**2)) / pixel_size)


def _hurst(q: np.ndarray, c: np.ndarray, dim: int) -> float | None:
    """Hurst exponent from a log-log fit of the PSD, C ~ q^-(dim + 2H).

    Fitted between 4 grid wavenumbers and half the largest
    wavenumber: the lowest modes are few and the highest are blurred by the
    instrument and the pixel, both biasing the slope.  A surface whose
    short-wavelength cut-off lies inside that window gives a steep slope and
    an H outside (0, 1), which ``info`` flags in its notes.
    """
    q = np.asarray(q, dtype=float)
    c = np.asarray(c, dtype=float)
    ok = np.isfinite(q) & np.isfinite(c) & (q > 0) & (c > 0)
    q, c = q[ok], c[ok]
    if q.size < 4:
        return None
    lo, hi = 4 * q.min(), 0.5 * q.max()
    sel = (q >= lo) & (q <= hi)
    if np.count_nonzero(sel) < 3:
        sel = np.ones_like(q, dtype=bool)
    slope = np.polyfit(np.log(q[sel]), np.log(c[sel]), 1)[0]
    return float((-slope - dim) / 2.0)


def topography_info(
    path, *, pixel_size=None, unit=None, detrend="none", png=None, psd_csv=None, channel=None
) -> dict:
    """Statistics of a measured topography file, computed by SurfaceTopography.

    Returns the JSON fields of ``tribolmp topography info`` (SI units):
    ``format``, ``grid`` ([nx, ny]), ``size_m`` ([Lx, Ly]), ``pixel_size_m``,
    ``rms_height_m``, ``rms_gradient`` (2D; the rms slope for a line scan),
    ``hurst``, ``unit_source``, plus ``kind``, ``uniform``, ``missing_points``,
    ``detrend``, ``psd`` ({q_1_per_m, C, dim}) and ``files``.
    Nonuniform line scans and maps with missing points are handled: the
    statistics run over the measured points.
    """
    path = Path(path)
    _check_override(pixel_size, unit)
    if detrend not in DETREND_MODES:
        raise SurfaceFileError(f"detrend: expected one of {list(DETREND_MODES)}, got {detrend!r}")
    require_surfacetopography("topography info")
    _check_exists(path)
    if _is_native(path):
        surf = read_surface(path, pixel_size=pixel_size, unit=unit)
        top, fmt, source = to_surfacetopography(surf), surf.format, surf.unit_source
    else:
        top, fmt, source = _read_st(path, pixel_size=pixel_size, unit=unit, channel=channel)
    mode = DETREND_MODES[detrend]
    if mode is not None:
        top = top.detrend(detrend_mode=mode)
    uniform = bool(top.is_uniform)
    missing = (
        int(np.count_nonzero(np.ma.getmaskarray(top.heights())))
        if uniform and top.has_undefined_data
        else 0
    )
    notes = []
    if top.dim == 2:
        nx, ny = (int(n) for n in top.nb_grid_pts)
        lx, ly = (float(s) for s in top.physical_sizes)
        kind = "map"
        rms_h = float(top.Sq())
        try:
            rms_g = float(top.rms_gradient())
        except Exception as exc:  # noqa: BLE001 - e.g. gradients undefined next to missing points
            rms_g, _ = None, notes.append(f"rms gradient not computed: {_line(exc)}")
    else:
        nx, ny = int(top.nb_grid_pts[0]), 1
        lx, ly = float(np.atleast_1d(top.physical_sizes)[0]), 0.0
        kind = "line scan"
        rms_h = float(top.Rq())
        try:
            rms_g = float(top.Rdq())
        except Exception as exc:  # noqa: BLE001
            rms_g, _ = None, notes.append(f"rms slope not computed: {_line(exc)}")
    pixel = lx / nx if uniform else None
    psd: dict[str, Any] = {}
    hurst = None
    try:
        ptop = top
        if missing:
            # The PSD needs every point: computed on the harmonic fill, said
            # so; rms values use measured points only.
            ptop = top.interpolate_undefined_data("harmonic")
            notes.append(
                f"PSD and Hurst on the map with {missing} "
                "missing points filled (harmonic interpolation)"
            )
        if top.dim == 2:
            q, c = ptop.power_spectrum_from_area()
        else:
            q, c = ptop.power_spectrum_from_profile()
        q, c = np.asarray(q, float), np.asarray(c, float)
        ok = np.isfinite(q) & np.isfinite(c)
        q, c = q[ok], c[ok]
        psd = {"q_1_per_m": q.tolist(), "C": c.tolist(), "dim": top.dim,
               "units": {"q_1_per_m": "rad/m", "C": f"m^{top.dim + 2}"}}
        hurst = _hurst(q, c, top.dim)
    except Exception as exc:  # noqa: BLE001 - PSD undefined (e.g. missing data): say so, keep the rest
        notes.append(f"PSD not computed: {_line(exc)}")
    if hurst is not None and not (0.0 < hurst < 1.5):
        notes.append(f"PSD slope gives H = {hurst:.3g}, outside the self-affine range (0, 1)")
    files: dict[str, str] = {}
    if psd_csv is not None and psd:
        psd_csv = Path(psd_csv)
        psd_csv.parent.mkdir(parents=True, exist_ok=True)
        np.savetxt(psd_csv, np.column_stack([psd["q_1_per_m"], psd["C"]]), delimiter=",",
                   header=f"q_1_per_m,C_m{top.dim + 2}", comments="")
        files["psd_csv"] = str(psd_csv)
    if png is not None:
        files["png"] = str(_plot_info(top, psd, Path(png), title=f"{path.name} ({fmt})"))
    return {
        "file": str(path),
        "format": fmt,
        "kind": kind,
        "grid": [nx, ny],
        "size_m": [lx, ly],
        "pixel_size_m": pixel,
        "rms_height_m": rms_h,
        "rms_gradient": rms_g,
        "hurst": hurst,
        "unit_source": source,
        "uniform": uniform,
        "missing_points": missing,
        "detrend": detrend,
        "periodic": bool(top.is_periodic),
        "psd": psd,
        "files": files,
        "notes": notes,
        "units": {
            "size_m": "m",
            "pixel_size_m": "m",
            "rms_height_m": "m",
            "rms_gradient": "1",
            "hurst": "1",
        },
    }


def _plot_info(top, psd, png: Path, title: str) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    png.parent.mkdir(parents=True, exist_ok=True)
    fig, (a, b) = plt.subplots(1, 2, figsize=(9, 3.8))
    if top.dim == 2:
        h = np.ma.masked_invalid(np.ma.filled(top.heights(), np.nan)).T
        lx, ly = top.physical_sizes
        im = a.imshow(h * 1e6, origin="lower", extent=(0, lx * 1e6, 0, ly * 1e6), cmap="viridis")
        fig.colorbar(im, ax=a, label="height (µm)")
        a.set_xlabel("x (µm)")
        a.set_ylabel("y (µm)")
    else:
        x, h = top.positions_and_heights()
        a.plot(np.asarray(x) * 1e6, np.asarray(h) * 1e6, lw=0.8)
        a.set_xlabel("x (µm)")
        a.set_ylabel("height (µm)")
    if psd:
        q, c = np.asarray(psd["q_1_per_m"]), np.asarray(psd["C"])
        ok = (q > 0) & (c > 0)
        b.loglog(q[ok], c[ok], ".-", ms=3)
        b.set_xlabel("q (rad/m)")
        b.set_ylabel(f"C ({'m^4, radial' if top.dim == 2 else 'm^3'})")
    b.set_title("PSD")
    a.set_title(title, fontsize=9)
    fig.tight_layout()
    fig.savefig(png, dpi=100)
    plt.close(fig)
    return png
