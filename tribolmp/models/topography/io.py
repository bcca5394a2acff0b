"""Height-map files: ``.npy`` with a JSON sidecar, and plain ASCII grids.

* ``save_height_map(path, h, pixel_size)`` writes ``<stem>.npy`` (heights in m,
  float64, shape ``(n,)`` or ``(ny, nx)``) and ``<stem>.json`` with
  ``pixel_size_m``, ``shape``, ``units`` and ``periodic``.
* ``save_ascii_grid`` writes an ESRI ASCII grid (``.asc``; 2D; header
  ``ncols nrows xllcorner yllcorner cellsize``, cellsize and heights in m,
  read by GIS tools and Gwyddion) or an ``x [y] z`` text table (``.xyz``/
  ``.txt``; 1D or 2D, m), which every plotting tool reads.
* ``load_height_map(path)`` reads any of them back as ``(h, pixel_size)``.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from ...errors import SurfaceFileError

__all__ = ["save_height_map", "load_height_map", "save_ascii_grid"]


def _check(h, pixel_size):
    h = np.asarray(h, dtype=float)
    if h.ndim not in (1, 2) or min(h.shape) < 2:
        raise SurfaceFileError(f"height map: expected a 1D or 2D array with >= 2 points per side, got shape {h.shape}")
    if not np.all(np.isfinite(h)):
        raise SurfaceFileError("height map: expected finite heights, got NaN or inf")
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
    meta = {"pixel_size_m": pixel_size, "shape": list(h.shape), "units": {"h": "m", "pixel_size_m": "m"},
            "periodic": True, "format": "tribolmp height map v1"}
    side.write_text(json.dumps(meta, indent=1))
    return npy, side


def save_ascii_grid(path, h, pixel_size: float) -> Path:
    """Write an ASCII height map: ESRI grid for ``.asc`` (2D), ``x [y] z`` columns otherwise.

    Rows of the ESRI grid are written top (last row of ``h``) to bottom, as
    the format requires; coordinates are pixel centres in m.
    """
    h, pixel_size = _check(h, pixel_size)
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    if path.suffix.lower() == ".asc":
        if h.ndim != 2:
            raise SurfaceFileError(f"{path}: an ESRI .asc grid needs a 2D map, got shape {h.shape}; use .xyz")
        ny, nx = h.shape
        header = (f"ncols {nx}\nnrows {ny}\nxllcorner 0.0\nyllcorner 0.0\n"
                  f"cellsize {pixel_size!r}\nNODATA_value -9999\n")
        with path.open("w") as fh:
            fh.write(header)
            np.savetxt(fh, h[::-1], fmt="%.10e")
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


def load_height_map(path) -> tuple[np.ndarray, float]:
    """Read a height map written by :func:`save_height_map` or :func:`save_ascii_grid`.

    Returns
    -------
    h : ndarray
        Heights (m).
    pixel_size : float
        Grid spacing (m).
    """
    path = Path(path)
    suffix = path.suffix.lower()
    try:
        if suffix in (".npy", ".json", ""):
            npy, side = path.with_suffix(".npy"), path.with_suffix(".json")
            h = np.load(npy, allow_pickle=False)
            meta = json.loads(side.read_text())
            pixel = meta["pixel_size_m"]
        elif suffix == ".asc":
            h, pixel = _read_asc(path)
        else:
            h, pixel = _read_xyz(path)
    except SurfaceFileError:
        raise
    except (OSError, ValueError, KeyError, json.JSONDecodeError) as exc:
        raise SurfaceFileError(f"{path}: expected a tribolmp height map (.npy + .json, .asc or .xyz), got {exc}") from None
    return _check(h, pixel)


def _read_asc(path: Path):
    lines = path.read_text().splitlines()
    header = {}
    i = 0
    while i < len(lines) and lines[i].split() and lines[i].split()[0][0].isalpha():
        key, value = lines[i].split()[:2]
        header[key.lower()] = float(value)
        i += 1
    data = np.loadtxt(lines[i:], ndmin=2)[::-1]
    if data.shape != (int(header["nrows"]), int(header["ncols"])):
        raise SurfaceFileError(f"{path}: expected {int(header['nrows'])}x{int(header['ncols'])} values, got {data.shape}")
    return data, header["cellsize"]


def _read_xyz(path: Path):
    table = np.loadtxt(path, ndmin=2)
    if table.shape[1] == 2:
        x, z = table.T
        return z, float(x[1] - x[0])
    if table.shape[1] == 3:
        x, y, z = table.T
        nx = int(np.count_nonzero(y == y[0]))
        ny = len(z) // nx
        return z.reshape(ny, nx), float(x[1] - x[0])
    raise SurfaceFileError(f"{path}: expected 2 (x z) or 3 (x y z) columns, got {table.shape[1]}")
