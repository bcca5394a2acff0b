"""Material mapping: (E, nu, yield, ultimate, d, rho) -> BPM bond / granular pair coefficients.

The automata sit on a regular lattice with nearest neighbours one diameter
``d`` apart: a hexagonal (triangular) lattice in 2D, read as a sheet of
thickness ``d`` (plane stress), and an FCC lattice in 3D loaded along a cube
axis [100].  Each link has a normal stiffness ``k_n`` and, for
``bpm/rotational``, a shear stiffness ``k_s``.  For an affine strain the
elastic constants of such a lattice are

    C_ijkl = (d^2 / V) * sum_bonds [ (k_n - k_s) n_i n_j n_k n_l + k_s sym(delta_ik n_j n_l) ]

(``V`` = volume per automaton, sum over the bonds of one automaton counted
once each), from which the uniaxial Young's modulus and Poisson's ratio along
x follow.  :func:`lattice_moduli` evaluates this; :func:`map_material`
inverts it.

What a bond model can and cannot match
--------------------------------------
``bpm/spring/plastic`` (central springs, fast)
    * E: exact (linear in k_n).
    * nu: fixed by the lattice: 1/3 for both the hexagonal lattice and FCC
      along [100], whatever the material (steel 0.3: +11 %).
    * yield: elastic-perfectly plastic bonds, so the flow stress plateaus at a
      single value.  There is no hardening, so yield and ultimate strength
      cannot differ: the plateau is set to their mean, which is off by
      +/- (sigma_u - sigma_y) / (sigma_u + sigma_y) (7 % for the seed's
      steels, where sigma_u / sigma_y = 1.15).
    * rupture: at |strain| > failure strain, in tension AND compression
      (LAMMPS breaks on |e|).
    * FCC with central springs is elastically anisotropic (Zener ratio 2):
      E is matched along x only; along [110] it is 2x larger.
``bpm/rotational`` (normal + shear + bending springs, ~10x slower)
    * E and nu: both matched for nu in (-1, 1/3) in 2D (nu = (k_n - k_s) /
      (3 k_n + k_s)) and nu in (-1, 1/3) along FCC [100] in 3D.
    * no plasticity: brittle.  The bonds break at the ultimate strength in
      tension/shear only (LAMMPS's criterion ignores compression); the yield
      strength cannot be represented (measured yield = ultimate).

All inputs are SI; :class:`BondCoefficients` holds LAMMPS ``units nano``
numbers (nm, ag, ns, force 1e-12 N, stiffness 1e-3 N/m).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from functools import lru_cache

import numpy as np

from ..errors import ParameterError
from ..models.base import check_choice, check_range
from ..units import from_lammps, to_lammps

__all__ = [
    "link_deck_variables",
    "MAX_DIAMETER",
    "MIN_DIAMETER",
    "BondCoefficients",
    "MaterialSpec",
    "lattice_moduli",
    "lattice_vectors",
    "map_material",
    "measure_uniaxial",
    "stability_factor",
]

MIN_DIAMETER = 0.5e-9
MAX_DIAMETER = 50e-9


@dataclass(frozen=True)
class MaterialSpec:
    """A solid and its discretisation (SI units).

    Parameters
    ----------
    youngs_modulus : float
        E (Pa).
    poisson_ratio : float
        nu (matched only by ``bpm/rotational``).
    yield_strength, ultimate_strength : float
        sigma_y <= sigma_u (Pa).
    diameter : float
        Automaton diameter d (m), 0.5-50 nm.
    density : float
        Mass density (kg/m^3).
    dim : {2, 3}
        Lattice: hexagonal (2D) or FCC (3D).
    bond_style : str
        ``"bpm/spring/plastic"`` or ``"bpm/rotational"``.
    failure_strain : float
        Bond strain at rupture for ``bpm/spring/plastic`` (dimensionless).
    damping_ratio : float
        Fraction of critical damping of one link (bond and contact damping).
    contact_friction : float
        Coulomb cap of the viscous tangential force between touching,
        unlinked automata.
    contact_viscosity : float
        Viscosity of the seed's dissipative force between touching, unlinked
        automata (Pa s; used by the ``mca`` law, whose default is 0.05 Pa s).
    """

    youngs_modulus: float = 206e9
    poisson_ratio: float = 0.3
    yield_strength: float = 480e6
    ultimate_strength: float = 552e6
    diameter: float = 2.5e-9
    density: float = 7800.0
    dim: int = 2
    bond_style: str = "bpm/spring/plastic"
    failure_strain: float = 0.05
    damping_ratio: float = 0.1
    contact_friction: float = 0.5
    contact_viscosity: float = 0.05

    def __post_init__(self) -> None:
        check_range("youngs_modulus", self.youngs_modulus, 0.0, 2e12, lo_open=True, unit="Pa")
        check_range("poisson_ratio", self.poisson_ratio, -1.0, 0.5, lo_open=True, hi_open=True)
        check_range(
            "yield_strength",
            self.yield_strength,
            0.0,
            self.youngs_modulus,
            lo_open=True,
            hi_open=True,
            unit="Pa",
        )
        check_range(
            "ultimate_strength",
            self.ultimate_strength,
            self.yield_strength,
            self.youngs_modulus,
            hi_open=True,
            unit="Pa",
        )
        check_range("diameter", self.diameter, MIN_DIAMETER, MAX_DIAMETER, unit="m")
        check_range("density", self.density, 0.0, 1e5, lo_open=True, unit="kg/m^3")
        if self.dim not in (2, 3):
            raise ParameterError("dim", "2 or 3", self.dim)
        check_range("damping_ratio", self.damping_ratio, 0.0, 1.0)
        check_range("contact_friction", self.contact_friction, 0.0, 10.0)
        check_range("contact_viscosity", self.contact_viscosity, 0.0, 1e3, unit="Pa s")
        from .laws import get_law  # the law's own limits (registry: tribolmp.lammps.laws)

        get_law(self.bond_style).validate(self)


@dataclass(frozen=True)
class BondCoefficients:
    """Mapped LAMMPS coefficients (``units nano``) and what they reproduce.

    Attributes
    ----------
    mass : float
        Automaton mass (ag) = density x lattice volume per automaton.
    contact_diameter : float
        Diameter written to the data file (nm): ``d (1 - eps_crit)``.  Unlinked
        automata touch only when compressed to the rupture strain of a link, so
        that a link that breaks in compression (LAMMPS breaks plastic links on
        |strain|) hands its load to the contact without a force jump, and the
        compressive modulus stays that of the links.
    density_column : float
        Value for the data file's density column (ag/nm^3); LAMMPS sets the
        mass to ``density * pi D^3 / 6`` with D the contact diameter.
    k_n, k_s : float
        Normal / shear link stiffness (force/length, 1e-3 N/m).
    k_b, k_t : float
        Bending / twisting stiffness (force*length/rad) for bpm/rotational.
    eps_plastic, eps_crit : float
        Plastic (yield) strain and rupture strain of a spring/plastic link.
    f_crit, fs_crit, tb_crit, tt_crit : float
        Rupture limits of a bpm/rotational link (force, force*length).
    gamma_n, gamma_s : float
        Link damping (force/velocity, ag/ns).
    gamma_r, gamma_t : float
        Rolling / twisting damping of bpm/rotational (force*length/velocity).
    k_contact, gamma_contact, mu_contact : float
        Granular hooke contact between unlinked automata.
    dt_unit : float
        sqrt(m / k_n) (ns); the timestep is a fraction of it.
    dt_max_factor : float
        Verlet stability limit of the lattice in units of ``dt_unit``.
    target_E, model_E, target_nu, model_nu, flow_stress : float
        What the lattice gives (SI: Pa, -, Pa) against what was asked.
    """

    mass: float
    contact_diameter: float
    density_column: float
    k_n: float
    k_s: float
    k_b: float
    k_t: float
    eps_plastic: float
    eps_crit: float
    f_crit: float
    fs_crit: float
    tb_crit: float
    tt_crit: float
    gamma_n: float
    gamma_s: float
    gamma_r: float
    gamma_t: float
    k_contact: float
    gamma_contact: float
    mu_contact: float
    dt_unit: float
    dt_max_factor: float
    target_E: float
    model_E: float
    target_nu: float
    model_nu: float
    flow_stress: float

    def as_dict(self) -> dict:
        """Plain dict (for meta.json)."""
        return asdict(self)


def lattice_vectors(dim: int) -> tuple[np.ndarray, float]:
    """Return unit bond vectors of one automaton (each bond once) and its volume / d^3.

    Returns
    -------
    (ndarray (nb, 3), float)
        Hexagonal lattice (2D, 3 bonds, volume sqrt(3)/2 d^3 for a sheet of
        thickness d) or FCC (3D, 6 bonds, volume d^3 / sqrt(2)).
    """
    if dim == 2:
        ang = np.deg2rad([0.0, 60.0, 120.0])
        return np.column_stack([np.cos(ang), np.sin(ang), np.zeros(3)]), math.sqrt(3.0) / 2.0
    v = np.array(
        [[1, 1, 0], [1, -1, 0], [1, 0, 1], [1, 0, -1], [0, 1, 1], [0, 1, -1]], float
    ) / math.sqrt(2.0)
    return v, 1.0 / math.sqrt(2.0)


def _stiffness_tensor(k_n: float, k_s: float, d: float, dim: int) -> np.ndarray:
    n, vol = lattice_vectors(dim)
    c = np.zeros((3, 3, 3, 3))
    eye = np.eye(3)
    for b in n:
        nnnn = np.einsum("i,j,k,l->ijkl", b, b, b, b)
        # k_s acts on the tangential part of eps.n: |eps n|^2 - (n eps n)^2, symmetrised
        dnn = 0.25 * (
            np.einsum("ik,j,l->ijkl", eye, b, b)
            + np.einsum("jk,i,l->ijkl", eye, b, b)
            + np.einsum("il,j,k->ijkl", eye, b, b)
            + np.einsum("jl,i,k->ijkl", eye, b, b)
        )
        c += (k_n - k_s) * nnnn + k_s * dnn
    return c * d**2 / (vol * d**3)


def lattice_moduli(k_n: float, k_s: float, d: float, dim: int) -> tuple[float, float]:
    """Uniaxial Young's modulus and Poisson's ratio of the lattice along x.

    Parameters
    ----------
    k_n, k_s : float
        Normal and shear link stiffness (any force/length unit).
    d : float
        Nearest-neighbour distance (length unit).
    dim : {2, 3}
        2D: plane stress of a sheet of thickness d (in-plane axes x, y);
        3D: FCC loaded along [100].

    Returns
    -------
    (E, nu)
        E in force/length^2 of the inputs; nu = -eps_y / eps_x.
    """
    c = _stiffness_tensor(k_n, k_s, d, dim)
    axes = [0, 1] if dim == 2 else [0, 1, 2]
    # Voigt matrix on the normal components, shear decoupled for these symmetric lattices
    m = np.array([[c[i, i, j, j] for j in axes] for i in axes])
    s = np.linalg.inv(m)
    return 1.0 / s[0, 0], -s[1, 0] / s[0, 0]


@lru_cache(maxsize=32)
def stability_factor(dim: int, ks_ratio: float) -> float:
    """Verlet stability limit of the lattice, dt_max / sqrt(m / k_n).

    The largest normal-mode frequency is found on a grid over the Brillouin
    zone of the dynamical matrix D(q) = sum_b (1 - cos q.r_b) [k_n n n + k_s
    (1 - n n)] / m (both bond directions); velocity Verlet is stable for
    omega_max dt < 2.
    """
    n, _ = lattice_vectors(dim)
    qs = np.linspace(-2 * np.pi, 2 * np.pi, 41)
    grids = np.meshgrid(qs, qs, qs if dim == 3 else [0.0], indexing="ij")
    q = np.stack([g.ravel() for g in grids], axis=1)
    lam_max = 0.0
    eye = np.eye(3)
    for chunk in np.array_split(q, 8):
        dmat = np.zeros((len(chunk), 3, 3))
        for b in n:
            phase = 2.0 * (1.0 - np.cos(chunk @ b))  # bonds +b and -b
            proj = ks_ratio * eye + (1.0 - ks_ratio) * np.outer(b, b)
            dmat += phase[:, None, None] * proj
        lam_max = max(lam_max, float(np.linalg.eigvalsh(dmat).max()))
    return 2.0 / math.sqrt(lam_max)


def map_material(spec: MaterialSpec) -> BondCoefficients:
    """Convert a :class:`MaterialSpec` (SI) into LAMMPS ``units nano`` coefficients.

    Parameters
    ----------
    spec : MaterialSpec

    Returns
    -------
    BondCoefficients
    """
    d = to_lammps(spec.diameter, "length")
    e_target = to_lammps(spec.youngs_modulus, "pressure")
    rho = to_lammps(spec.density, "density")
    _, vol = lattice_vectors(spec.dim)
    mass = rho * vol * d**3

    if spec.bond_style == "bpm/rotational":
        ratio = _ks_ratio_for_nu(spec.poisson_ratio, spec.dim)
    else:
        ratio = 0.0
    e_unit, nu_model = lattice_moduli(1.0, ratio, d, spec.dim)
    k_n = e_target / e_unit
    k_s = ratio * k_n
    flow = 0.5 * (spec.yield_strength + spec.ultimate_strength)
    # bond strain per unit uniaxial strain of the most strained link (1 in 2D, 1/3 along FCC [100])
    bond_per_strain = _max_bond_strain(ratio, spec.dim, nu_model)
    eps_plastic = (flow / spec.youngs_modulus) * bond_per_strain
    eps_crit = spec.failure_strain * bond_per_strain
    # rotational rupture: normal + shear force of the critical link at sigma_u
    fn_u, fs_u = _critical_link_forces(
        k_n, k_s, d, spec.dim, to_lammps(spec.ultimate_strength, "pressure")
    )
    # B = fn/fcr + fs/fscr = 1 at sigma_u with fcr = fscr
    f_crit = fn_u + fs_u
    fs_crit = f_crit
    big = 1e6 * f_crit * d  # torque limits that never govern
    gamma_c = math.sqrt(2.0 * k_n * mass)  # critical damping of a link (reduced mass m/2)
    gamma_n = spec.damping_ratio * gamma_c
    k_b = k_t = k_s * d**2 / 4.0
    dt_unit = math.sqrt(mass / k_n)
    # rotational links never break in compression; their contacts still start at the rupture strain
    contact_d = d * (1.0 - eps_crit)
    return BondCoefficients(
        mass=mass,
        contact_diameter=contact_d,
        density_column=mass / (math.pi * contact_d**3 / 6.0),
        k_n=k_n,
        k_s=k_s,
        k_b=k_b,
        k_t=k_t,
        eps_plastic=eps_plastic,
        eps_crit=eps_crit,
        f_crit=f_crit,
        fs_crit=fs_crit,
        tb_crit=big,
        tt_crit=big,
        gamma_n=gamma_n,
        gamma_s=gamma_n * ratio,
        gamma_r=gamma_n * ratio * d**2 / 4.0,
        gamma_t=gamma_n * ratio * d**2 / 4.0,
        k_contact=k_n,
        gamma_contact=gamma_n,
        mu_contact=spec.contact_friction,
        dt_unit=dt_unit,
        dt_max_factor=stability_factor(spec.dim, ratio),
        target_E=spec.youngs_modulus,
        model_E=spec.youngs_modulus,
        target_nu=spec.poisson_ratio,
        model_nu=float(nu_model),
        flow_stress=flow if spec.bond_style == "bpm/spring/plastic" else spec.ultimate_strength,
    )



def link_deck_variables(
    c: BondCoefficients, bond_style: str = "bpm/spring/plastic"
) -> dict[str, str]:
    """Deck variables of the link coefficients (LAMMPS nano units), from the law registry.

    Both decks (``mca_friction.in`` and ``mca_tension.in``) read the same
    names; the law's entry in :data:`tribolmp.lammps.laws.BOND_LAWS` renders them.
    """
    from .laws import get_law

    return dict(get_law(bond_style).deck_variables(c))


def _ks_ratio_for_nu(nu: float, dim: int) -> float:
    """k_s / k_n giving Poisson's ratio ``nu`` along x (monotone in the ratio)."""
    from scipy.optimize import brentq

    def f(r: float) -> float:
        return lattice_moduli(1.0, r, 1.0, dim)[1] - nu

    return float(brentq(f, 0.0, 50.0, xtol=1e-12))


