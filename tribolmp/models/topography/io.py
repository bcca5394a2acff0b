"""Height-map files: ``.npy`` with a JSON sidecar, and plain ASCII grids.

* ``save_height_map(path, h, pixel_size)`` writes ``<stem>.npy`` (heights in m,
  float64, shape ``(n,)`` or ``(ny, nx)``) and ``<stem>.json`` with
  ``pixel_size_m``, ``shape``, ``units`` and ``periodic``.
* ``save_ascii_grid`` writes an ESRI-style ASCII grid (``.asc``; 2D; header
  ``ncols nrows xllcorner yllcorner cellsize``, cellsize and heights in m) or
  an ``x [y] z`` text table (``.xyz``/``.txt``; 1D or 2D, header
  ``# x_m [y_m] z_m`` stating the unit), which every plotting tool reads.
* ``load_height_map(path)`` reads any of them back as ``(h, pixel_size)``;
  :func:`tribolmp.models.topography.measured.read_surface` reads these and
  every instrument format SurfaceTopography knows.
* ``save_height_map`` also writes ``<stem>.nc`` (NetCDF, through
  SurfaceTopography's writer, read by SurfaceTopography and Gwyddion) when
  SurfaceTopography is installed.

Row order of ``.asc`` grids: the first data row is ``y = 0`` (``h[0]``), the
convention of instrument text exports (Gwyddion, Wyko, SPIP) and of
SurfaceTopography's reader; GIS grids list the northernmost row first, which
read the map flipped in y (issue 16).

Text files without a stated unit are not taken as metres: an ``x y z`` file
in µm read as m is a 10^6 error.  Such files need an explicit ``unit``.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from ...errors import SurfaceFileError

__all__ = ["save_height_map", "load_height_map", "save_ascii_grid", "read_native"]


def _check(h, pixel_size):
    h = np.asarray(h, dtype=float)
    if h.ndim not in (1, 2) or min(h.shape) < 2:
        raise SurfaceFileError(
            "surface height map: expected a 1D or 2D array "
            f"with >= 2 points per side, got shape {h.shape}"
        )
    if not np.all(np.isfinite(h)):
        raise SurfaceFileError("surface height map: expected finite heights, got NaN or inf")
    if isinstance(pixel_size, bool) or not isinstance(pixel_size, (int, float)) or not (
        math.isfinite(pixel_size) and pixel_size > 0
    ):
        raise SurfaceFileError(f"pixel_size: expected a finite number > 0 (m), got {pixel_size!r}")
    return h, float(pixel_size)


def save_height_map(path, h, pixel_size: float) -> tuple[Path, Path]:
    """Write heights (m) to ``<stem>.npy`` and the pixel size (m) to ``<stem>.json``.

    Parameters
    ----------
    path : str or Path
        Target; the suffix is replaced by ``.npy`` / ``.json``.
    h : array_like
        Heights (m), 1D or 2D.
    pixel_size : float
        Grid spacing (m).

    Returns
    -------
    (Path, Path)
        The ``.npy`` and ``.json`` paths.
    """
    h, pixel_size = _check(h, pixel_size)
    path = Path(path)
    npy, side = path.with_suffix(".npy"), path.with_suffix(".json")
    npy.parent.mkdir(parents=True, exist_ok=True)
    np.save(npy, h)
    meta = {
        "pixel_size_m": pixel_size,
        "shape": list(h.shape),
        "units": {"h": "m", "pixel_size_m": "m"},
        "periodic": True,
        "format": "tribolmp height map v1",
    }
    side.write_text(json.dumps(meta, indent=1))
    _write_netcdf_copy(path.with_suffix(".nc"), h, pixel_size)
    return npy, side


def _write_netcdf_copy(path: Path, h, pixel_size: float) -> Path | None:
    """Return the same map as NetCDF for SurfaceTopography/Gwyddion users.

    Skipped without SurfaceTopography.
    """
    try:
        import SurfaceTopography  # noqa: F401
    except ImportError:
        return None
    from .measured import write_surface

    return write_surface(path, h, pixel_size, periodic=True)


def save_ascii_grid(path, h, pixel_size: float) -> Path:
    """Write an ASCII height map: ESRI grid for ``.asc`` (2D), ``x [y] z`` columns otherwise.

    Rows of the grid are written ``h[0]`` (``y = 0``) first, as instruments
    write text exports and SurfaceTopography reads them; coordinates are pixel
    centres in m.
    """
    h, pixel_size = _check(h, pixel_size)
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    if path.suffix.lower() == ".asc":
        if h.ndim != 2:
            raise SurfaceFileError(
                f"{path}: an ESRI .asc grid needs a 2D map, got shape {h.shape}; use .xyz"
            )
        ny, nx = h.shape
        header = (f"ncols {nx}\nnrows {ny}\nxllcorner 0.0\nyllcorner 0.0\n"
                  f"cellsize {pixel_size!r}\nNODATA_value -9999\n")
        with path.open("w") as fh:
            fh.write(header)
            np.savetxt(fh, h, fmt="%.10e")
        return path
    x = (np.arange(h.shape[-1]) + 0.5) * pixel_size
    if h.ndim == 1:
        table = np.column_stack([x, h])
        head = "x_m z_m"
    else:
        y = (np.arange(h.shape[0]) + 0.5) * pixel_size
        X, Y = np.meshgrid(x, y)
        table = np.column_stack([X.ravel(), Y.ravel(), h.ravel()])
        head = "x_m y_m z_m"
    np.savetxt(path, table, fmt="%.10e", header=head)
    return path


def load_height_map(
    path, pixel_size: float | None = None, unit: str | None = None
) -> tuple[np.ndarray, float]:
    """Read a height map written by :func:`save_height_map` or :func:`save_ascii_grid`.

    Parameters
    ----------
    path : str or Path
        ``.npy`` (+ ``.json``), ``.asc`` or ``.xyz``/``.txt``.
    pixel_size : float, optional
        Grid spacing (m); overrides the file's value when given.
    unit : str, optional
        Length unit of a text file without a ``_m`` header (``"um"``, ``"nm"``, ...).

    Returns
    -------
    h : ndarray
        Heights (m).
    pixel_size : float
        Grid spacing (m).
    """
    h, px, _, _ = read_native(path, pixel_size=pixel_size, unit=unit)
    return h, px


def read_native(
    path, pixel_size: float | None = None, unit: str | None = None
) -> tuple[np.ndarray, float, str, str]:
    """Read a tribolmp-format height map; returns ``(h [m], pixel_size [m], format, unit_source)``.

    ``unit_source`` says where the units and pixel size came from
    (``"file metadata"``, ``"override"`` or both).
    """
    path = Path(path)
    suffix = path.suffix.lower()
    try:
        if suffix in (".npy", ".json", ""):
            npy, side = path.with_suffix(".npy"), path.with_suffix(".json")
            try:
                h = np.load(npy, allow_pickle=False)
            except ValueError:
                # numpy's "pickled data" text misleads for a file that is simply not .npy.
                raise SurfaceFileError(
                    f"surface file {npy}: expected a .npy array "
                    "file (numpy format), got other content"
                ) from None
            if not isinstance(h, np.ndarray):
                raise SurfaceFileError(f"{npy}: expected a single .npy array, got an archive")
            meta = json.loads(side.read_text()) if side.exists() else {}
            if "shape" in meta and list(meta["shape"]) != list(h.shape):
                # The sidecar belongs to another map (or the array was cut):
                # its pixel size would be wrong too.
                raise SurfaceFileError(
                    f"{side}: expected the shape of {npy.name}, "
                    f"{list(h.shape)}, got {meta['shape']}"
                )
            fmt = "tribolmp-npy"
            if pixel_size is not None:
                pixel, source = (
                    pixel_size,
                    "override"
                    if "pixel_size_m" not in meta
                    else "file metadata + pixel size (override)",
                )
            elif "pixel_size_m" in meta:
                pixel, source = meta["pixel_size_m"], "file metadata"
            else:
                raise SurfaceFileError(
                    f"{npy}: expected a sidecar {side.name} with "
                    "pixel_size_m or a pixel_size override (m), got none"
                )
            if unit not in (None, "m"):
                raise SurfaceFileError(
                    f"{npy}: tribolmp .npy heights are in m; unit "
                    f"override expected 'm' or none, got {unit!r}"
                )
        elif suffix == ".asc":
            h, pixel = _read_asc(path)
            fmt, source = "esri-asc", "file metadata"
            if unit not in (None, "m"):
                from .measured import _unit_factor

                f = _unit_factor(unit, "unit")
                h, pixel, source = h * f, pixel * f, "override (unit)"
            if pixel_size is not None:
                pixel, source = pixel_size, source + " + pixel size (override)"
        else:
            h, pixel, source = _read_xyz(path, unit)
            fmt = "xyz"
            if pixel_size is not None:
                pixel, source = pixel_size, source + " + pixel size (override)"
    except SurfaceFileError:
        raise
    except (OSError, ValueError, KeyError, IndexError, json.JSONDecodeError) as exc:
        msg = " ".join(str(exc).split())
        raise SurfaceFileError(
            f"{path}: expected a tribolmp height map (.npy + .json, .asc or .xyz), got {msg}"
        ) from None
    h, pixel = _check(h, pixel)
    return h, pixel, fmt, source


def _read_asc(path: Path):
    lines = path.read_text().splitlines()
    header = {}
    i = 0
    while i < len(lines) and lines[i].split() and lines[i].split()[0][0].isalpha():
        key, value = lines[i].split()[:2]
        header[key.lower()] = float(value)
        i += 1
    for key in ("ncols", "nrows", "cellsize"):
        if key not in header:
            raise SurfaceFileError(
                f"{path}: expected an ESRI grid header with {key}, got keys {sorted(header)}"
            )
    data = np.loadtxt(lines[i:], ndmin=2)
    if data.shape != (int(header["nrows"]), int(header["ncols"])):
        raise SurfaceFileError(
            f"{path}: expected {int(header['nrows'])}x{int(header['ncols'])} "
            f"values, got {data.shape}"
        )
    if "nodata_value" in header:
        bad = data == header["nodata_value"]
        if bad.any():
            raise SurfaceFileError(
                f"{path}: expected a complete grid, got {int(bad.sum())} NODATA points"
            )
    return data, header["cellsize"]


def _header_unit(path: Path) -> str | None:
    """Return the length unit stated by a ``# x_<unit> ...`` header line, or None."""
    with path.open("r", errors="replace") as fh:
        for line in fh:
            s = line.strip()
            if not s:
                continue
            if not s.startswith("#"):
                return None
            words = s.lstrip("#").split()
            if words and words[0].lower().startswith("x_"):
                return words[0][2:]
    return None


