"""Scene files: TOML parsed into frozen, validated dataclasses in SI units.

>>> from tribolmp.scene import default_scene
>>> scene = default_scene()
>>> round(scene.material.youngs_modulus / 1e9)
206
"""

from __future__ import annotations

import dataclasses
import math
import sys
from dataclasses import dataclass
from importlib import resources
from pathlib import Path
from typing import Any

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

from ..errors import ParameterError, SceneError
from ..params import build_dataclass
from .schema import (
    SECTIONS,
    Contact,
    CounterMaterial,
    Geometry,
    Kinematics,
    Load,
    Lubricant,
    Material,
    Nanoscale,
    Outputs,
    Polishing,
    Rates,
    Roughness,
    RunningIn,
    SceneMeta,
    Topography,
    Tribospectroscopy,
)

__all__ = [
    "Scene",
    "load_scene",
    "parse_scene",
    "default_scene",
    "builtin_scene",
    "example_scenes",
    "scene_path",
    "BUILTIN_SCENES",
]

#: Sections every scene has (filled with defaults when absent).
ALWAYS = ("scene", "material", "geometry", "load", "kinematics", "contact", "outputs")


@dataclass(frozen=True)
class Scene:
    """A complete, validated scene.

    Optional sections are ``None`` when the file does not have them: their
    absence is meaningful (no ``[lubricant]`` means a dry contact, no
    ``[nanoscale]`` with ``[rates]`` means the rates are given).
    """

    scene: SceneMeta
    material: Material
    geometry: Geometry
    load: Load
    kinematics: Kinematics
    contact: Contact
    outputs: Outputs
    counter_material: CounterMaterial | None = None
    roughness: Roughness | None = None
    lubricant: Lubricant | None = None
    polishing: Polishing | None = None
    nanoscale: Nanoscale | None = None
    topography: Topography | None = None
    tribospectroscopy: Tribospectroscopy | None = None
    rates: Rates | None = None
    running_in: RunningIn | None = None
    source: str = "<default>"

    @property
    def counter(self) -> Material:
        """The counter-body material (``[material]`` when not given separately)."""
        return self.counter_material or self.material

    @property
    def effective_modulus(self) -> float:
        """E* in Pa: 1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2."""
        a, b = self.material, self.counter
        return 1.0 / (
            (1 - a.poisson_ratio**2) / a.youngs_modulus
            + (1 - b.poisson_ratio**2) / b.youngs_modulus
        )

    @property
    def effective_shear_modulus(self) -> float:
        """MDR tangential modulus G* in Pa: 1/G* = (2-nu1)/(4G1) + (2-nu2)/(4G2)."""
        a, b = self.material, self.counter
        return 1.0 / (
            (2 - a.poisson_ratio) / (4 * a.shear_modulus)
            + (2 - b.poisson_ratio) / (4 * b.shear_modulus)
        )

    def to_dict(self) -> dict[str, Any]:
        """Plain dict of all present sections (for hashing and reports)."""
        out: dict[str, Any] = {}
        for name in SECTIONS:
            sec = getattr(self, name)
            if sec is not None:
                # None means "not given" (optional [rates] fields): left
                # out, so the dict stays TOML.
                out[name] = {
                    k: (list(v) if isinstance(v, tuple) else v)
                    for k, v in dataclasses.asdict(sec).items()
                    if v is not None
                }
        return out


def parse_scene(data: dict[str, Any] | str, source: str = "<scene>") -> Scene:
    """Build a :class:`Scene` from a parsed TOML mapping or from TOML text.

    Parameters
    ----------
    data : dict or str
        The TOML document as a dict, or its text (as in a notebook cell).
    source : str
        File name used as message prefix.

    Raises
    ------
    SceneError
        One line naming the file, ``[section].field``, what was expected and what was received.
    """
    if isinstance(data, str):
        try:
            data = tomllib.loads(data)
        except tomllib.TOMLDecodeError as exc:
            raise SceneError("scene", "valid TOML text", str(exc), source) from None
    if not isinstance(data, dict):
        # Name both accepted kinds: a bare "a TOML table" hid that text works too.
        raise SceneError(
            "scene", "a mapping (parsed TOML) or TOML text (str)", type(data).__name__, source
        )
    kwargs: dict[str, Any] = {}
    for key, value in data.items():
        if key not in SECTIONS:
            raise SceneError(
                f"[{key}]",
                f"one of the known sections {sorted(SECTIONS)}",
                "unknown section",
                source,
            )
        try:
            kwargs[key] = build_dataclass(SECTIONS[key], value, prefix=f"[{key}].", source=source)
        except SceneError:
            raise
        except ParameterError as exc:
            raise SceneError(exc.field, exc.expected, exc.got, source) from None
    for key in ALWAYS:
        kwargs.setdefault(key, SECTIONS[key]())
    scene = Scene(**kwargs, source=source)
    _check_consistency(scene)
    return scene


