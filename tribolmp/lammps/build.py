"""Geometry of the MCA friction experiment, built with ASE and written as a ``bpm/sphere`` data file.

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
        """Number of automata with molecule id ``mol``."""
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

    Returns
    -------
    MCAGeometry
    """
    if dim not in (2, 3):
        raise ParameterError("dim", "2 or 3", dim)
    if not (0.0 < hurst <= 1.0):
        raise ParameterError("hurst", "a number in (0, 1]", hurst)
    if dim == 2:
        nx = max(4, int(round(length / d)))
        nrows = max(4, int(math.ceil(body_height / (math.sqrt(3.0) / 2.0 * d)))) + 4
        lower, dy = _hex_block(nx, nrows + RIGID_ROWS, d)
        upper, _ = _hex_block(nx, nrows + RIGID_ROWS, d)
        lx, lz = nx * d, d
        nsurf: int | tuple[int, int] = 4 * nx
        nz = 1
    else:
        a = math.sqrt(2.0) * d
        nx = max(2, int(round(length / a)))
        nz = max(2, int(round((width if width is not None else length / 4.0) / a)))
        ncell = max(2, int(math.ceil(body_height / a))) + 2
        lower, dy = _fcc_block(nx, ncell + 1, nz, d)
        upper, _ = _fcc_block(nx, ncell + 1, nz, d)
        lx, lz = nx * a, nz * a
        nsurf = (4 * nx, 4 * nz)
    h_lo = self_affine_profile(nsurf, roughness_rms, hurst, rng)
    h_up = self_affine_profile(nsurf, roughness_rms, hurst, rng)

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
    bonds = _neighbour_bonds(pos, mol, box, d, dim)
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
    """Vertical shift of the upper body that closes the gap in a fraction ``frac`` of the columns."""
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
    """A single bonded, fully periodic block (mol 2, type 1) for uniaxial tests.

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
) -> np.ndarray:
    """Bonds between nearest neighbours (distance < 1.05 d) of the same body, plus attachments.

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
    pairs = tree.query_pairs(1.05 * d, output_type="ndarray")
    mi, mj = mol[pairs[:, 0]], mol[pairs[:, 1]]
    rigid = {MOL_BASE, MOL_SLIDER}
    same_body = (mi == mj) & ~np.isin(mi, list(rigid))
    attach = ((mi == MOL_BASE) & (mj == MOL_LOWER)) | ((mj == MOL_BASE) & (mi == MOL_LOWER))
    attach |= ((mi == MOL_SLIDER) & (mj == MOL_UPPER)) | ((mj == MOL_SLIDER) & (mi == MOL_UPPER))
    btype = np.where(same_body, BOND_BODY, np.where(attach, BOND_ATTACH, 0))
    sel = btype > 0
    out = np.column_stack([btype[sel], np.sort(pairs[sel], axis=1)])
    return out[np.lexsort((out[:, 2], out[:, 1]))]


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
    body = [
        f"{i} {m} {t} {dia:.10g} {density:.10g} {x:.10g} {y:.10g} {z:.10g}"
        for i, m, t, (x, y, z) in zip(ids, mol, typ, pos, strict=True)
    ]
    lines += body
    if len(geom.bonds):
        lines += ["", "Bonds", ""]
        lines += [f"{k} {t} {i + 1} {j + 1}" for k, (t, i, j) in enumerate(geom.bonds, start=1)]
    path.write_text("\n".join(lines) + "\n")
    return path
