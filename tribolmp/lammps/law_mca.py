"""The MCA interaction law (``pair_style mca``): SI parameters -> LAMMPS coefficients.

The law itself lives in C++ (``tribolmp/lammps/plugin_src``, one function per
rule in ``mca_law.h``; the derivation is in ``docs/mca.md``, "The MCA law").
This module owns its parameters (SI, validated, frozen), converts them to
LAMMPS ``units nano`` through :mod:`tribolmp.units`, and renders the deck
fragment that selects the law.

Geometry conventions are those of :mod:`tribolmp.lammps.mapping`: automata of
diameter ``d`` on a hexagonal lattice (2D, a sheet of thickness ``d``, here in
plane strain) or an FCC lattice (3D).  The pair area ``A`` and the automaton
volume ``V`` below are the ones the C++ uses (``pair_area``,
``automaton_volume``).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, replace

from ..errors import ParameterError
from ..models.base import check_range
from ..units import to_lammps

__all__ = [
    "McaCoefficients",
    "McaLaw",
    "law_from_spec",
    "map_spec",
    "validate_spec",
    "automaton_volume",
    "pair_area",
    "mca_deck_variables",
    "mca_pair_commands",
    "REQUIRED_PLUGIN_STYLES",
]

#: (category, style) pairs the law needs (provided by the tribolmp plugin).
REQUIRED_PLUGIN_STYLES = (("pair", "mca"), ("fix", "mca/state"), ("atom", "bpm/sphere"))


def pair_area(dbar: float, dim: int) -> float:
    """Contact area of a pair of automata with ``r_a + r_b = dbar`` (same unit squared).

    Chosen so that a close-packed lattice's Love-Weber stress equals the pair
    traction: ``A dbar / (2 V) = D / Z`` (Z = 6 in 2D, 12 in 3D).
    """
    return dbar * dbar / (2.0 * math.sqrt(2.0)) if dim == 3 else dbar * dbar / math.sqrt(3.0)


def automaton_volume(d: float, dim: int) -> float:
    """Voronoi volume of an automaton of diameter ``d`` (2D: sheet of thickness ``d``)."""
    return d**3 / math.sqrt(2.0) if dim == 3 else 0.5 * math.sqrt(3.0) * d**3


@dataclass(frozen=True)
class McaLaw:
    """Parameters of the MCA interaction law (SI units).

    Parameters
    ----------
    youngs_modulus : float
        E (Pa).
    poisson_ratio : float
        nu; any value in (-0.25, 0.5) in 3D and (-0.5, 0.5) in 2D (the range in
        which the explicit mean-stress term converges, |alpha| < 1).
    yield_strength : float
        Initial von Mises yield stress sigma_y (Pa).
    ultimate_strength : float
        sigma_0 >= sigma_y (Pa): end of the hardening and strength of a bulk link.
    hardening_strain : float
        Equivalent plastic strain at which the linear hardening reaches
        sigma_0 (default 0.05; the seed gives only sigma_y and sigma_0).
    contact_friction : float
        Coulomb coefficient between touching, unlinked automata.
    contact_viscosity : float
        Viscosity of the seed's dissipative force between touching, unlinked
        automata (Pa s): F = eta A / d * v_rel.  The default 0.05 Pa s damps a
        contact of 2.5 nm steel automata at about 20 % of critical.
    weld_factor : float
        Weld strength as a fraction of sigma_0 (default 0.5: a cold-pressure
        weld without heat or diffusion; junctions in cold welding of steels
        reach roughly a third to two thirds of the bulk strength).
    weld_onset : float or None
        Compressive pair stress at which an unlinked contact welds (Pa);
        default sigma_y: a junction forms where the contact is pressed into
        plastic flow.
    link_damping : float
        Damping of links, fraction of critical of one pair (numerical: it
        removes lattice ringing; zero in affinely loaded material tests).
    diameter : float
        Automaton diameter d (m).
    density : float
        Mass density (kg/m^3); the automaton mass is density x V.
    dim : {2, 3}
        2D (plane strain) or 3D.
    """

    youngs_modulus: float = 206e9
    poisson_ratio: float = 0.3
    yield_strength: float = 480e6
    ultimate_strength: float = 552e6
    hardening_strain: float = 0.05
    contact_friction: float = 0.5
    contact_viscosity: float = 0.05
    weld_factor: float = 0.5
    weld_onset: float | None = None
    link_damping: float = 0.1
    diameter: float = 2.5e-9
    density: float = 7800.0
    dim: int = 2

    def __post_init__(self) -> None:
        if self.dim not in (2, 3):
            raise ParameterError("dim", "2 or 3", self.dim)
        check_range("youngs_modulus", self.youngs_modulus, 0.0, 2e12, lo_open=True, unit="Pa")
        nulo = -0.25 if self.dim == 3 else -0.5
        check_range("poisson_ratio", self.poisson_ratio, nulo, 0.5, lo_open=True, hi_open=True)
        check_range(
            "yield_strength", self.yield_strength, 0.0, self.youngs_modulus, lo_open=True, unit="Pa"
        )
        check_range(
            "ultimate_strength",
            self.ultimate_strength,
            self.yield_strength,
            self.youngs_modulus,
            unit="Pa",
        )
        check_range("hardening_strain", self.hardening_strain, 0.0, 10.0, lo_open=True)
        check_range("contact_friction", self.contact_friction, 0.0, 10.0)
        check_range("contact_viscosity", self.contact_viscosity, 0.0, 1e3, unit="Pa s")
        check_range("weld_factor", self.weld_factor, 0.0, 1.0)
        if self.weld_onset is not None:
            check_range("weld_onset", self.weld_onset, 0.0, self.youngs_modulus, unit="Pa")
        check_range("link_damping", self.link_damping, 0.0, 1.0)
        check_range("diameter", self.diameter, 0.5e-9, 50e-9, unit="m")
        check_range("density", self.density, 0.0, 1e5, lo_open=True, unit="kg/m^3")

    # ------------------------------------------------------------ derived (SI)
    @property
    def shear_modulus(self) -> float:
        """G = E / (2 (1 + nu)) (Pa)."""
        return self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))

    @property
    def bulk_modulus(self) -> float:
        """K = E / (3 (1 - 2 nu)) (Pa)."""
        return self.youngs_modulus / (3.0 * (1.0 - 2.0 * self.poisson_ratio))

    @property
    def lame_lambda(self) -> float:
        """Lame's first parameter (Pa)."""
        nu = self.poisson_ratio
        return 2.0 * self.shear_modulus * nu / (1.0 - 2.0 * nu)

    @property
    def alpha(self) -> float:
        """Weight of the mean-stress term: 3 nu/(1+nu) (3D), 2 nu (2D plane strain)."""
        nu = self.poisson_ratio
        return 3.0 * nu / (1.0 + nu) if self.dim == 3 else 2.0 * nu

    @property
    def contact_modulus(self) -> float:
        """Normal stiffness of an unlinked contact, Kc = 2G / (1 - alpha) (Pa)."""
        return 2.0 * self.shear_modulus / (1.0 - self.alpha)

    @property
    def hardening_modulus(self) -> float:
        """H = (sigma_0 - sigma_y) / hardening_strain (Pa)."""
        return (self.ultimate_strength - self.yield_strength) / self.hardening_strain

    @property
    def weld_onset_stress(self) -> float:
        """Compressive pair stress that welds a contact (Pa)."""
        return self.yield_strength if self.weld_onset is None else self.weld_onset

    @property
    def mass(self) -> float:
        """Automaton mass (kg)."""
        return self.density * automaton_volume(self.diameter, self.dim)

    def timestep_unit(self) -> float:
        """sqrt(m / k) of the stiffest pair spring, k = Kc A / d (s)."""
        d = self.diameter
        k = self.contact_modulus * pair_area(2.0 * 0.5 * d, self.dim) / d
        return math.sqrt(self.mass / k)

    def replace(self, **changes) -> McaLaw:
        """Return a copy with some fields changed (validated again)."""
        return replace(self, **changes)

    def as_dict(self) -> dict:
        """Plain dict of the parameters (SI)."""
        return asdict(self)


