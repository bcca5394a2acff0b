"""Scene schema: one frozen, validated dataclass per TOML section, all in SI.

A scene file is TOML.  Each top-level table maps to one section class below;
unknown tables or keys, wrong types, NaN/inf and out-of-range values are
rejected with a one-line message ``file: [section].field: expected ..., got ...``.

Model issues add fields to *their own* section; keep names stable, because
scene files in the wild use them.
"""

from __future__ import annotations

import dataclasses
import typing
from dataclasses import dataclass

from ..errors import ParameterError
from ..params import param, renamed, validate_dataclass
from ..records import RATES_GROUPS
from ..records import Rates as RatesRecord

__all__ = [
    "Section",
    "SceneMeta",
    "Material",
    "Geometry",
    "Roughness",
    "Load",
    "Kinematics",
    "Lubricant",
    "Polishing",
    "Nanoscale",
    "Topography",
    "Contact",
    "Tribospectroscopy",
    "Rates",
    "RunningIn",
    "Outputs",
    "OUTPUT_CHOICES",
    "SECTIONS",
]


@dataclass(frozen=True)
class Section:
    """Base class: validates all fields on construction (subclasses set ``_name``)."""

    _name = ""

    def __post_init__(self) -> None:
        validate_dataclass(self, prefix=f"[{self._name}].")
        self._check()

    def _check(self) -> None:
        """Cross-field checks; override in subclasses."""

    def _fail(self, field: str, expected: str, got: object) -> None:
        raise ParameterError(f"[{self._name}].{field}", expected, got)


@dataclass(frozen=True)
class SceneMeta(Section):
    """``[scene]``: identification and the master seed."""

    _name = "scene"
    name: str = param("scene", doc="Short name used in reports.")
    description: str = param("", doc="Free text.")
    seed: int = param(20060327, lo=0, hi=2**63 - 1, doc="Master seed of every random stream.")


@dataclass(frozen=True)
class Material(Section):
    """``[material]`` (body) and ``[counter_material]`` (counter-body): isotropic solid."""

    _name = "material"
    youngs_modulus: float = param(
        206e9, unit="Pa", lo=0.0, lo_open=True, hi=2e12, doc="Young's modulus E."
    )
    poisson_ratio: float = param(
        0.3, lo=-1.0, hi=0.5, lo_open=True, hi_open=True, doc="Poisson's ratio nu."
    )
    density: float = param(7800.0, unit="kg/m^3", lo=0.0, lo_open=True, hi=1e5, doc="Mass density.")
    yield_strength: float = param(
        480e6, unit="Pa", lo=0.0, lo_open=True, hi=1e11, doc="Yield strength."
    )
    ultimate_strength: float = param(
        552e6, unit="Pa", lo=0.0, lo_open=True, hi=1e11, doc="Ultimate (tensile) strength."
    )

    def _check(self) -> None:
        if self.ultimate_strength < self.yield_strength:
            self._fail(
                "ultimate_strength",
                f"a value >= yield_strength ({self.yield_strength:g} Pa)",
                self.ultimate_strength,
            )
        if self.yield_strength >= self.youngs_modulus:
            self._fail(
                "yield_strength",
                f"a value < youngs_modulus ({self.youngs_modulus:g} Pa)",
                self.yield_strength,
            )

    @property
    def shear_modulus(self) -> float:
        """Shear modulus G = E / (2 (1 + nu)) in Pa."""
        return self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))


@dataclass(frozen=True)
class CounterMaterial(Material):
    """``[counter_material]``: the counter-body; defaults to ``[material]`` when absent."""

    _name = "counter_material"


@dataclass(frozen=True)
class Geometry(Section):
    """``[geometry]``: macroscopic shape of the contact."""

    _name = "geometry"
    profile: str = param(
        "sphere", choices=("sphere", "cone", "flat", "rough"), doc="Indenter profile."
    )
    radius: float = param(
        5e-3, unit="m", lo=0.0, lo_open=True, hi=10.0, doc="Sphere radius / punch radius."
    )
    half_angle_deg: float = param(
        80.0,
        unit="deg",
        lo=0.0,
        hi=90.0,
        lo_open=True,
        hi_open=True,
        doc="Cone half-angle from its axis.",
    )
    apparent_length: float = param(
        1e-3, unit="m", lo=0.0, lo_open=True, hi=10.0, doc="Side of the nominal contact."
    )
    apparent_width: float = param(
        1e-3, unit="m", lo=0.0, lo_open=True, hi=10.0, doc="Width of the nominal contact."
    )