def _uniaxial_strain(ratio: float, dim: int) -> np.ndarray:
    """Strain tensor for unit uniaxial strain along x under uniaxial stress."""
    _, nu = lattice_moduli(1.0, ratio, 1.0, dim)
    eps = np.zeros((3, 3))
    eps[0, 0] = 1.0
    eps[1, 1] = -nu
    if dim == 3:
        eps[2, 2] = -nu
    return eps


def _max_bond_strain(ratio: float, dim: int, nu: float) -> float:
    n, _ = lattice_vectors(dim)
    eps = _uniaxial_strain(ratio, dim)
    return float(max(abs(b @ eps @ b) for b in n))


def _critical_link_forces(
    k_n: float, k_s: float, d: float, dim: int, sigma: float
) -> tuple[float, float]:
    """Return the tension and shear force of the most loaded link at uniaxial stress ``sigma``."""
    n, _ = lattice_vectors(dim)
    e_mod, _ = lattice_moduli(k_n, k_s, d, dim)
    eps = _uniaxial_strain(k_s / k_n, dim) * (sigma / e_mod)
    best = (0.0, 0.0)
    for b in n:
        en = b @ eps @ b
        es = math.sqrt(max(0.0, float(b @ eps @ eps @ b) - en**2))
        fn, fs = k_n * d * max(en, 0.0), k_s * d * es
        if fn + fs > sum(best):
            best = (fn, fs)
    return best