_COEFF_ORDER = ("G", "nu", "sy", "s0", "H", "mu", "eta", "wfac", "wonset", "damp")


def mca_deck_variables(law: McaLaw) -> dict[str, str]:
    """Return the deck variables of ``pair_coeff * * G nu sy s0 H mu eta wfac wonset damp``.

    All converted to LAMMPS ``units nano`` (pressure 1e6 Pa, viscosity 1e-3 Pa s).
    """
    p = lambda v: f"{to_lammps(v, 'pressure'):.10g}"  # noqa: E731
    return {
        "G": p(law.shear_modulus),
        "nu": f"{law.poisson_ratio:.10g}",
        "sy": p(law.yield_strength),
        "s0": p(law.ultimate_strength),
        "H": p(law.hardening_modulus),
        "mu": f"{law.contact_friction:.10g}",
        "eta": f"{to_lammps(law.contact_viscosity, 'viscosity'):.10g}",
        "wfac": f"{law.weld_factor:.10g}",
        "wonset": p(law.weld_onset_stress),
        "damp": f"{law.link_damping:.10g}",
    }


def mca_pair_commands(law: McaLaw, plugin: str | None = None) -> list[str]:
    """Return the deck fragment that selects the MCA law (after ``read_data``).

    Parameters
    ----------
    law : McaLaw
    plugin : str, optional
        Path of the plugin; when given, ``plugin load`` is the first line.

    Returns
    -------
    list of str
        LAMMPS commands.  The deck must use ``atom_style bpm/sphere`` (or
        sphere) and integrate with ``fix nve/sphere``
        or ``fix nve/bpm/sphere`` (plus ``fix enforce2d`` in 2D).
    """
    v = mca_deck_variables(law)
    lines = [f"plugin load {plugin}"] if plugin else []
    lines += [
        "pair_style mca",
        "pair_coeff * * " + " ".join(v[k] for k in _COEFF_ORDER),
    ]
    return lines