@dataclass(frozen=True)
class Roughness(Section):
    """``[roughness]``: self-affine random surface (or a measured height map)."""

    _name = "roughness"
    rms_height: float = param(
        0.5e-6, unit="m", lo=0.0, lo_open=True, hi=1e-2, doc="Rq of the surface."
    )
    hurst: float = param(0.8, lo=0.0, hi=1.0, lo_open=True, doc="Hurst exponent H.")
    rolloff_wavelength: float = param(
        100e-6, unit="m", lo=0.0, lo_open=True, hi=10.0, doc="Roll-off wavelength."
    )
    short_cutoff_wavelength: float = param(
        4e-6, unit="m", lo=0.0, lo_open=True, hi=10.0, doc="Short-wavelength cut-off."
    )
    grid_points: int = param(256, lo=8, hi=1 << 24, doc="Points per side of generated height maps.")
    pixel_size: float = param(
        2e-6, unit="m", lo=0.0, lo_open=True, hi=1.0, doc="Grid spacing of generated height maps."
    )
    surface_file: str = param(
        "",
        doc="Optional measured height map: tribolmp .npy/.asc/.xyz or any SurfaceTopography "
            "format (x3p, sur, opd, datx, gwy, plu, nc, ...); empty = generate.",
    )
    realizations: int = param(16, lo=1, hi=100_000, doc="Ensemble size for 1D MDR profiles.")
    # Measured surfaces (issue 16): units and pixel size come from the file;
    # these override only when given.
    surface_unit: str = param(
        "",
        choices=("", "m", "mm", "um", "µm", "nm", "A", "Å", "pm"),
        doc="Length unit of a surface_file that states none "
            "(or overriding the file's); empty = from the file.",
    )
    surface_pixel_size: float = param(
        0.0,
        unit="m",
        lo=0.0,
        hi=1.0,
        doc="Pixel size overriding surface_file's metadata; 0 = from "
            "the file ([roughness].pixel_size for files without one).",
    )
    surface_detrend: str = param(
        "none",
        choices=("none", "mean", "plane", "curvature"),
        doc="Detrending of surface_file before use.",
    )
    surface_missing: str = param(
        "refuse",
        choices=("refuse", "fill"),
        doc="Missing points of surface_file: refuse the "
            "file or fill them (harmonic interpolation).",
    )

    def _check(self) -> None:
        if self.short_cutoff_wavelength > self.rolloff_wavelength:
            self._fail(
                "short_cutoff_wavelength",
                f"a value <= rolloff_wavelength ({self.rolloff_wavelength:g} m)",
                self.short_cutoff_wavelength,
            )
        if self.short_cutoff_wavelength < 2 * self.pixel_size:
            self._fail(
                "short_cutoff_wavelength",
                f"a value >= 2 pixel_size ({2 * self.pixel_size:g} m, Nyquist)",
                self.short_cutoff_wavelength,
            )


@dataclass(frozen=True)
class Load(Section):
    """``[load]``: normal load and friction law."""

    _name = "load"
    normal_force: float = param(10.0, unit="N", lo=0.0, hi=1e9, doc="Normal force on the body.")
    pressures: tuple[float, ...] = param(
        (1e5, 1e6, 1e7, 1e8),
        unit="Pa",
        lo=0.0,
        lo_open=True,
        hi=1e11,
        doc="Nominal pressures for stiffness-vs-load curves.",
    )
    friction_coefficient: float = param(
        0.3, lo=0.0, hi=10.0, doc="Coulomb coefficient when not measured."
    )


@dataclass(frozen=True)
class Kinematics(Section):
    """``[kinematics]``: macroscopic driving."""

    _name = "kinematics"
    sliding_velocity: float = param(0.01, unit="m/s", lo=0.0, hi=1e3, doc="Drive velocity.")
    drive_stiffness: float = param(
        1e6, unit="N/m", lo=0.0, lo_open=True, hi=1e15, doc="Stiffness of the pulling spring."
    )
    mass: float = param(0.1, unit="kg", lo=0.0, lo_open=True, hi=1e6, doc="Mass of the rigid body.")
    duration: float = param(0.05, unit="s", lo=0.0, lo_open=True, hi=1e6, doc="Simulated time.")


