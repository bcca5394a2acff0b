"""Geometry of the MCA friction experiment.

Built with ASE and written as a ``bpm/sphere`` data file.

The system is a stack along the normal axis ``y`` (sliding along ``x``,
periodic in ``x``; in 3D also periodic in ``z``)::

    y  ^  slider  (mol 4, rigid, driven at velocity V under normal force F_N)
       |  upper body (mol 3, deformable)      <- rough lower surface
       |  ~~~~~~~~~~~~~~~~ interface ~~~~~~~~
       |  lower body (mol 2, deformable)      <- rough upper surface
       |  base    (mol 1, fixed)
       +-----------------------------------> x (periodic)

Packings: a hexagonal (triangular) lattice in 2D with close-packed rows along
``x``; an FCC lattice in 3D with its cube axes along x, y, z.  Nearest
neighbours are one automaton diameter ``d`` apart, so touching automata are
exactly at contact.  The two rough surfaces are independent self-affine
profiles (Hurst exponent ``hurst``) with a given rms height drawn from an
explicit :class:`numpy.random.Generator`; the upper body is placed so that its
lowest point is one diameter above the highest point of the lower body, i.e.
the highest asperities are just touching.

ASE cannot write LAMMPS's ``bpm/sphere`` atom style (it has no per-atom
diameter/density columns), so :func:`write_bpm_data` writes the file itself.

Atom types: 1 = deformable (lower and upper bodies; one type so that
``fix bond/create`` re-links across the interface), 2 = base, 3 = slider.
Bond types: 1 = original links inside a body, 2 = re-formed links (written by
``fix bond/create`` during the run; none in the file), 3 = unbreakable
attachment of the bodies to the base and to the slider.

All lengths passed to and returned from this module are in nm (the LAMMPS
``units nano`` boundary); :class:`MCAGeometry` records them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import ParameterError

__all__ = [
    "MOL_BASE",
    "MOL_LOWER",
    "MOL_SLIDER",
    "MOL_UPPER",
    "MCAGeometry",
    "build_block",
    "build_system",
    "self_affine_profile",
    "write_bpm_data",
]

MOL_BASE, MOL_LOWER, MOL_UPPER, MOL_SLIDER = 1, 2, 3, 4
TYPE_BODY, TYPE_BASE, TYPE_SLIDER = 1, 2, 3
BOND_BODY, BOND_REFORMED, BOND_ATTACH = 1, 2, 3
#: Rows (2D) or cubic cells (3D) in the base and in the slider.
RIGID_ROWS = 2


@dataclass(frozen=True)
class MCAGeometry:
    """A built MCA system (lengths in nm, LAMMPS ``units nano``).

    Attributes
    ----------
    atoms : ase.Atoms
        Positions (nm, stored in ASE's length slot unchanged), with arrays
        ``mol_id`` and ``lammps_type``.
    bonds : ndarray of int, shape (nb, 3)
        ``(type, i, j)`` with 0-based atom indices, ``i < j``.
    dim : int
        2 or 3.
    d : float
        Automaton diameter (nm).
    box : ndarray, shape (3, 2)
        ``[[xlo, xhi], [ylo, yhi], [zlo, zhi]]`` (nm).
    interface_y : float
        Mean height of the initial interface (nm).
    """

    atoms: object
    bonds: np.ndarray
    dim: int
    d: float
    box: np.ndarray
    interface_y: float

    @property
    def n_atoms(self) -> int:
        """Number of automata."""
        return len(self.atoms)

    def count(self, mol: int) -> int:
        """Return number of automata with molecule id ``mol``."""
        return int(np.count_nonzero(self.atoms.arrays["mol_id"] == mol))


def self_affine_profile(
    n: int | tuple[int, int], rms: float, hurst: float, rng: np.random.Generator
) -> np.ndarray:
    """Periodic self-affine random heights by Fourier filtering of white noise.

    Parameters
    ----------
    n : int or (int, int)
        Number of samples per period (1D) or per side (2D).
    rms : float
        Target rms height (any length unit; returned in the same unit).
    hurst : float
        Hurst exponent H in (0, 1]; PSD ~ q^-(1+2H) in 1D, q^-(2+2H) in 2D.
    rng : numpy.random.Generator
        Source of randomness.

    Returns
    -------
    ndarray
        Heights with zero mean and rms exactly ``rms`` (0 if ``rms == 0``).
    """
    shape = (n,) if np.isscalar(n) else tuple(n)
    noise = rng.standard_normal(shape)
    spec = np.fft.rfftn(noise)
    qs = np.meshgrid(
        *[np.fft.fftfreq(m) for m in shape[:-1]], np.fft.rfftfreq(shape[-1]), indexing="ij"
    )
    q = np.sqrt(sum(qq**2 for qq in qs))
    with np.errstate(divide="ignore"):
        # amplitude ~ sqrt(PSD); the mean (q = 0) is removed
        amp = np.where(q > 0, q ** (-(len(shape) + 2 * hurst) / 2.0), 0.0)
    h = np.fft.irfftn(spec * amp, s=shape, axes=tuple(range(len(shape))))
    std = h.std()
    if rms == 0.0 or std == 0.0:
        return np.zeros(shape)
    return (h - h.mean()) * (rms / std)


def _hex_block(nx: int, nrows: int, d: float):
    """ASE Atoms of a 2D hexagonal block: rows along x, row spacing sqrt(3)/2 d."""
    from ase import Atoms

    dy = math.sqrt(3.0) / 2.0 * d
    cell = Atoms(
        "H2",
        positions=[[0.0, 0.0, 0.0], [0.5 * d, dy, 0.0]],
        cell=[d, 2 * dy, d],
        pbc=[True, False, True],
    )
    block = cell.repeat((nx, (nrows + 1) // 2, 1))
    if nrows % 2:
        block = block[block.positions[:, 1] < (nrows - 0.5) * dy]
    return block, dy


def _rotated_fit(nx: int) -> tuple[int, int]:
    """(nx, ncol): box of nx lattice spacings that holds an even number ncol of rotated columns.

    Columns of the 90-degree rotated hexagonal lattice are sqrt(3)/2 d apart
    and alternate, so the rotated body repeats after an even number of them;
    of the box lengths within 3 spacings of ``nx`` that need a stretch below 1 %,
    the nearest is taken (else the one with the smallest stretch).
    """
    fits = []
    for n in range(max(4, nx - 3), nx + 4):
        ncol = 2 * max(2, round(n / math.sqrt(3.0)))
        stretch = abs(n / (ncol * math.sqrt(3.0) / 2.0) - 1.0)
        # below 1 % stretch: the box nearest the requested one; else the smallest stretch
        fits.append((stretch >= 0.01, abs(n - nx) if stretch < 0.01 else stretch, n, ncol))
    _, _, n, ncol = min(fits)
    return n, ncol


def _poly_block(lx: float, height: float, d: float, grain_size: float, rng: np.random.Generator):
    """ASE Atoms of a 2D polycrystal: periodic-in-x Voronoi grains of rotated hexagonal lattices."""
    from ase import Atoms
    from scipy.spatial import cKDTree

    ngrain = max(2, int(round(lx * height / grain_size**2)))
    seeds = np.column_stack([rng.uniform(0.0, lx, ngrain), rng.uniform(0.0, height, ngrain)])
    angles = rng.uniform(0.0, np.pi / 3.0, ngrain)  # hexagonal symmetry: 60 degrees cover all
    offsets = rng.uniform(0.0, 1.0, (ngrain, 2))
    half = 0.5 * math.hypot(lx, height) + 2.0 * d
    n = int(math.ceil(half / d)) + 2
    i, j = np.meshgrid(np.arange(-n, n + 1), np.arange(-n, n + 1), indexing="ij")
    # hexagonal lattice points around the origin (lattice vectors d (1, 0) and d (1/2, sqrt(3)/2))
    base = np.column_stack([(i + 0.5 * j).ravel(), (math.sqrt(3.0) / 2.0 * j).ravel()]) * d
    centre = np.array([0.5 * lx, 0.5 * height])
    pts, owner = [], []
    for g in range(ngrain):
        c, s_ = math.cos(angles[g]), math.sin(angles[g])
        rot = (
            base + offsets[g] @ np.array([[d, 0.0], [0.5 * d, math.sqrt(3.0) / 2.0 * d]])
        ) @ np.array([[c, s_], [-s_, c]]) + centre
        inside = (rot[:, 0] >= 0) & (rot[:, 0] < lx) & (rot[:, 1] >= 0) & (rot[:, 1] < height)
        rot = rot[inside]
        dx = np.abs(rot[:, None, 0] - seeds[None, :, 0])
        dx = np.minimum(dx, lx - dx)  # periodic along x
        dist = np.sqrt(dx**2 + (rot[:, None, 1] - seeds[None, :, 1]) ** 2)
        # each grain reaches half a diameter past its Voronoi boundary, so that the thinning
        # below closes the boundary instead of leaving d-sized pores along it
        mine = dist[:, g] <= dist.min(axis=1) + 0.5 * d
        pts.append(rot[mine])
        owner.append(np.full(int(mine.sum()), g))
    p = np.concatenate(pts)
    tree = cKDTree(np.column_stack([np.mod(p[:, 0], lx), p[:, 1] + 1e3]), boxsize=[lx, 1e12])
    drop = np.zeros(len(p), bool)
    # thin out grain boundaries (and the seam of a grain across x = 0): no
    # two automata closer than 0.8 d
    for a, b in sorted(map(tuple, tree.query_pairs(0.7 * d, output_type="ndarray"))):
        if not drop[a]:
            drop[b] = True
    p = p[~drop]
    pos = np.column_stack([p, np.zeros(len(p))])
    return Atoms(f"H{len(pos)}", positions=pos, cell=[lx, height, d], pbc=[True, False, True])


#: Orientations of the ``tilted`` texture (degrees of the lattice's close-packed rows against
#: x; each within 2 degrees, the windows apart so the bodies never share a lattice vector).
#: The upper body is mirrored when it is turned face down (angle -> -angle), so the bodies
#: meet about 30 degrees apart, the largest misorientation of two hexagonal lattices; neither
#: angle is a low-index direction (0 or 30 degrees), so neither surface repeats after d.
TILT_DEG = (12.0, 19.0)


def _tilted_fit(nx: int, d: float) -> tuple[float, tuple[int, int], tuple[int, int]]:
    """(box length, (m, n) of the lower body, (m, n) of the upper body) for the ``tilted`` texture.

    A hexagonal lattice (vectors d (1, 0), d (1/2, sqrt(3)/2)) turned so that its lattice vector
    t = m a1 + n a2 lies along x is periodic along x with period |t| = d sqrt(m^2 + mn + n^2);
    its rows then make the angle atan2(n sqrt(3)/2, m + n/2) with x.  Candidates for each body
    are the primitive vectors within 2 degrees of its angle in :data:`TILT_DEG` and with |t|
    within 4 spacings of ``nx`` d; of the (lower, upper) pairs whose lengths agree within 1 %,
    the one nearest the requested length is taken (the upper body is stretched along x by the
    mismatch, and its links take the stretched length as their rest length).
    """
    def candidates(target):
        out = []
        for m in range(1, nx + 6):
            for n in range(0, nx + 6):
                length = math.sqrt(m * m + m * n + n * n)
                if abs(length - nx) > 4 or math.gcd(m, n) != 1:
                    continue
                ang = math.degrees(math.atan2(n * math.sqrt(3.0) / 2.0, m + 0.5 * n))
                if abs(ang - target) <= 2.0:
                    out.append((length, (m, n)))
        return out

    lo, up = candidates(TILT_DEG[0]), candidates(TILT_DEG[1])
    if not lo or not up:
        raise ParameterError(
            "box_length", "at least 16 automaton diameters for body_texture tilted", nx * d
        )
    # of the pairs that fit each other within 1 %, the box nearest the requested length
    fits = [
        (abs(a - nx), abs(a / b - 1.0), a, mn_a, mn_b)
        for a, mn_a in lo
        for b, mn_b in up
        if abs(a / b - 1.0) < 0.01
    ]
    if not fits:
        raise ParameterError(
            "box_length", "a length where both tilted lattices fit within 1 %", nx * d
        )
    _, _, length, mn_lo, mn_up = min(fits)
    return length * d, mn_lo, mn_up


def _tilted_block(mn: tuple[int, int], lx: float, height: float, d: float):
    """ASE Atoms of a hexagonal block whose lattice vector m a1 + n a2 lies along x, period ``lx``.

    The lattice points with 0 <= x < |t| and 0 <= y < height are exactly one period of the
    turned crystal (t maps the lattice onto itself); x is then scaled from |t| to ``lx``.
    """
    from ase import Atoms

    m, n = mn
    t = np.array([m + 0.5 * n, math.sqrt(3.0) / 2.0 * n]) * d
    period = float(np.hypot(*t))
    c, s_ = t / period
    rot = np.array([[c, -s_], [s_, c]])  # turns t onto +x (row vectors: p @ rot)
    reach = int(math.ceil((period + height) / d)) + 2
    i, j = np.meshgrid(np.arange(-2 * reach, 2 * reach + 1), np.arange(-2 * reach, 2 * reach + 1),
                       indexing="ij")
    base = np.column_stack([(i + 0.5 * j).ravel(), (math.sqrt(3.0) / 2.0 * j).ravel()]) * d
    p = base @ rot
    tol = 1e-9 * d
    keep = (p[:, 0] >= -tol) & (p[:, 0] < period - tol) & (p[:, 1] >= -tol) & (p[:, 1] < height)
    p = p[keep]
    p[:, 0] = np.clip(p[:, 0], 0.0, None) * (lx / period)
    pos = np.column_stack([p, np.zeros(len(p))])
    return Atoms(f"H{len(pos)}", positions=pos, cell=[lx, height, d], pbc=[True, False, True])


def _hex_columns(ncol: int, height: float, d: float, lx: float):
    """ASE Atoms of a hexagonal block turned by 90 deg: close-packed columns along y.

    ``ncol`` (even) columns, stretched along x to fill the period ``lx``
    exactly; atoms d apart along each column, alternate columns offset by d/2.
    """
    from ase import Atoms

    dx = lx / ncol  # = sqrt(3)/2 d within the fit's stretch
    xs, ys = [], []
    nrow = int(math.ceil(height / d)) + 1
    for i in range(ncol):
        for j in range(nrow):
            xs.append(i * dx)
            ys.append(j * d + (0.5 * d if i % 2 else 0.0))
    pos = np.column_stack([xs, ys, np.zeros(len(xs))])
    pos = pos[pos[:, 1] < height]
    return Atoms(f"H{len(pos)}", positions=pos, cell=[lx, height, d], pbc=[True, False, True])


#: The ``rotated`` texture in 3D: both bodies' cube axes turned about the surface normal by
#: +-atan(1/3) = +-18.43 deg, so they meet 36.87 deg apart (the Sigma-5 misorientation of two
#: cubic lattices, the largest below 45 deg with a short coincidence period).  The rotated FCC
#: lattice repeats along x and z after sqrt(10) a (the cube vectors (3, 0, +-1) a), so both
#: bodies are exactly periodic in a box of whole multiples of sqrt(10) a, without stretching.
ROT3D_MN = (3, 1)


def _rotated_fcc_block(kx: int, kz: int, ncells: int, d: float, sign: int):
    """ASE Atoms of an FCC block turned by ``sign * atan(n/m)`` about y (see :data:`ROT3D_MN`).

    ``kx`` x ``kz`` coincidence cells of side sqrt(m^2 + n^2) a along x and z, ``ncells``
    cubic cells (a) high; nearest neighbours at ``d``.  Lattice points are generated over a
    region covering the rotated box and wrapped into it; the coincidence makes the wrap exact,
    so the images of one site coincide and are merged.
    """
    from ase import Atoms

    m, n = ROT3D_MN
    a = math.sqrt(2.0) * d
    period = math.hypot(m, n) * a
    lx, lz = kx * period, kz * period
    c, s = m / math.hypot(m, n), sign * n / math.hypot(m, n)
    basis = np.array([[0, 0, 0], [0.5, 0.5, 0], [0.5, 0, 0.5], [0, 0.5, 0.5]])
    # cube-lattice cells covering the rotated box: its corners mapped back by the inverse rotation
    corners = np.array([[x, z] for x in (0.0, lx) for z in (0.0, lz)])
    back = np.column_stack(
        [c * corners[:, 0] - s * corners[:, 1], s * corners[:, 0] + c * corners[:, 1]]
    )
    lo = np.floor(back.min(axis=0) / a).astype(int) - 1
    hi = np.ceil(back.max(axis=0) / a).astype(int) + 1
    i, j, k = np.meshgrid(
        np.arange(lo[0], hi[0]), np.arange(ncells), np.arange(lo[1], hi[1]), indexing="ij"
    )
    cells = np.column_stack([i.ravel(), j.ravel(), k.ravel()]).astype(float)
    pts = (cells[:, None, :] + basis[None, :, :]).reshape(-1, 3) * a
    # rotation about y (x' = c x + s z, z' = -s x + c z): the inverse of the map above
    x = c * pts[:, 0] + s * pts[:, 2]
    z = -s * pts[:, 0] + c * pts[:, 2]
    pos = np.column_stack([np.mod(x, lx), pts[:, 1], np.mod(z, lz)])
    # images of one site differ by rounding only; the site closest to the box edge may wrap to
    # either side, so compare modulo the period
    key = np.round(pos / (1e-6 * d)).astype(np.int64)
    key[:, 0] %= int(round(lx / (1e-6 * d)))
    key[:, 2] %= int(round(lz / (1e-6 * d)))
    _, first = np.unique(key, axis=0, return_index=True)
    pos = pos[np.sort(first)]
    return Atoms(f"H{len(pos)}", positions=pos, cell=[lx, ncells * a, lz], pbc=[True, False, True])


def _fcc_block(nx: int, ncells: int, nz: int, d: float):
    """ASE Atoms of an FCC block with cube axes along x, y, z; nearest neighbours at d."""
    from ase.build import bulk

    a = math.sqrt(2.0) * d
    block = bulk("Cu", "fcc", a=a, cubic=True).repeat((nx, ncells, nz))
    return block, a / 2.0


def build_system(
    *,
    dim: int,
    d: float,
    length: float,
    body_height: float,
    roughness_rms: float,
    rng: np.random.Generator,
    width: float | None = None,
    hurst: float = 0.8,
    contact_fraction: float = 0.1,
    texture: str = "aligned",
    grain_size: float | None = None,
) -> MCAGeometry:
    """Build base / lower body / upper body / slider with rough interface surfaces.

    Parameters
    ----------
    dim : {2, 3}
        Spatial dimension.
    d : float
        Automaton diameter = nearest-neighbour distance (nm).
    length : float
        Periodic length along the sliding direction x (nm); rounded to whole
        lattice periods.
    body_height : float
        Height of each deformable body (nm), measured to its mean surface.
    roughness_rms : float
        Rms height of each rough surface (nm).
    rng : numpy.random.Generator
        Source of the two independent surface profiles.
    width : float, optional
        Periodic width along z in 3D (nm); default ``length / 4``, at least
        two cubic cells.
    hurst : float
        Hurst exponent of the surfaces.
    contact_fraction : float
        Fraction of surface columns (bins of width d) initially in contact;
        0 places the highest asperities just touching.
    texture : {"aligned", "rotated", "tilted", "polycrystalline"}
        ``aligned``: both bodies with close-packed rows along x (the lower
        body's surface period d is the upper body's: sliding is a washboard
        at frequency V/d).  ``rotated`` (2D): the upper body's lattice turned
        by 90 deg about the normal, close-packed rows along y, so its period
        along x is sqrt(3)/2 d, incommensurate with the lower body's d.  The
        box length is chosen (within 3 lattice periods of ``length``) so that
        the rotated body fits it periodically with the smallest stretch along
        x (below 1 %; the links take that length as their rest length, so the
        body is stress-free).  ``polycrystalline`` (2D): both bodies made of
        grains (periodic Voronoi cells along x, mean size ``grain_size``) of
        randomly oriented lattices, seeds and angles drawn from ``rng`` after
        the surface profiles; atoms of two grains closer than 0.8 d are
        thinned out at the boundaries.  Every contact then sees its own row
        period, so sliding has no common washboard frequency.  ``tilted`` (2D):
        both bodies single crystals, their close-packed rows at about 12 and 19
        deg to x (:data:`TILT_DEG`); the upper one is mirrored face down, so the
        bodies meet about 30 deg apart and neither surface repeats after d.  Each lattice is
        periodic along x through a lattice vector of length close to ``length``
        (the upper body stretched along x by below 1 %, stress-free).
    grain_size : float, optional
        Mean grain size (nm) for ``polycrystalline`` (default 4 d).

    Returns
    -------
    MCAGeometry
    """
    if dim not in (2, 3):
        raise ParameterError("dim", "2 or 3", dim)
    if not (0.0 < hurst <= 1.0):
        raise ParameterError("hurst", "a number in (0, 1]", hurst)
    if texture not in ("aligned", "rotated", "tilted", "polycrystalline"):
        raise ParameterError("body_texture", "aligned, rotated, tilted or polycrystalline", texture)
    if texture in ("tilted", "polycrystalline") and dim != 2:
        raise ParameterError("body_texture", "aligned or rotated in 3D", texture)
    if dim == 2:
        nx = max(4, int(round(length / d)))
        nrows = max(4, int(math.ceil(body_height / (math.sqrt(3.0) / 2.0 * d)))) + 4
        if texture == "rotated":
            nx, ncol = _rotated_fit(nx)
        lower, dy = _hex_block(nx, nrows + RIGID_ROWS, d)
        lx, lz = nx * d, d
        if texture == "rotated":
            upper = _hex_columns(ncol, (nrows + RIGID_ROWS) * dy, d, nx * d)
        elif texture == "tilted":
            lx, mn_lo, mn_up = _tilted_fit(nx, d)
            lower = _tilted_block(mn_lo, lx, (nrows + RIGID_ROWS) * dy, d)
            upper = _tilted_block(mn_up, lx, (nrows + RIGID_ROWS) * dy, d)
        else:
            upper, _ = _hex_block(nx, nrows + RIGID_ROWS, d)
        nsurf: int | tuple[int, int] = 4 * nx
        nz = 1
    else:
        a = math.sqrt(2.0) * d
        ncell = max(2, int(math.ceil(body_height / a))) + 2
        wz = width if width is not None else length / 4.0
        if texture == "rotated":
            period = math.hypot(*ROT3D_MN) * a
            kx, kz = max(2, round(length / period)), max(1, round(wz / period))
            lower = _rotated_fcc_block(kx, kz, ncell + 1, d, +1)
            upper = _rotated_fcc_block(kx, kz, ncell + 1, d, -1)
            dy = a / 2.0
            lx, lz = kx * period, kz * period
            nx, nz = int(round(lx / a)), int(round(lz / a))
        else:
            nx = max(2, int(round(length / a)))
            nz = max(2, int(round(wz / a)))
            lower, dy = _fcc_block(nx, ncell + 1, nz, d)
            upper, _ = _fcc_block(nx, ncell + 1, nz, d)
            lx, lz = nx * a, nz * a
        nsurf = (4 * nx, 4 * nz)
    h_lo = self_affine_profile(nsurf, roughness_rms, hurst, rng)
    h_up = self_affine_profile(nsurf, roughness_rms, hurst, rng)
    if texture == "polycrystalline":
        gs = grain_size if grain_size is not None else 4.0 * d
        height = (nrows + RIGID_ROWS) * dy
        lower = _poly_block(lx, height, d, gs, rng)
        upper = _poly_block(lx, height, d, gs, rng)

    def surf(h, pos):
        ix = np.floor(pos[:, 0] / lx * h.shape[0]).astype(int) % h.shape[0]
        if h.ndim == 1:
            return h[ix]
        iz = np.floor(pos[:, 2] / lz * h.shape[1]).astype(int) % h.shape[1]
        return h[ix, iz]

    # rigid layers: RIGID_ROWS lattice planes (spacing dy) below / above the bodies
    base_top = (RIGID_ROWS - 0.5) * dy
    y_mean_lo = base_top + body_height
    p = lower.positions
    keep = p[:, 1] <= y_mean_lo + surf(h_lo, p)
    lower = lower[keep]
    mol_lo = np.where(lower.positions[:, 1] < base_top, MOL_BASE, MOL_LOWER)

    # the upper block is flipped so that its rough face points down
    p = upper.positions.copy()
    ytop = p[:, 1].max()
    p[:, 1] = ytop - p[:, 1]
    upper.positions = p
    slider_bottom = ytop - (RIGID_ROWS - 0.5) * dy
    keep = p[:, 1] >= (slider_bottom - body_height) - surf(h_up, p)
    upper = upper[keep]
    p = upper.positions
    mol_up = np.where(p[:, 1] > slider_bottom, MOL_SLIDER, MOL_UPPER)
    # Bring the surfaces together so that a fraction `contact_fraction` of the surface columns touch
    # (separation of their outermost automata <= d); upper-body automata that would then sit closer
    # than one diameter to a lower-body automaton are removed (the asperity tips are trimmed).
    # Without this the slider spends most of a short run approaching the first, highest asperity.
    shift = _contact_shift(
        lower.positions[mol_lo == MOL_LOWER],
        p[mol_up == MOL_UPPER],
        d,
        lx,
        lz,
        dim,
        contact_fraction,
    )
    p[:, 1] += shift
    upper.positions = p
    trim = _too_close(lower.positions[mol_lo == MOL_LOWER], p, d, lx, lz, dim) & (
        mol_up == MOL_UPPER
    )
    upper = upper[~trim]
    mol_up = mol_up[~trim]

    atoms = lower + upper
    mol = np.concatenate([mol_lo, mol_up])
    atoms.set_array("mol_id", mol.astype(int))
    ltype = np.full(len(atoms), TYPE_BODY)
    ltype[mol == MOL_BASE] = TYPE_BASE
    ltype[mol == MOL_SLIDER] = TYPE_SLIDER
    atoms.set_array("lammps_type", ltype)
    pos = atoms.positions
    if dim == 2:
        pos[:, 2] = 0.0
        atoms.positions = pos
    ymax = pos[:, 1].max()
    # free space above the slider lets it move; LAMMPS box is fixed in y
    zlim = (-0.5 * d, 0.5 * d) if dim == 2 else (0.0, lz)
    box = np.array([[0.0, lx], [-d, ymax + 4.0 * d + body_height], zlim])
    atoms.cell = np.diag(box[:, 1] - box[:, 0])
    atoms.pbc = [True, False, True]
    # grain boundaries leave gaps up to ~1.2 d: link across them too (links
    # are stress-free at build)
    bonds = _neighbour_bonds(
        pos, mol, box, d, dim, cutoff=1.2 if texture == "polycrystalline" else 1.05
    )
    interface = 0.5 * (y_mean_lo + (slider_bottom - body_height + shift))
    return MCAGeometry(
        atoms=atoms, bonds=bonds, dim=dim, d=d, box=box, interface_y=float(interface)
    )


def _columns(pos: np.ndarray, d: float, lx: float, lz: float, dim: int) -> np.ndarray:
    ix = np.floor(pos[:, 0] / d).astype(int) % max(1, int(round(lx / d)))
    if dim == 2:
        return ix
    iz = np.floor(pos[:, 2] / d).astype(int) % max(1, int(round(lz / d)))
    return ix * 100000 + iz


def _contact_shift(
    lo: np.ndarray, up: np.ndarray, d: float, lx: float, lz: float, dim: int, frac: float
) -> float:
    """Vertical shift (m) of the upper body closing the gap in a fraction ``frac`` of columns."""
    base = lo[:, 1].max() + d - up[:, 1].min()  # highest asperities just touching
    if frac <= 0.0:
        return float(base)
    clo, cup = _columns(lo, d, lx, lz, dim), _columns(up, d, lx, lz, dim)
    gaps = []
    for c in np.intersect1d(clo, cup):
        gaps.append(up[cup == c, 1].min() - lo[clo == c, 1].max() - d)
    if not gaps:
        return float(base)
    return float(-np.quantile(np.asarray(gaps), min(frac, 1.0)))


def _too_close(
    lo: np.ndarray, pos: np.ndarray, d: float, lx: float, lz: float, dim: int
) -> np.ndarray:
    """Mask of ``pos`` within 0.99 d of any point of ``lo`` (periodic in x, and z in 3D)."""
    from scipy.spatial import cKDTree

    def wrap(a):
        b = a.copy()
        b[:, 0] = np.mod(b[:, 0], lx)
        b[:, 1] += 1e6
        b[:, 2] = np.mod(b[:, 2], lz) if dim == 3 else 0.0
        return b

    box = np.array([lx, 1e12, lz if dim == 3 else 1e12])
    tree = cKDTree(wrap(lo), boxsize=box)
    dist, _ = tree.query(wrap(pos), k=1)
    return dist < 0.99 * d


def build_block(*, dim: int, d: float, n: int) -> MCAGeometry:
    """Return a single bonded, fully periodic block (mol 2, type 1) for uniaxial tests.

    Parameters
    ----------
    dim : {2, 3}
        Hexagonal (n x n rows) or FCC (n x n x n cubic cells).
    d : float
        Automaton diameter (nm).
    n : int
        Lattice repeats per side (>= 4).
    """
    if dim == 2:
        n += n % 2  # whole hexagonal cells along y
        atoms, dy = _hex_block(n, n, d)
        lx, ly, zlim = n * d, n * dy, (-0.5 * d, 0.5 * d)
    else:
        atoms, dy = _fcc_block(n, n, n, d)
        lx = ly = n * math.sqrt(2.0) * d
        zlim = (0.0, lx)
    pos = atoms.positions
    mol = np.full(len(atoms), MOL_LOWER)
    atoms.set_array("mol_id", mol)
    atoms.set_array("lammps_type", np.full(len(atoms), TYPE_BODY))
    box = np.array([[0.0, lx], [0.0, ly], zlim])
    atoms.cell = np.diag(box[:, 1] - box[:, 0])
    atoms.pbc = True
    bonds = _neighbour_bonds(pos, mol, box, d, dim, periodic_y=True)
    return MCAGeometry(atoms=atoms, bonds=bonds, dim=dim, d=d, box=box, interface_y=float("nan"))


def _neighbour_bonds(
    pos: np.ndarray,
    mol: np.ndarray,
    box: np.ndarray,
    d: float,
    dim: int,
    *,
    periodic_y: bool = False,
    cutoff: float = 1.05,
) -> np.ndarray:
    """Bonds between neighbours (distance < ``cutoff`` d) of the same body, plus attachments.

    Links inside a deformable body are type 1; links of a body to the base or
    to the slider are unbreakable attachments (type 3).  No links cross the
    interface (mol 2 - mol 3) or join two rigid atoms.
    """
    from scipy.spatial import cKDTree

    lengths = box[:, 1] - box[:, 0]
    periodic = [True, periodic_y, dim == 3]
    # cKDTree needs positions in [0, L) on periodic axes and a huge box on the others
    boxsize = np.array([lengths[i] if periodic[i] else 1e12 for i in range(3)])
    shifted = pos - np.where(periodic, box[:, 0], 0.0)
    shifted = np.where(periodic, np.mod(shifted, boxsize), shifted + 1e6)
    tree = cKDTree(shifted, boxsize=boxsize)
    pairs = tree.query_pairs(cutoff * d, output_type="ndarray")
    mi, mj = mol[pairs[:, 0]], mol[pairs[:, 1]]
    rigid = {MOL_BASE, MOL_SLIDER}
    same_body = (mi == mj) & ~np.isin(mi, list(rigid))
    attach = ((mi == MOL_BASE) & (mj == MOL_LOWER)) | ((mj == MOL_BASE) & (mi == MOL_LOWER))
    attach |= ((mi == MOL_SLIDER) & (mj == MOL_UPPER)) | ((mj == MOL_SLIDER) & (mi == MOL_UPPER))
    btype = np.where(same_body, BOND_BODY, np.where(attach, BOND_ATTACH, 0))
    sel = btype > 0
    out = np.column_stack([btype[sel], np.sort(pairs[sel], axis=1)])
    return out[np.lexsort((out[:, 2], out[:, 1]))]


def _nearest_distances(geom: MCAGeometry) -> np.ndarray:
    """Distance of every automaton to its nearest neighbour (nm), periodic along x (and z in 3D).

    Automata closer than the contact diameter (only at grain boundaries of a polycrystal) get a
    smaller contact diameter, so that no unlinked pair starts, or is left by a broken link,
    overlapping: such an overlap would release a force far beyond any link force.
    """
    from scipy.spatial import cKDTree

    box = geom.box
    lengths = box[:, 1] - box[:, 0]
    periodic = [True, False, geom.dim == 3]
    boxsize = np.array([lengths[i] if periodic[i] else 1e12 for i in range(3)])
    p = geom.atoms.positions - np.where(periodic, box[:, 0], 0.0)
    p = np.where(periodic, np.mod(p, boxsize), p + 1e6)
    dist, _ = cKDTree(p, boxsize=boxsize).query(p, k=2)
    return dist[:, 1]


def write_bpm_data(
    path: str | Path,
    geom: MCAGeometry,
    *,
    density: float,
    diameter: float | None = None,
    bond_types: int = 3,
) -> Path:
    """Write ``geom`` as a LAMMPS data file for ``atom_style bpm/sphere``.

    Parameters
    ----------
    path : str or Path
        Output file.
    geom : MCAGeometry
        The system.
    density : float
        Value of the per-atom density column (ag/nm^3).  LAMMPS sets the mass
        to ``density * pi d^3 / 6`` in 2D and 3D alike; pass the density that
        gives the mass you want (see :mod:`tribolmp.lammps.mapping`).
    diameter : float, optional
        Contact diameter written to the file (nm); default the lattice
        spacing ``geom.d``.
    bond_types : int
        Number of bond types declared in the header.

    Returns
    -------
    Path
        The file written.

    Notes
    -----
    Atoms columns of ``bpm/sphere``: ``id mol type diameter density x y z``.
    """
    path = Path(path)
    atoms = geom.atoms
    pos = atoms.positions
    mol = atoms.arrays["mol_id"]
    typ = atoms.arrays["lammps_type"]
    n = len(atoms)
    box = geom.box
    lines = [
        f"MCA friction system (tribolmp), dim={geom.dim}, d={geom.d:.6g} nm, units nano",
        "",
        f"{n} atoms",
        "3 atom types",
        f"{len(geom.bonds)} bonds",
        f"{bond_types} bond types",
        "",
        f"{box[0, 0]:.10g} {box[0, 1]:.10g} xlo xhi",
        f"{box[1, 0]:.10g} {box[1, 1]:.10g} ylo yhi",
        f"{box[2, 0]:.10g} {box[2, 1]:.10g} zlo zhi",
        "",
        "Atoms # bpm/sphere",
        "",
    ]
    ids = np.arange(1, n + 1)
    dia = geom.d if diameter is None else diameter
    dias = np.minimum(dia, _nearest_distances(geom))
    # same mass for every automaton: LAMMPS sets m = density pi D^3 / 6 from each atom's diameter
    dens = density * (dia / dias) ** 3
    body = [
        f"{i} {m} {t} {di:.10g} {rho:.10g} {x:.10g} {y:.10g} {z:.10g}"
        for i, m, t, di, rho, (x, y, z) in zip(ids, mol, typ, dias, dens, pos, strict=True)
    ]
    lines += body
    if len(geom.bonds):
        lines += ["", "Bonds", ""]
        lines += [f"{k} {t} {i + 1} {j + 1}" for k, (t, i, j) in enumerate(geom.bonds, start=1)]
    path.write_text("\n".join(lines) + "\n")
    return path