# ---------------------------------------------------------------- registry hooks (laws.py)


def law_from_spec(spec) -> McaLaw:
    """Return the :class:`McaLaw` of a :class:`~tribolmp.lammps.mapping.MaterialSpec` (SI)."""
    return McaLaw(
        youngs_modulus=spec.youngs_modulus,
        poisson_ratio=spec.poisson_ratio,
        yield_strength=spec.yield_strength,
        ultimate_strength=spec.ultimate_strength,
        contact_friction=min(spec.contact_friction, 10.0),
        contact_viscosity=getattr(spec, "contact_viscosity", McaLaw.contact_viscosity),
        link_damping=spec.damping_ratio,
        diameter=spec.diameter,
        density=spec.density,
        dim=spec.dim,
    )


def validate_spec(spec) -> None:
    """Raise a one-line ``ParameterError`` for a material the MCA law cannot represent."""
    law_from_spec(spec)


@dataclass(frozen=True)
class McaCoefficients:
    """What the MCA decks need from the mapping (LAMMPS ``units nano`` unless noted).

    Attributes
    ----------
    law : McaLaw
        The SI parameters.
    mass : float
        Automaton mass (ag) = density x lattice volume per automaton.
    contact_diameter : float
        Diameter written to the data file (nm): the lattice spacing d (links
        start stress-free at d; unlinked automata touch at d).
    density_column : float
        Data-file density (ag/nm^3) giving ``mass`` (LAMMPS: density pi D^3 / 6).
    dt_unit : float
        sqrt(m / k) of the stiffest pair spring k = Kc A / d (ns).
    dt_max_factor : float
        Verlet stability limit in units of dt_unit, 2 (sqrt(1 + zeta^2) - zeta)
        / sqrt(2 Z): the limit of an explicit step for a damped oscillator,
        taken with the Gershgorin bounds of the dynamical matrix (omega^2 <= 2 Z
        k / m, Z = 6 / 12 neighbours; the rotational modes stay below it since
        the shear stiffness 2G < Kc) and of the contact-viscosity matrix
        (lambda <= 2 Z c / m, c = eta A / d), zeta = lambda / (2 omega).  Without
        viscosity it is 2 / sqrt(2 Z).
    flow_stress : float
        Normal pressure (Pa) at which a laterally confined slab yields:
        sigma_y (1 - nu) / (1 - 2 nu) (uniaxial strain).
    k_contact, gamma_contact, mu_contact : float
        Contact stiffness Kc A / d, its critical damping x link_damping, and
        the friction coefficient (for drivers that report them).
    """

    law: McaLaw
    mass: float
    contact_diameter: float
    density_column: float
    dt_unit: float
    dt_max_factor: float
    flow_stress: float
    k_contact: float
    gamma_contact: float
    mu_contact: float

    def as_dict(self) -> dict:
        """Plain dict (SI law parameters + nano coefficients) for meta.json."""
        out = asdict(self)
        out["law"] = self.law.as_dict()
        return out