@dataclass(frozen=True)
class Lubricant(Section):
    """``[lubricant]``: the fluid between the surfaces (absent = dry)."""

    _name = "lubricant"
    viscosity: float = param(
        0.1, unit="Pa s", lo=0.0, lo_open=True, hi=1e6, doc="Newtonian viscosity eta."
    )
    power_law_index: float = param(
        1.0, lo=1.0 / 3.0, lo_open=True, hi=3.0, doc="Power-law index n (>1/3)."
    )
    consistency: float = param(
        0.1, unit="Pa s^n", lo=0.0, lo_open=True, hi=1e6, doc="Power-law consistency K."
    )
    film_thickness: float = param(
        1e-6, unit="m", lo=0.0, lo_open=True, hi=1.0, doc="Initial film thickness h0."
    )


@renamed(velocity="sliding_velocity")  # the old key keeps working (docs/conventions.md)
@dataclass(frozen=True)
class Polishing(Section):
    """``[polishing]``: lubricated polishing with abrasive particles."""

    _name = "polishing"
    particle_radius: float = param(
        1e-6, unit="m", lo=0.0, lo_open=True, hi=1e-2, doc="Abrasive particle radius."
    )
    particle_fraction: float = param(
        0.05, lo=0.0, hi=0.6, lo_open=True, doc="Areal fraction of particles."
    )
    archard_coefficient: float = param(
        1e-13,
        unit="1/Pa",
        lo=0.0,
        lo_open=True,
        hi=1e-3,
        doc="Removal coefficient k in dh/dt = k p v.",
    )
    pressure: float = param(
        1e5, unit="Pa", lo=0.0, lo_open=True, hi=1e10, doc="Nominal polishing pressure."
    )
    sliding_velocity: float = param(
        0.5, unit="m/s", lo=0.0, lo_open=True, hi=1e3, doc="Relative sliding velocity."
    )
    duration: float = param(60.0, unit="s", lo=0.0, lo_open=True, hi=1e7, doc="Polishing time.")


@renamed(roughness_rms="rms_height")  # the old key keeps working (docs/conventions.md)
@dataclass(frozen=True)
class Nanoscale(Section):
    """``[nanoscale]``: the MCA friction experiment on LAMMPS."""

    _name = "nanoscale"
    automaton_diameter: float = param(
        2.5e-9, unit="m", lo=0.5e-9, hi=50e-9, doc="Automaton size d (0.5-50 nm)."
    )
    dim: int = param(2, choices=(2, 3), doc="Spatial dimension of the MCA run.")
    bond_style: str = param(
        "mca",
        choices=("bpm/spring/plastic", "bpm/rotational", "mca"),
        doc="MCA interaction law (tribolmp.lammps.laws).",
    )
    sliding_velocity: float = param(
        5.0, unit="m/s", lo=0.0, lo_open=True, hi=100.0, doc="Velocity of the rigid top layer."
    )
    pressure: float = param(
        150e6, unit="Pa", lo=0.0, lo_open=True, hi=2e9, doc="Normal pressure on the top layer."
    )
    duration: float = param(2e-9, unit="s", lo=0.0, lo_open=True, hi=1e-5, doc="Simulated time.")
    box_length: float = param(
        100e-9, unit="m", lo=0.0, lo_open=True, hi=1e-5, doc="Periodic length along sliding."
    )
    body_height: float = param(
        25e-9, unit="m", lo=0.0, lo_open=True, hi=1e-5, doc="Height of each deformable body."
    )
    rms_height: float = param(
        2e-9,
        unit="m",
        lo=0.0,
        hi=1e-6,
        doc="Initial interface roughness Rq (old key roughness_rms).",
    )
    contact_viscosity: float = param(
        0.05,
        unit="Pa s",
        lo=0.0,
        hi=1e3,
        doc="Viscosity of the dissipative force between touching, unlinked automata (mca law); "
        "the seed's fitting parameter for the layer depth.",
    )
    dt_factor: float = param(
        0.1,
        lo=0.0,
        lo_open=True,
        hi=10.0,
        doc="Timestep / sqrt(m/k); at most half the Verlet limit of the lattice with its "
        "contact viscosity (a large viscosity needs a smaller one).",
    )
    preset: str = param("smoke", choices=("smoke", "default", "paper"), doc="Size/time preset.")
    ranks: int = param(1, lo=1, hi=1024, doc="MPI ranks (mpiexec -n).")

    def _check(self) -> None:
        if self.box_length < 8 * self.automaton_diameter:
            self._fail(
                "box_length",
                f"a value >= 8 automaton diameters ({8 * self.automaton_diameter:g} m)",
                self.box_length,
            )
        if self.body_height < 4 * self.automaton_diameter:
            self._fail(
                "body_height",
                f"a value >= 4 automaton diameters ({4 * self.automaton_diameter:g} m)",
                self.body_height,
            )


