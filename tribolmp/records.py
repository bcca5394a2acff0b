"""Typed hand-off records shared across the layers (foundation module).

:class:`Rates` is the one record of the nanoscale rates.  The analysis
builds it from an MCA run (``rates.json``, CONTRACTS.md C1), the scene's
``[rates]`` section is declared from its fields (same names, units, ranges),
the chain hands it from stage to stage, and the topography model maps it to
the coefficients of Eq. 23.  Every field is optional: ``None`` means "not
measured / not given", never zero.

Field groups (SI units; the unit of every field is in :meth:`Rates.units`):

friction
    ``mu`` (the friction coefficient, 1) with ``mu_err``; ``mu_static`` and
    ``mu_kinetic`` when a static/kinetic pair is known.
Eq. 23 coefficients of the 1D surface profile (CONTRACTS.md C1)
    ``gamma(k) = mu_per_s + d0_m2_s k^2`` and
    ``S(k) gamma(k) = dz + dx_l2 k^2``: ``mu_per_s`` (1/s), ``d0_m2_s``
    (m^2/s), ``dz`` (m^3/s), ``dx_l2`` (m^5/s), each with ``*_err``.
    The conversion to a 2D surface (per area) is the chain's, not the record's.
microscopic rates (what the MCA analysis measures directly)
    ``diffusion_m2_s``, ``transfer_rate`` (1/m), ``wear_rate``,
    ``detachment_rate``, ``reattachment_rate`` (1/s), ``layer_depth_m``,
    ``step_length_m`` (m), ``step_time_s`` (s).
conditions (where the rates were measured)
    ``pressure_Pa``, ``sliding_velocity_m_s``, ``law`` (bond law),
    ``dim`` (dimension of the MCA run), ``automaton_diameter_m``,
    ``slab_thickness_m`` (of the 2D MCA slab, for the per-area conversion).
provenance
    ``source`` (one line: which file, stage or scene section), ``flagged``
    (fields the producer marked not valid, C1 ``valid: false``),
    ``modes_used`` (C1), ``warnings``.

>>> r = Rates.from_mapping({"mu": 0.2, "velocity_m_s": 5.0, "valid": {"dz": False}}, source="test")
>>> r.mu, r.sliding_velocity_m_s, r.flagged
(0.2, 5.0, ('dz',))
>>> Rates.units()["dx_l2"]
'm^5/s'
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from .errors import ParameterError
from .params import param, validate_dataclass

__all__ = ["Rates", "RATES_GROUPS", "RATES_ALIASES"]


@dataclass(frozen=True)
class Rates:
    """The nanoscale rates handed from the MCA (or a scene, or a table) to the continuum models.

    See the module docstring for the field groups.  Construct with keywords,
    or from a ``rates.json``-like mapping with :meth:`from_mapping`.
    """

    # -- friction
    mu: float | None = param(
        None, unit="1", lo=0.0, hi=10.0, doc="Friction coefficient (F_t / F_n)."
    )
    mu_err: float | None = param(None, unit="1", lo=0.0, doc="Standard error of mu.")
    mu_static: float | None = param(
        None, unit="1", lo=0.0, hi=10.0, doc="Static friction coefficient, when known."
    )
    mu_kinetic: float | None = param(
        None, unit="1", lo=0.0, hi=10.0, doc="Kinetic friction coefficient, when known."
    )
    # -- Eq. 23 coefficients, 1D profile (CONTRACTS.md C1)
    mu_per_s: float | None = param(
        None, unit="1/s", lo=0.0, doc="Eq. 23 wear (relaxation) rate mu of gamma(k) = mu + D0 k^2."
    )
    mu_per_s_err: float | None = param(None, unit="1/s", lo=0.0, doc="Standard error of mu_per_s.")
    d0_m2_s: float | None = param(None, unit="m^2/s", lo=0.0, doc="Eq. 23 surface diffusion D0.")
    d0_m2_s_err: float | None = param(None, unit="m^2/s", lo=0.0, doc="Standard error of d0_m2_s.")
    dz: float | None = param(
        None, unit="m^3/s", lo=0.0, doc="Eq. 23 non-conserved noise Dz of the 1D profile."
    )
    dz_err: float | None = param(None, unit="m^3/s", lo=0.0, doc="Standard error of dz.")
    dx_l2: float | None = param(
        None, unit="m^5/s", lo=0.0, doc="Eq. 23 conserved noise Dx l^2 of the 1D profile."
    )
    dx_l2_err: float | None = param(None, unit="m^5/s", lo=0.0, doc="Standard error of dx_l2.")
    # -- microscopic rates (ranges as the [rates] scene section has always had)
    diffusion_m2_s: float | None = param(
        None,
        unit="m^2/s",
        lo=0.0,
        hi=1e3,
        doc="Lateral diffusion coefficient D of surface automata.",
    )
    transfer_rate: float | None = param(
        None,
        unit="1/m",
        lo=0.0,
        hi=1e12,
        doc="Transferred fraction of surface automata per sliding distance.",
    )
    wear_rate: float | None = param(
        None, unit="1/s", lo=0.0, hi=1e12, doc="transfer_rate times the MCA sliding velocity."
    )
    detachment_rate: float | None = param(
        None,
        unit="1/s",
        lo=0.0,
        doc="Automata leaving their body, per surface automaton per second.",
    )
    reattachment_rate: float | None = param(
        None, unit="1/s", lo=0.0, doc="Automata joining a body, per layer automaton per second."
    )
    layer_depth_m: float | None = param(
        None, unit="m", lo=0.0, hi=1e-3, doc="Quasi-liquid (sheared) layer depth."
    )
    step_length_m: float | None = param(
        None, unit="m", lo=0.0, lo_open=True, hi=1e-3, doc="Elementary step length l."
    )
    step_time_s: float | None = param(
        None, unit="s", lo=0.0, lo_open=True, hi=1e6, doc="Elementary step time tau."
    )
    # -- conditions of the measurement
    pressure_Pa: float | None = param(
        None, unit="Pa", lo=0.0, doc="Normal pressure of the MCA run."
    )
    sliding_velocity_m_s: float | None = param(
        None, unit="m/s", lo=0.0, doc="Sliding velocity of the MCA run."
    )
    law: str | None = param(None, doc="Bond law of the MCA run.")
    dim: int | None = param(None, choices=(1, 2, 3), doc="Spatial dimension of the MCA run.")
    automaton_diameter_m: float | None = param(
        None, unit="m", lo=0.0, lo_open=True, doc="Automaton diameter d."
    )
    slab_thickness_m: float | None = param(
        None,
        unit="m",
        lo=0.0,
        lo_open=True,
        doc="Thickness of the 2D MCA slab (1D-to-surface conversion); None = the chain's default.",
    )
    # -- provenance
    source: str = param(
        "", doc="Where the values come from (file, stage or scene section), one line."
    )
    flagged: tuple[str, ...] = param(
        (), doc="Fields their producer marked not valid (C1 valid: false)."
    )
    modes_used: tuple[int, ...] | None = param(
        None, doc="Wavenumber modes used by the Eq. 23 fit (C1)."
    )
    warnings: tuple[str, ...] = param((), doc="Producer's warnings, one line each.")

    def __post_init__(self) -> None:
        validate_dataclass(self, prefix="rates.")
        bad = [f for f in self.flagged if f not in _FIELD_NAMES]
        if bad:
            raise ParameterError(
                "rates.flagged", f"names of Rates fields {sorted(_FIELD_NAMES)}", bad
            )

    # ---------------------------------------------------------------- build

    @classmethod
    def from_mapping(cls, data: Mapping[str, Any], *, source: str | None = None) -> Rates:
        """Build the record from a ``rates.json``-like mapping.

        Unknown keys (diagnostics, ``units``, ``provenance``) are ignored; a
        ``conditions`` sub-table is flattened; the aliases in
        :data:`RATES_ALIASES` (``velocity_m_s``, ``dimension``) are accepted;
        ``valid: {field: false}`` becomes ``flagged``.

        Parameters
        ----------
        data : mapping
            E.g. the content of ``rates.json`` or of ``tribolmp analysis eq23-fit --json``.
        source : str, optional
            Provenance line (default: ``data["source"]`` or empty).

        Returns
        -------
        Rates
        """
        if isinstance(data, Rates):
            return data if source is None else dataclasses.replace(data, source=source)
        if not isinstance(data, Mapping):
            raise ParameterError("rates", "a mapping (rates.json content)", type(data).__name__)
        flat: dict[str, Any] = {}
        cond = data.get("conditions")
        if isinstance(cond, Mapping):
            flat.update(cond)
        flat.update({k: v for k, v in data.items() if k != "conditions"})
        kwargs: dict[str, Any] = {}
        for key, value in flat.items():
            name = RATES_ALIASES.get(key, key)
            if (
                name in _FIELD_NAMES
                and name not in ("flagged",)
                and (name not in kwargs or key == name)
            ):
                kwargs[name] = tuple(value) if isinstance(value, list) else value
        valid = data.get("valid")
        if isinstance(valid, Mapping):
            kwargs["flagged"] = tuple(
                sorted({*kwargs.get("flagged", ()), *(k for k, ok in valid.items() if ok is False)})
            )
        if source is not None:
            kwargs["source"] = source
        kwargs.setdefault("source", "")
        return cls(**kwargs)

    # ---------------------------------------------------------------- read

    @classmethod
    def units(cls) -> dict[str, str]:
        """SI unit of every numeric field (``"1"`` for dimensionless)."""
        return {
            f.name: f.metadata["unit"] for f in dataclasses.fields(cls) if f.metadata.get("unit")
        }

    def to_dict(self, *, with_units: bool = True) -> dict[str, Any]:
        """Return all fields as a plain dict (tuples as lists), with ``units`` unless disabled."""
        out = {
            k: (list(v) if isinstance(v, tuple) else v) for k, v in dataclasses.asdict(self).items()
        }
        if with_units:
            out["units"] = {k: u for k, u in self.units().items() if out.get(k) is not None}
        return out

    @property
    def has_eq23(self) -> bool:
        """True when all four Eq. 23 coefficients (C1) are given."""
        return all(getattr(self, k) is not None for k in RATES_GROUPS["eq23"])

    def require(self, *names: str) -> tuple[float, ...]:
        """Return the named values; raise a one-line ParameterError naming the first missing one."""
        out = []
        for n in names:
            v = getattr(self, n)
            if v is None:
                where = f" ({self.source})" if self.source else ""
                raise ParameterError(
                    f"rates.{n}", f"a value{where}", "nothing (not measured or not given)"
                )
            out.append(v)
        return tuple(out)


_FIELD_NAMES = frozenset(f.name for f in dataclasses.fields(Rates))

#: Field names by group (see the module docstring).
RATES_GROUPS: dict[str, tuple[str, ...]] = {
    "friction": ("mu", "mu_err", "mu_static", "mu_kinetic"),
    "eq23": ("mu_per_s", "d0_m2_s", "dz", "dx_l2"),
    "eq23_err": ("mu_per_s_err", "d0_m2_s_err", "dz_err", "dx_l2_err"),
    "microscopic": (
        "diffusion_m2_s",
        "transfer_rate",
        "wear_rate",
        "detachment_rate",
        "reattachment_rate",
        "layer_depth_m",
        "step_length_m",
        "step_time_s",
    ),
    "conditions": (
        "pressure_Pa",
        "sliding_velocity_m_s",
        "law",
        "dim",
        "automaton_diameter_m",
        "slab_thickness_m",
    ),
    "provenance": ("source", "flagged", "modes_used", "warnings"),
}

#: Other spellings accepted by :meth:`Rates.from_mapping` (``rates.json`` of the MCA analysis).
RATES_ALIASES: dict[str, str] = {"velocity_m_s": "sliding_velocity_m_s", "dimension": "dim"}