def _check_consistency(scene: Scene) -> None:
    """Cross-section checks: contradictory sections are rejected."""
    src = scene.source
    g = scene.geometry
    if g.profile == "rough" and scene.roughness is None and "stiffness" in scene.outputs.requested:
        raise SceneError(
            "[roughness]", "a [roughness] section for geometry.profile = 'rough'", "nothing", src
        )
    if "lubrication" in scene.outputs.requested and scene.lubricant is None:
        raise SceneError(
            "[lubricant]",
            "a [lubricant] section when outputs request 'lubrication'",
            "nothing",
            src,
        )
    if "polishing" in scene.outputs.requested and (
        scene.lubricant is None or scene.polishing is None
    ):
        missing = "[lubricant]" if scene.lubricant is None else "[polishing]"
        raise SceneError(
            missing, f"a {missing} section when outputs request 'polishing'", "nothing", src
        )
    if scene.nanoscale is not None and scene.rates is not None:
        raise SceneError(
            "[rates]",
            "either [nanoscale] (measure rates) or [rates] (give them), not both",
            "both",
            src,
        )
    if scene.nanoscale is not None:
        nano, mat = scene.nanoscale, scene.material
        # A pressure above the yield strength crushes the automaton lattice before sliding starts.
        if nano.pressure >= mat.yield_strength:
            raise SceneError(
                "[nanoscale].pressure",
                f"a value < [material].yield_strength ({mat.yield_strength:g} Pa)",
                nano.pressure,
                src,
            )
    if scene.roughness is not None and scene.roughness.surface_file:
        path = Path(scene.roughness.surface_file)
        if not path.is_absolute() and scene.source not in ("<default>", "<scene>"):
            path = Path(scene.source).parent / path
        if not path.exists():
            raise SceneError(
                "[roughness].surface_file", "an existing .npy height map", str(path), src
            )
    if not scene.load.pressures:
        # The contact stage's stiffness-vs-load table needs at least one load (found after the
        # LAMMPS stage otherwise).
        raise SceneError("[load].pressures", "at least one nominal pressure in Pa", "[]", src)
    if not math.isfinite(scene.effective_modulus):  # pragma: no cover - guarded by ranges
        raise SceneError("[material].youngs_modulus", "finite moduli", "inf", src)


def load_scene(path: str | Path) -> Scene:
    """Read and validate a TOML scene file.

    Parameters
    ----------
    path : str or Path
        The scene file.

    Raises
    ------
    SceneError
        The file is missing, is not valid TOML, or fails validation.
    """
    path = Path(path)
    name = str(path)
    try:
        raw = path.read_bytes()
    except OSError as exc:
        raise SceneError("file", "a readable TOML file", f"{exc.strerror or exc}", name) from None
    try:
        # utf-8-sig: editors on Windows write a byte-order mark, which TOML itself does not allow.
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError:
        raise SceneError("file", "UTF-8 text", "undecodable bytes", name) from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise SceneError("file", "valid TOML", str(exc), name) from None
    if not data:
        # An empty file (or /dev/null, or a truncated copy) would otherwise run the defaults of
        # every section silently, which is never what the user meant.
        raise SceneError("file", "a scene with at least one [section]", "an empty file", name)
    return parse_scene(data, source=name)


def scene_path(name: str) -> Path:
    """Path of a shipped example scene (``"default"``, ``"lubricated"``, ...)."""
    ref = resources.files("tribolmp") / "data" / "scenes" / f"{name}.toml"
    return Path(str(ref))


def example_scenes() -> list[str]:
    """Names of the shipped example scenes."""
    folder = resources.files("tribolmp") / "data" / "scenes"
    return sorted(p.name[:-5] for p in folder.iterdir() if p.name.endswith(".toml"))


def default_scene() -> Scene:
    """Return the embedded default scene: the seed's steel-steel couple, scaled to run here."""
    return load_scene(scene_path("default"))


#: Scenes commands fall back on when the user gives none and the embedded default lacks the sections
#: the command needs (tables as in a scene file; every other value is the schema default).
BUILTIN_SCENES: dict[str, dict[str, Any]] = {
    # `tribolmp lubrication summary|polish` without a scene: the schema's lubricant and polishing,
    # on a 64-point roughness grid so that a polishing run takes a second.
    "lubrication": {"lubricant": {}, "polishing": {}, "roughness": {"grid_points": 64}},
}


def builtin_scene(name: str) -> Scene:
    """Return a built-in scene of :data:`BUILTIN_SCENES` (source ``<built-in>``)."""
    try:
        data = BUILTIN_SCENES[name]
    except KeyError:
        raise SceneError(
            "scene", f"one of the built-in scenes {sorted(BUILTIN_SCENES)}", name
        ) from None
    return parse_scene({k: dict(v) for k, v in data.items()}, source="<built-in>")