@dataclass(frozen=True)
class Topography(Section):
    """``[topography]``: the stochastic surface equation (Eq. 23)."""

    _name = "topography"
    d0: float = param(1e-12, unit="m^2/s", lo=0.0, hi=1e3, doc="Surface diffusion coefficient D0.")
    # Defaults (used when no rates are given) suit the default 2D grid of 256 x 2.5 nm: k1 = 3.0e7,
    # k2 = 3.0e8 1/m, high plateau l^4 (one automaton), Rq ~ 3 nm.
    dx_noise: float = param(
        6.25e-30,
        unit="m^4/s",
        lo=0.0,
        hi=1e3,
        doc="Conserved-noise intensity Dx (2D: m^4/s, 1D: m^3/s).",
    )
    dz: float = param(
        3.5e-30,
        unit="m^4/s",
        lo=0.0,
        hi=1e3,
        doc="Deposition/detachment noise intensity Dz (2D: m^4/s, 1D: m^3/s).",
    )
    mu: float = param(900.0, unit="1/s", lo=0.0, hi=1e9, doc="Wear rate constant mu.")
    l: float = param(  # noqa: E741 (scene key: the paper's l)
        2.5e-9, unit="m", lo=0.0, lo_open=True, hi=1.0, doc="Step length l of the stochastic flux."
    )
    correlation_length: float = param(
        0.0, unit="m", lo=0.0, hi=1.0, doc="Noise correlation length l_c (0 = delta)."
    )
    dim: int = param(1, choices=(1, 2), doc="1D profile or 2D surface.")
    grid_points: int = param(1024, lo=4, hi=1 << 22, doc="Grid points per side.")
    pixel_size: float = param(10e-9, unit="m", lo=0.0, lo_open=True, hi=1.0, doc="Grid spacing.")
    duration: float = param(1e4, unit="s", lo=0.0, lo_open=True, hi=1e12, doc="Evolution time.")
    steps: int = param(200, lo=1, hi=10**9, doc="Number of exact-OU steps.")
    scheme: str = param("exact", choices=("exact", "euler"), doc="Integrator.")

    def _check(self) -> None:
        # The real-FFT solver needs an even grid (real k = 0 and Nyquist modes).
        if self.grid_points % 2:
            self._fail("grid_points", "an even number of grid points >= 4", self.grid_points)


@dataclass(frozen=True)
class Contact(Section):
    """``[contact]``: contact-mechanics solver choice."""

    _name = "contact"
    method: str = param(
        "auto", choices=("auto", "mdr", "bem"), doc="Solver; auto picks from measured speed/error."
    )
    springs: int = param(2000, lo=3, hi=10**7, doc="MDR springs per profile.")
    tolerance: float = param(
        0.3, lo=0.0, lo_open=True, hi=10.0, doc="Acceptable relative error of stiffness."
    )
    periodic: bool = param(True, doc="BEM: periodic surface (True) or rigid square punch (False).")


@dataclass(frozen=True)
class Tribospectroscopy(Section):
    """``[tribospectroscopy]``: oscillating probe with two contacts."""

    _name = "tribospectroscopy"
    frequency: float = param(
        65e3, unit="Hz", lo=0.0, lo_open=True, hi=1e8, doc="Oscillation frequency."
    )
    amplitudes: tuple[float, ...] = param(
        tuple(i * 1e-8 for i in range(0, 51)),
        unit="m",
        lo=0.0,
        hi=1e-3,
        doc="Per-contact amplitudes.",
    )
    model: str = param("potential", choices=("stiffness", "potential"), doc="Friction model.")
    convention: str = param(
        "per-contact",
        choices=("per-contact", "probe"),
        doc="Amplitude convention: per contact (dl/4) or probe (dl/2).",
    )
    correlation_length: float = param(
        50e-9, unit="m", lo=0.0, lo_open=True, hi=1e-3, doc="Pinning correlation length lambda."
    )


