"""The registry of MCA interaction (bond) laws: one entry per law, plus its deck fragment.

A law is everything that differs between link models in the MCA decks: the
LAMMPS styles it needs, how the material (SI) maps onto its coefficients, the
deck variables that carry them, its validity limits, and the deck fragment
``lammps_inputs/laws/<keyword>.in`` that issues its LAMMPS commands.  Both
decks (``mca_friction.in`` and ``mca_tension.in``) ``include`` the fragment;
everything else in them is law-independent.  Adding a law is therefore one
:class:`BondLaw` entry in :data:`BOND_LAWS` and one fragment file (contract C4
in CONTRACTS.md).

Fragment contract (what the decks provide and expect)
-----------------------------------------------------
Provided by the decks before ``include``: the box and atoms (``read_data`` or
``read_restart``), ``${resume}`` (1 after ``read_restart``), ``${mca_context}``
(``friction`` or ``tension``), ``${dim}``, ``${comm_cut}``, ``${smooth}``
(one smoothing setting for both decks), groups ``mobile`` (deformable
automata, friction) and ``all``, and every variable the law's
``deck_variables`` returned.
Expected from the fragment, in context ``friction``: the link style and
coefficients for bond types 1 (original), 2 (re-formed), 3 (unbreakable
attachment) when ``${resume} == 0`` (a restart file carries them), the
contact interaction between unlinked automata (always: pair styles without
history are not in restart files), any re-linking/welding fix, and a per-atom
compute with ID ``nbond`` (links per automaton, dumped as ``c_nbond``).  In
context ``tension``: the link style for every bond type and no contact forces.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any

from ..errors import ParameterError

__all__ = ["BOND_LAWS", "DEFAULT_LAW", "NEIGHBOR_SKIN", "BondLaw", "get_law", "law_names"]


def _rot_nu_limit(spec) -> None:
    if spec.poisson_ratio >= 1.0 / 3.0:
        raise ParameterError(
            "poisson_ratio", "a number in (-1, 1/3) for bpm/rotational lattices", spec.poisson_ratio
        )


def _failure_strain_limit(spec) -> None:
    flow = 0.5 * (spec.yield_strength + spec.ultimate_strength) / spec.youngs_modulus
    # the rupture strain must clear the flow strain well, else links break before they yield
    if not (3.0 * flow < spec.failure_strain <= 0.5):
        raise ParameterError(
            "failure_strain",
            f"a number in ({3.0 * flow:.3g}, 0.5] (> 3x the flow strain {flow:.3g})",
            spec.failure_strain,
        )


def _bpm_plastic_validate(spec) -> None:
    _failure_strain_limit(spec)


def _bpm_rotational_validate(spec) -> None:
    _failure_strain_limit(spec)
    _rot_nu_limit(spec)


def _bpm_map(spec):
    from .mapping import map_material

    return map_material(spec)


#: deck variable -> BondCoefficients attribute, per bpm law (LAMMPS nano units)
_PLASTIC_VARIABLES = (
    ("kn", "k_n"),
    ("ecrit", "eps_crit"),
    ("gn", "gamma_n"),
    ("ep", "eps_plastic"),
)
_ROTATIONAL_VARIABLES = (
    ("kn", "k_n"), ("ks", "k_s"), ("kb", "k_b"), ("kt", "k_t"), ("fcr", "f_crit"),
    ("fscr", "fs_crit"), ("tbcr", "tb_crit"), ("ttcr", "tt_crit"), ("gn", "gamma_n"),
    ("gs", "gamma_s"), ("gr", "gamma_r"), ("gt", "gamma_t"),
)


def _render(table):
    def variables(coeff) -> dict[str, str]:
        return {name: f"{getattr(coeff, attr):.10g}" for name, attr in table}

    return variables


@dataclass(frozen=True)
class BondLaw:
    """One interaction law of the MCA decks.

    Attributes
    ----------
    name : str
        The value of ``MCAParams.bond_style`` / ``MaterialSpec.bond_style``
        / ``[nanoscale].bond_style`` (e.g. ``"bpm/spring/plastic"``).
    keyword : str
        Deck keyword: ``-var bond KEYWORD`` selects the fragment
        ``lammps_inputs/laws/KEYWORD.in``.
    styles : tuple of (category, style)
        LAMMPS styles the fragment uses (checked before a run starts).
    map_material : callable
        ``map_material(spec: MaterialSpec) -> coefficients``; the result
        carries at least the attributes the driver reads: ``mass``,
        ``contact_diameter``, ``density_column``, ``dt_unit``,
        ``dt_max_factor``, ``flow_stress`` (Pa); LAMMPS ``units nano``.
    deck_variables : callable
        ``deck_variables(coeff) -> {name: str}``: the law's coefficient
        variables (LAMMPS ``units nano``), declared with defaults by the
        fragment.
    validate : callable
        ``validate(spec) -> None``; raises ``ParameterError`` (one line,
        field and expected range) for materials the law cannot represent.
    setup : callable, optional
        ``setup() -> {name: str}``, run before LAMMPS starts (e.g. build and
        locate a plugin); extra deck variables, e.g. the plugin path.
    deferred_fragment : str, optional
        File in ``lammps_inputs/laws/`` that the Python driver includes at the
        first step ``s`` of every chunk with ``(s + 1) % rebond_every == 0``
        (the bpm laws' ``fix bond/create``; see ``bpm_relink.in`` for why).
    coordination_cap : bool
        Informational: True when the law's links are LAMMPS bonds (bond slots per atom).
    ghost_cutoff : float
        Communication (ghost) cutoff of the friction deck in automaton diameters (the deck
        variable ``comm_cut``; LAMMPS raises it to the neighbour cutoff if that is longer).
        The bpm laws keep 2.2 d (links stretched to rupture and the 1-2 partners of
        ``fix bond/create``); the mca law needs only its neighbour range.
    doc : str
        One line for ``--help`` and the docs.
    """

    name: str
    keyword: str
    styles: tuple[tuple[str, str], ...]
    map_material: Callable[[Any], Any]
    deck_variables: Callable[..., Mapping[str, str]]
    validate: Callable[[Any], None]
    setup: Callable[[], Mapping[str, str]] | None = None
    deferred_fragment: str | None = None
    coordination_cap: bool = True
    doc: str = field(default="")
    ghost_cutoff: float = 2.2


#: Verlet skin of the friction deck's neighbour lists, in automaton diameters (every law).
NEIGHBOR_SKIN = 0.3


_COMMON_STYLES = (("atom", "bpm/sphere"), ("fix", "nve/bpm/sphere"))


def _mca_map(spec):
    from .law_mca import map_spec

    return map_spec(spec)


def _mca_variables(coeff) -> dict[str, str]:
    from .law_mca import registry_deck_variables

    return registry_deck_variables(coeff)


def _mca_validate(spec) -> None:
    from .law_mca import validate_spec

    validate_spec(spec)


def _mca_setup() -> dict[str, str]:
    from .law_mca import registry_setup

    return registry_setup()

BOND_LAWS: Mapping[str, BondLaw] = MappingProxyType(
    {
        "bpm/spring/plastic": BondLaw(
            name="bpm/spring/plastic",
            keyword="plastic",
            styles=_COMMON_STYLES
            + (("bond", "bpm/spring/plastic"), ("pair", "granular"), ("fix", "bond/create")),
            map_material=_bpm_map,
            deck_variables=_render(_PLASTIC_VARIABLES),
            validate=_bpm_plastic_validate,
            deferred_fragment="bpm_relink.in",
            doc="central elastic-perfectly plastic springs (LAMMPS BPM), nu fixed at 1/3",
        ),
        "bpm/rotational": BondLaw(
            name="bpm/rotational",
            keyword="rotational",
            styles=_COMMON_STYLES
            + (("bond", "bpm/rotational"), ("pair", "granular"), ("fix", "bond/create")),
            map_material=_bpm_map,
            deck_variables=_render(_ROTATIONAL_VARIABLES),
            validate=_bpm_rotational_validate,
            deferred_fragment="bpm_relink.in",
            doc="normal/shear/bending springs (LAMMPS BPM), brittle, nu < 1/3",
        ),
        # movable cellular automata (tribolmp plugin, C++): the pair style, its state fix and
        # per-atom compute come from the plugin the fragment loads (``setup`` builds it), so
        # they are checked by the fragment's ``plugin load``, not before the deck runs
        "mca": BondLaw(
            name="mca",
            keyword="mca",
            # (its integrator, fix nve/mca, comes from the plugin as well)
            styles=(("atom", "bpm/sphere"),),
            map_material=_mca_map,
            deck_variables=_mca_variables,
            validate=_mca_validate,
            setup=_mca_setup,
            coordination_cap=False,
            # pair_style mca's cutoff (1.25 d, links break far below it: rupture strains are
            # < 1 %) plus the skin (0.3 d) is 1.55 d; nothing else needs ghosts (its bonds are
            # deleted after the first force evaluation), so the ghost shell is the neighbour
            # cutoff, rounded up so that LAMMPS does not adjust it
            ghost_cutoff=1.6,
            doc="movable cellular automata: many-body elasticity, von Mises plasticity, "
            "fracture and welding (tribolmp plugin pair_style mca)",
        ),
    }
)

#: The law used when none is named (the scene default).
DEFAULT_LAW = "mca"


def law_names() -> tuple[str, ...]:
    """Names of the registered laws, registry order."""
    return tuple(BOND_LAWS)


def get_law(name: str) -> BondLaw:
    """Return the registered law ``name``; one-line ``ParameterError`` otherwise."""
    try:
        return BOND_LAWS[name]
    except KeyError:
        raise ParameterError("bond_style", f"one of {list(BOND_LAWS)}", name) from None