def measure_uniaxial(
    spec: MaterialSpec,
    *,
    mode: str = "tension",
    strain: float | None = None,
    strain_rate: float = 5e7,
    n: int | None = None,
    out_dir=None,
):
    """Measure E, nu, yield and ultimate strength of the mapped lattice in LAMMPS.

    Runs ``lammps_inputs/mca_tension.in`` on a bonded block (periodic along
    x, free lateral surfaces) stretched or compressed affinely at a constant
    strain rate.

    Parameters
    ----------
    spec : MaterialSpec
        Material and discretisation (SI).
    mode : {"tension", "compression"}
        Loading direction.
    strain : float, optional
        Final engineering strain magnitude; default 1.5 x the failure strain
        in tension (to pass rupture), 5 x the flow strain in compression.
    strain_rate : float
        Engineering strain rate magnitude (1/s); the default 5e7 /s keeps
        link damping forces below 0.5 % of the yield force.
    n : int, optional
        Lattice repeats per side (default 14 in 2D, 5 in 3D).
    out_dir : path, optional
        Where the data file, log and ``tension.csv`` go (default: a temporary folder).

    Returns
    -------
    Result
        ``youngs_modulus`` (Pa, fit over the first half of the elastic range),
        ``poisson_ratio`` (-lateral/axial strain, y), ``yield_strength``
        (Pa, 0.2 % offset), ``ultimate_strength`` (Pa, max |stress|),
        ``strain`` and ``stress`` (Pa) arrays, ``bonds_broken``.
    """
    import tempfile
    from pathlib import Path

    from ..models.base import Result, timed
    from .build import build_block, write_bpm_data
    from .decks import deck_path, laws_dir
    from .laws import get_law
    from .session import LammpsSession

    check_choice("mode", mode, ("tension", "compression"))
    c = map_material(spec)
    flow_strain = c.flow_stress / spec.youngs_modulus
    if strain is None:
        strain = 1.5 * spec.failure_strain if mode == "tension" else 5.0 * flow_strain
    check_range("strain", strain, 0.0, 0.5, lo_open=True)
    d = to_lammps(spec.diameter, "length")
    geom = build_block(dim=spec.dim, d=d, n=n or (14 if spec.dim == 2 else 5))
    tmp = None
    if out_dir is None:
        tmp = tempfile.TemporaryDirectory(prefix="mca_tension_")
        out_dir = tmp.name
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    data = write_bpm_data(
        out / "block.data", geom, density=c.density_column, diameter=c.contact_diameter
    )
    dt = 0.1 * c.dt_unit
    # elastic part (to 2x the flow strain) 10x slower, so the lateral barostat keeps up
    sign = 1.0 if mode == "tension" else -1.0
    erate = sign * strain_rate * from_lammps(1.0, "time")  # 1/s -> 1/(LAMMPS time unit)
    slow = min(2.0 * flow_strain, strain)
    steps_slow = int(math.ceil(slow / (0.1 * abs(erate) * dt)))
    steps = max(1, int(math.ceil((strain - slow) / (abs(erate) * dt))))
    every = max(1, (steps + steps_slow) // 600)
    variables = {
        "data": data,
        "out": out,
        "dim": spec.dim,
        "bond": get_law(spec.bond_style).keyword,
        "lawdir": laws_dir(),
        "dt": f"{dt:.10g}",
        "erate": f"{erate:.10g}",
        "steps": steps,
        "print_every": every,
        "erate_slow": f"{0.1 * erate:.10g}",
        "steps_slow": steps_slow,
        **link_deck_variables(c, spec.bond_style),
        "comm_cut": f"{2.2 * d:.10g}",
        "modulus": f"{to_lammps(spec.youngs_modulus, 'pressure'):.10g}",
    }
    res = Result(
        method=f"lammps/{spec.bond_style}/{mode}",
        units={
            "youngs_modulus": "Pa",
            "yield_strength": "Pa",
            "ultimate_strength": "Pa",
            "stress": "Pa",
            "poisson_ratio": "1",
        },
    )
    with timed(res):
        with LammpsSession(log=None, variables=variables) as lmp:
            lmp.file(deck_path("mca_tension"))
            bonds_end = int(lmp.thermo("bonds"))
        table = np.loadtxt(out / "tension.csv", delimiter=",", skiprows=1, ndmin=2)
    _, vol = lattice_vectors(spec.dim)
    v_mat = geom.n_atoms * vol * d**3
    eps = np.abs(table[:, 0])
    sigma = from_lammps(np.abs(table[:, 1]) / v_mat, "pressure")  # Pa
    lateral = table[:, 2]
    elastic = (eps > 0) & (eps <= 0.5 * flow_strain)
    e_fit = float(np.polyfit(eps[elastic], sigma[elastic], 1)[0])
    nu_fit = float(-np.polyfit(np.sign(table[elastic, 0]) * eps[elastic], lateral[elastic], 1)[0])
    # 0.2 % offset yield; a lattice that ruptures first (brittle) has none: NaN
    offset = sigma < e_fit * (eps - 0.002)
    yield_s = float(sigma[np.argmax(offset)]) if offset.any() else float("nan")
    if yield_s < 0.9 * sigma.max():  # the offset line was crossed by the post-rupture drop
        yield_s = float("nan")
    res.update(
        youngs_modulus=e_fit,
        poisson_ratio=nu_fit,
        yield_strength=yield_s,
        ultimate_strength=float(sigma.max()),
        strain=eps,
        stress=sigma,
        bonds_broken=len(geom.bonds) - bonds_end,
        nit=steps + steps_slow,
    )
    if tmp is not None:
        tmp.cleanup()
    return res