#: Defaults of the ``[rates]`` keys that scene files have always had (the record itself defaults to
#: None = "not given"); a scene that gives only some of them keeps running as before.
RATES_SCENE_DEFAULTS = {
    "mu": 0.3,
    "diffusion_m2_s": 1e-12,
    "transfer_rate": 1e-3,
    "wear_rate": 1e-3,
    "layer_depth_m": 6.5e-9,
    "step_length_m": 2.5e-9,
    "step_time_s": 1e-9,
}


def _rates_section() -> type[Section]:
    """``[rates]``: the fields of :class:`tribolmp.records.Rates`, except its provenance group.

    Declared from the record so that the scene, the analysis, the chain and the
    topography model share one definition (name, unit, range, doc) of every rate.
    """
    provenance = set(RATES_GROUPS["provenance"])
    hints = typing.get_type_hints(RatesRecord)
    specs = []
    for f in dataclasses.fields(RatesRecord):
        if f.name in provenance:
            continue
        default = RATES_SCENE_DEFAULTS.get(f.name, f.default)
        specs.append(
            (f.name, hints[f.name], dataclasses.field(default=default, metadata=f.metadata))
        )

    def to_record(self, source: str = "[rates]") -> RatesRecord:
        """Return the shared :class:`~tribolmp.records.Rates` record of this section."""
        return RatesRecord(**{name: getattr(self, name) for name, _t, _f in specs}, source=source)

    return dataclasses.make_dataclass(
        "Rates",
        specs,
        bases=(Section,),
        frozen=True,
        namespace={
            "_name": "rates",
            "__doc__": "``[rates]``: nanoscale rates given directly (skips LAMMPS); fields of "
            ":class:`tribolmp.records.Rates`.",
            "__module__": __name__,
            "to_record": to_record,
        },
    )


Rates = _rates_section()


@dataclass(frozen=True)
class RunningIn(Section):
    """``[running_in]``: the coupled running-in of the part's surface (issue 15; owner runin)."""

    _name = "running_in"
    checkpoints: int = param(8, lo=1, hi=10_000, doc="Contact solves over the sliding duration.")
    phi_tolerance: float = param(
        0.05,
        lo=0.0,
        lo_open=True,
        hi=1e9,
        doc="Largest relative change of phi per Eq. 23 sub-step.",
    )
    friction_pressure: str = param(
        "nominal",
        choices=("nominal", "real"),
        doc="Part pressure matched to the MCA: nominal N/A0 or mean real p/phi.",
    )
    mu_static: float | None = param(
        None,
        lo=0.0,
        hi=10.0,
        doc="Static friction coefficient (stated; default static_ratio * mu_k).",
    )
    mu_kinetic: float | None = param(
        None, lo=0.0, hi=10.0, doc="Kinetic friction coefficient (stated; default the MCA's)."
    )
    static_ratio: float = param(
        1.0, lo=1.0, hi=10.0, doc="mu_s / mu_k when mu_static is not given (stated assumption)."
    )
    tribospec_length: str = param(
        "correlation",
        choices=("correlation", "layer_depth"),
        doc="Length scale handed to tribospectroscopy.",
    )
    measurement_noise: float = param(
        0.05, lo=0.0, hi=1.0, doc="Relative noise of the simulated F^2(a) measurement."
    )
    convergence_check: bool = param(
        True, doc="Rerun with half the checkpoint spacing and report the change."
    )


OUTPUT_CHOICES = (
    "friction",
    "mca_snapshot",
    "rates",
    "topography",
    "stiffness",
    "lubrication",
    "polishing",
    "stick_slip",
    "tribospectroscopy",
)


@dataclass(frozen=True)
class Outputs(Section):
    """``[outputs]``: what the run should produce (the planner reads this)."""

    _name = "outputs"
    requested: tuple[str, ...] = param(
        ("friction", "topography", "stiffness", "tribospectroscopy"),
        choices=OUTPUT_CHOICES,
        doc="Requested results.",
    )
    figures: bool = param(True, doc="Write PNG figures.")


#: TOML table name -> section class.
SECTIONS: dict[str, type[Section]] = {
    "scene": SceneMeta,
    "material": Material,
    "counter_material": CounterMaterial,
    "geometry": Geometry,
    "roughness": Roughness,
    "load": Load,
    "kinematics": Kinematics,
    "lubricant": Lubricant,
    "polishing": Polishing,
    "nanoscale": Nanoscale,
    "topography": Topography,
    "contact": Contact,
    "tribospectroscopy": Tribospectroscopy,
    "rates": Rates,
    "running_in": RunningIn,
    "outputs": Outputs,
}

