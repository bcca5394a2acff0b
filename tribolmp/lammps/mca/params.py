"""Parameters of the MCA friction experiment (SI) and the size/time presets.

The fields that the scene's ``[nanoscale]`` and ``[material]`` sections also
declare take their default, bounds and documentation from the scene schema,
so that a scene and ``MCAParams`` cannot disagree on a default.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any

from ...errors import ParameterError
from ...params import param, validate_dataclass
from ...scene.schema import Material, Nanoscale
from ..laws import get_law
from ..mapping import MaterialSpec

__all__ = ["PRESETS", "MCAParams", "params_from_scene", "preset_params"]


def _scene_field(section: type, name: str, **meta: Any) -> Any:
    """Return a dataclass field with the default and metadata of ``section.name``.

    The default can be changed.
    """
    f = {fl.name: fl for fl in dataclasses.fields(section)}[name]
    return dataclasses.field(default=f.default, metadata={**f.metadata, **meta})


@dataclass(frozen=True)
class MCAParams:
    """Parameters of one MCA friction run (SI units).

    Fields shared with the scene's ``[nanoscale]`` and ``[material]`` have the
    scene's defaults; :data:`PRESETS` hold the run sizes (``smoke``,
    ``default``, ``paper``).
    """

    dim: int = _scene_field(Nanoscale, "dim")
    automaton_diameter: float = _scene_field(Nanoscale, "automaton_diameter")
    # the choices are the law registry's, checked in __post_init__ (a
    # registered law needs no other edit)
    bond_style: str = _scene_field(Nanoscale, "bond_style", choices=None)
    sliding_velocity: float = _scene_field(Nanoscale, "sliding_velocity")
    pressure: float = _scene_field(Nanoscale, "pressure")
    duration: float = _scene_field(Nanoscale, "duration")
    box_length: float = _scene_field(Nanoscale, "box_length")
    box_width: float = param(
        10e-9, unit="m", lo=0.0, lo_open=True, hi=1e-5, doc="Periodic width along z (3D)."
    )
    body_height: float = _scene_field(Nanoscale, "body_height")
    roughness_rms: float = _scene_field(Nanoscale, "rms_height")
    hurst: float = param(0.8, lo=0.0, hi=1.0, lo_open=True, doc="Hurst exponent of the surfaces.")
    body_texture: str = param(
        "auto",
        choices=("auto", "aligned", "rotated", "tilted", "polycrystalline"),
        doc="Lattices of the two bodies: tilted (2D: both bodies single crystals with their rows "
        "at about 12 and 19 deg to the sliding direction, meeting 30 deg apart, so neither surface "
        "repeats after d), rotated (2D: the upper body turned by 90 deg, washboard "
        "at V/d 6-30x weaker; 3D: both FCC bodies turned by -+18.43 deg about the normal, "
        "meeting 36.87 deg apart, box in whole sqrt(10) a cells), polycrystalline (2D: both "
        "bodies of randomly oriented grains, no washboard, but weak grain boundaries that "
        "compact under load), aligned (one orientation, "
        "the old commensurate setup), auto (rotated in 2D, aligned in 3D).",
    )
    grain_size: float = param(
        10e-9, unit="m", lo=0.0, lo_open=True, hi=1e-5, doc="Mean grain size (polycrystalline)."
    )
    youngs_modulus: float = _scene_field(Material, "youngs_modulus")
    poisson_ratio: float = _scene_field(Material, "poisson_ratio")
    yield_strength: float = _scene_field(Material, "yield_strength")
    ultimate_strength: float = _scene_field(Material, "ultimate_strength")
    density: float = _scene_field(Material, "density")
    failure_strain: float = param(
        0.05, lo=0.0, hi=0.5, lo_open=True, doc="Link rupture strain (uniaxial)."
    )
    damping_ratio: float = param(
        0.1, lo=0.0, hi=1.0, doc="Link/contact damping, fraction of critical."
    )
    contact_friction: float = param(0.5, lo=0.0, hi=10.0, doc="Coulomb cap of contact viscosity.")
    # F = eta A / d v_rel (mca law); calibration in docs/mca_study.md; a large viscosity needs a
    # smaller dt_factor (the explicit viscous damping limit, checked below)
    contact_viscosity: float = _scene_field(Nanoscale, "contact_viscosity")
    dt_factor: float = _scene_field(Nanoscale, "dt_factor")
    ramp_time: float = param(0.1e-9, unit="s", lo=0.0, hi=1e-6, doc="Velocity ramp 0 -> V.")
    approach_velocity: float = param(
        5.0,
        unit="m/s",
        lo=0.0,
        lo_open=True,
        hi=100.0,
        doc="Dashpot speed of the slider under F_N.",
    )
    rebond_factor: float = param(1.0, lo=0.0, hi=1.0, doc="Strength of re-formed links / original.")
    rebond_strain: float = param(
        0.01, lo=0.0, hi=0.2, doc="Extra compression below contact for re-linking."
    )
    rebond_interval: float = param(
        5e-12, unit="s", lo=0.0, lo_open=True, hi=1e-6, doc="Re-linking check interval."
    )
    sink_depth: float = param(
        0.0,
        unit="m",
        lo=0.0,
        hi=1e-5,
        doc="Thickness of the heat-sink layers next to base and slider (0: none).",
    )
    sink_tau: float = param(
        10e-12, unit="s", lo=0.0, lo_open=True, hi=1e-6, doc="Heat-sink time constant."
    )
    dump_interval: float = param(
        50e-12, unit="s", lo=0.0, lo_open=True, hi=1e-3, doc="Trajectory interval."
    )
    print_interval: float = param(
        5e-12, unit="s", lo=0.0, lo_open=True, hi=1e-3, doc="friction.csv interval."
    )
    restart_interval: float = param(
        0.25e-9, unit="s", lo=0.0, lo_open=True, hi=1e-3, doc="Restart file interval."
    )
    preset: str = param(
        "custom",
        choices=("smoke", "default", "paper", "custom"),
        doc="Name of the size/time preset these parameters came from (custom: none).",
    )

    def __post_init__(self) -> None:
        validate_dataclass(self)
        get_law(self.bond_style)  # one line naming the registered laws otherwise
        d = self.automaton_diameter
        if self.box_length < 8 * d:
            raise ParameterError(
                "box_length", f"a value >= 8 automaton diameters ({8 * d:g} m)", self.box_length
            )
        if self.body_height < 4 * d:
            raise ParameterError(
                "body_height", f"a value >= 4 automaton diameters ({4 * d:g} m)", self.body_height
            )
        if self.dim == 3 and self.box_width < 2.9 * d:
            raise ParameterError(
                "box_width", f"a value >= 2 FCC cells ({2.9 * d:g} m)", self.box_width
            )
        if self.roughness_rms > self.body_height / 4:
            raise ParameterError(
                "roughness_rms",
                f"a value <= body_height/4 ({self.body_height / 4:g} m)",
                self.roughness_rms,
            )
        if self.body_texture in ("tilted", "polycrystalline") and self.dim == 3:
            raise ParameterError(
                "body_texture",
                "aligned, rotated or auto in 3D (tilted and polycrystalline are 2D only)",
                self.body_texture,
            )
        if self.texture == "polycrystalline" and not (3 * d <= self.grain_size <= self.box_length):
            raise ParameterError(
                "grain_size",
                "a value in [3 automaton diameters, box_length] "
                f"([{3 * d:g}, {self.box_length:g}] m)",
                self.grain_size,
            )
        spec = self.material()  # validates the material and the law's own limits
        coeff = get_law(self.bond_style).map_material(spec)
        if self.dt_factor > 0.5 * coeff.dt_max_factor:
            # half the Verlet limit of the lattice: contacts and damping need margin
            raise ParameterError(
                "dt_factor",
                f"a value <= {0.5 * coeff.dt_max_factor:.3g} "
                "(half the Verlet stability limit of the lattice with its contact viscosity)",
                self.dt_factor,
            )
        if self.pressure >= coeff.flow_stress:
            raise ParameterError(
                "pressure",
                "a value below the lattice's flow stress "
                f"{coeff.flow_stress:g} Pa (it would crush the lattice)",
                self.pressure,
            )
        if self.duration < self.ramp_time:
            raise ParameterError(
                "duration", f"a value >= ramp_time ({self.ramp_time:g} s)", self.duration
            )

    @property
    def texture(self) -> str:
        """The body texture actually built (``auto`` resolved)."""
        if self.body_texture == "auto":
            return "rotated" if self.dim == 2 else "aligned"
        return self.body_texture

    def material(self) -> MaterialSpec:
        """Return the :class:`MaterialSpec` of the bodies."""
        return MaterialSpec(
            youngs_modulus=self.youngs_modulus,
            poisson_ratio=self.poisson_ratio,
            yield_strength=self.yield_strength,
            ultimate_strength=self.ultimate_strength,
            diameter=self.automaton_diameter,
            density=self.density,
            dim=self.dim,
            bond_style=self.bond_style,
            failure_strain=self.failure_strain,
            damping_ratio=self.damping_ratio,
            contact_friction=self.contact_friction,
            contact_viscosity=self.contact_viscosity,
        )

    def replace(self, **changes: Any) -> MCAParams:
        """Return a copy with some fields changed (validated again)."""
        return dataclasses.replace(self, **changes)


#: Size/time presets.  ``smoke``: < 1 min for CI.  ``default``: the issue's
#: feasibility size (200 x ~100 nm, d = 2.5 nm, ~3.6k automata) for 20 ns.
#: ``paper``: the same size for 100 ns (the seed's time to dynamic equilibrium).
PRESETS: dict[str, dict[str, Any]] = {
    "smoke": dict(
        box_length=50e-9,
        body_height=15e-9,
        duration=1e-9,
        roughness_rms=1.5e-9,
        restart_interval=0.25e-9,
    ),
    "default": dict(
        box_length=200e-9,
        body_height=45e-9,
        duration=20e-9,
        roughness_rms=2e-9,
        box_width=10e-9,
        dump_interval=0.2e-9,
        print_interval=10e-12,
        restart_interval=2e-9,
        sink_depth=5e-9,
    ),
    "paper": dict(
        box_length=200e-9,
        body_height=45e-9,
        duration=100e-9,
        roughness_rms=2e-9,
        box_width=10e-9,
        dump_interval=0.5e-9,
        print_interval=20e-12,
        restart_interval=5e-9,
        sink_depth=5e-9,
    ),
}


def preset_params(name: str = "smoke", **changes: Any) -> MCAParams:
    """Parameters of a named preset, with optional changes."""
    if name not in PRESETS:
        raise ParameterError("preset", f"one of {sorted(PRESETS)}", name)
    return MCAParams(**{**PRESETS[name], "preset": name, **changes})


def params_from_scene(scene) -> MCAParams:
    """Read ``[nanoscale]`` and ``[material]`` of a :class:`tribolmp.scene.Scene`.

    The scene's size fields win over its preset's; the preset supplies the
    output and restart intervals and the heat sinks.
    """
    nano = scene.nanoscale
    if nano is None:
        raise ParameterError("[nanoscale]", "a [nanoscale] section in the scene", None)
    mat = scene.material
    # Old names of renamed scene fields (e.g. roughness_rms, now [nanoscale].rms_height) still read.
    scene_names = {f.name for f in dataclasses.fields(Nanoscale)} | set(
        getattr(Nanoscale, "__field_aliases__", {})
    )
    shared = scene_names & {f.name for f in dataclasses.fields(MCAParams)}
    shared.discard("preset")
    return preset_params(
        nano.preset,
        **{name: getattr(nano, name) for name in sorted(shared)},
        youngs_modulus=mat.youngs_modulus,
        poisson_ratio=mat.poisson_ratio,
        yield_strength=mat.yield_strength,
        ultimate_strength=mat.ultimate_strength,
        density=mat.density,
    )