def map_spec(spec) -> McaCoefficients:
    """Map a :class:`~tribolmp.lammps.mapping.MaterialSpec` onto the MCA law (SI -> nano)."""
    law = law_from_spec(spec)
    d = to_lammps(law.diameter, "length")
    mass = to_lammps(law.mass, "mass")
    area = pair_area(d, law.dim)
    k = to_lammps(law.contact_modulus, "pressure") * area / d
    z = 6 if law.dim == 2 else 12
    nu = law.poisson_ratio
    dt_unit = math.sqrt(mass / k)
    # Why the viscosity enters: the seed's viscous force acts on every touching pair with
    # c = eta A / d; an explicit step on a mode damped at zeta is stable only for
    # omega dt <= 2 (sqrt(1 + zeta^2) - zeta) (central difference with the damping force
    # from the current velocities).  Measured on the smoke box at 150 MPa, 2D (limit from this
    # formula in brackets; MCAParams allows half of it): eta = 0.05 and 0.1 Pa s at dt_factor
    # 0.1 run (0.354, 0.236); 0.2 Pa s at 0.1 loses automata within 0.3 ns (0.134, so the
    # bound alone is not conservative, its half is); 0.2 Pa s at 0.05 runs.
    c = to_lammps(law.contact_viscosity, "viscosity") * area / d
    omega_dt = math.sqrt(2.0 * z)  # omega_max * dt_unit
    zeta = (2.0 * z * c / mass * dt_unit) / (2.0 * omega_dt)
    return McaCoefficients(
        law=law,
        mass=mass,
        contact_diameter=d,
        density_column=mass / (math.pi * d**3 / 6.0),
        dt_unit=dt_unit,
        dt_max_factor=2.0 * (math.sqrt(1.0 + zeta**2) - zeta) / omega_dt,
        flow_stress=law.yield_strength * (1.0 - nu) / (1.0 - 2.0 * nu),
        k_contact=k,
        gamma_contact=law.link_damping * 2.0 * math.sqrt(k * 0.5 * mass),
        mu_contact=law.contact_friction,
    )


def registry_deck_variables(c: McaCoefficients) -> dict[str, str]:
    """Deck variables of the ``mca`` fragment (``lammps_inputs/laws/mca.in``)."""
    return mca_deck_variables(c.law)


def registry_setup() -> dict[str, str]:
    """Build (or find) the plugin before LAMMPS starts; the fragment loads ``${mca_plugin}``."""
    from .plugin import plugin_path

    return {"mca_plugin": str(plugin_path())}