def _uniform_axis(values: np.ndarray, name: str, path: Path) -> tuple[np.ndarray, float]:
    u = np.unique(values)
    if u.size < 2:
        return u, 0.0
    d = np.diff(u)
    step = float(np.median(d))
    # 1e-6 relative: coordinates written with >= 7 significant digits.
    if np.any(np.abs(d - step) > 1e-6 * max(step, np.abs(u).max() * 1e-9)):
        raise SurfaceFileError(
            f"{path}: expected uniformly spaced {name} values, "
            f"got spacings from {d.min():.4g} to {d.max():.4g}"
        )
    return u, step


def _read_xyz(path: Path, unit: str | None):
    from .measured import _unit_factor

    stated = _header_unit(path)
    if stated is not None:
        fac, source = _unit_factor(stated, f"{path}: header unit"), "file metadata"
        if unit is not None:
            fac, source = (
                _unit_factor(unit, "unit"),
                f"file metadata + unit {unit} (override of the file's {stated})",
            )
    elif unit is not None:
        fac, source = _unit_factor(unit, "unit"), f"override (unit {unit})"
    else:
        table = np.loadtxt(path, ndmin=2, max_rows=2)
        raise SurfaceFileError(
            f"{path}: expected a header '# x_m ...' stating the length "
            "unit or a unit override (e.g. unit='um', --unit um), "
            f"got a unit-less table of {table.shape[1]} columns"
        )
    table = np.loadtxt(path, ndmin=2) * fac
    if table.shape[1] == 2:
        x, z = table.T
        order = np.argsort(x, kind="stable")
        x, z = x[order], z[order]
        _, step = _uniform_axis(x, "x", path)
        if step <= 0 or np.unique(x).size != x.size:
            raise SurfaceFileError(
                f"{path}: expected distinct, uniformly spaced x values, got repeated x"
            )
        return z, step, source
    if table.shape[1] == 3:
        x, y, z = table.T
        ux, dx = _uniform_axis(x, "x", path)
        uy, dy = _uniform_axis(y, "y", path)
        nx, ny = ux.size, uy.size
        if nx < 2 or ny < 2:
            raise SurfaceFileError(
                f"{path}: expected >= 2 distinct x and y values, got {nx} x and {ny} y"
            )
        if nx * ny != z.size:
            raise SurfaceFileError(
                f"{path}: expected a complete {nx}x{ny} grid ({nx * ny} rows), got {z.size} rows"
            )
        if abs(dx - dy) > 1e-6 * max(dx, dy):
            raise SurfaceFileError(
                f"{path}: expected square pixels, got dx = {dx:.6g} "
                f"and dy = {dy:.6g} (file units x {fac:g} m)"
            )
        # Place every point by its coordinates: works whichever of x or y
        # varies fastest, and any row order.
        ix = np.rint((x - ux[0]) / dx).astype(int)
        iy = np.rint((y - uy[0]) / dy).astype(int)
        h = np.full((ny, nx), np.nan)
        h[iy, ix] = z
        if np.isnan(h).any():
            raise SurfaceFileError(
                f"{path}: expected one z per (x, y) grid point, got repeated points"
            )
        return h, dx, source
    raise SurfaceFileError(f"{path}: expected 2 (x z) or 3 (x y z) columns, got {table.shape[1]}")
