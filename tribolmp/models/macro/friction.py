"""Friction laws for the sliding rigid body.

A law gives the static coefficient ``mu_s`` (the largest ratio ``|F|/N`` a
sticking contact holds) and the kinetic coefficient ``mu_k(v)`` for a sliding
speed ``v >= 0`` (m/s).  Laws must satisfy ``mu_k(0) <= mu_s``, so that a body
that stops does not start again without a larger force (no chattering).

Laws are chosen by name from :data:`FRICTION_LAWS` or read from the
nanoscale model's output with :func:`load_friction_law`: a ``rates.json``
(``mu`` -> constant law) or a table of ``mu`` against ``velocity_m_s`` (CSV
or JSON).
"""

from __future__ import annotations

import csv
import json
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ...errors import DataFileError, ParameterError
from ..base import MethodRegistry, check_positive, check_range

__all__ = [
    "FrictionLaw",
    "ConstantFriction",
    "VelocityWeakening",
    "TabulatedFriction",
    "FRICTION_LAWS",
    "make_friction_law",
    "load_friction_law",
]

FRICTION_LAWS = MethodRegistry("friction law")


class FrictionLaw:
    """Base class: ``mu_s`` (static) and ``kinetic(v)`` (sliding speed ``v >= 0`` in m/s)."""

    mu_s: float

    def kinetic(self, v: float) -> float:  # pragma: no cover - abstract
        """Return the kinetic coefficient (1) at sliding speed ``v`` (m/s)."""
        raise NotImplementedError

    def _check(self) -> None:
        if self.kinetic(0.0) > self.mu_s * (1 + 1e-12):
            raise ParameterError(
                "mu_s", f"a static coefficient >= mu_k(0) = {self.kinetic(0.0):g}", self.mu_s
            )


@FRICTION_LAWS.register("constant")
@dataclass(frozen=True)
class ConstantFriction(FrictionLaw):
    """Coulomb friction: static ``mu_s``, kinetic ``mu_k`` (default ``mu_s``)."""

    mu_s: float = 0.3
    mu_k: float | None = None

    def __post_init__(self):
        check_range("mu_s", self.mu_s, 0.0, 10.0)
        if self.mu_k is None:
            object.__setattr__(self, "mu_k", float(self.mu_s))
        check_range("mu_k", self.mu_k, 0.0, 10.0)
        self._check()

    def kinetic(self, v: float) -> float:
        """Kinetic coefficient (independent of ``v``)."""
        return self.mu_k


#: High-speed to static friction ratio of a velocity-weakening law when no mu_k is given: a typical
#: dry metal-on-metal value (kinetic ~ 3/4 of static), stated wherever it is used.
DYNAMIC_TO_STATIC = 0.75


@FRICTION_LAWS.register("velocity-weakening")
@dataclass(frozen=True)
class VelocityWeakening(FrictionLaw):
    """Velocity-weakening friction, ``kinetic(v) = mu_k + (mu_s - mu_k) exp(-|v| / v_c)``.

    Continuous at rest (``kinetic(0) = mu_s``) and weakening with speed
    towards ``mu_k``.

    Parameters
    ----------
    mu_s : float
        Static coefficient (1), also the kinetic coefficient at rest.
    mu_k : float or None
        Kinetic coefficient at high speed (1).  None takes
        :data:`DYNAMIC_TO_STATIC` times ``mu_s`` (a default ratio, not a
        measurement).
    v_c : float
        Characteristic weakening speed (m/s).
    """

    mu_s: float = 0.4
    mu_k: float | None = 0.25
    v_c: float = 1e-3

    def __post_init__(self):
        check_range("mu_s", self.mu_s, 0.0, 10.0)
        if self.mu_k is None:
            object.__setattr__(self, "mu_k", DYNAMIC_TO_STATIC * float(self.mu_s))
        check_range("mu_k", self.mu_k, 0.0, 10.0)
        check_positive("v_c", self.v_c, "m/s")
        self._check()

    def kinetic(self, v: float) -> float:
        """Kinetic coefficient at sliding speed ``v`` (m/s)."""
        return self.mu_k + (self.mu_s - self.mu_k) * math.exp(-abs(v) / self.v_c)


@FRICTION_LAWS.register("table")
@dataclass(frozen=True)
class TabulatedFriction(FrictionLaw):
    """``mu_k(v)`` interpolated linearly in a table (clamped outside).

    ``mu_s`` defaults to the table maximum at v = min.
    """

    velocity: tuple[float, ...] = (0.0, 1.0)
    mu: tuple[float, ...] = (0.3, 0.3)
    mu_s: float | None = None

    def __post_init__(self):
        v = np.asarray(self.velocity, dtype=float)
        m = np.asarray(self.mu, dtype=float)
        if v.ndim != 1 or v.size < 1 or v.shape != m.shape:
            raise ParameterError(
                "velocity, mu", "two lists of equal length >= 1", f"{v.size}, {m.size}"
            )
        if not (
            np.all(np.isfinite(v)) and np.all(np.isfinite(m)) and np.all(v >= 0) and np.all(m >= 0)
        ):
            raise ParameterError("velocity, mu", "finite non-negative numbers", "invalid entries")
        order = np.argsort(v)
        object.__setattr__(self, "velocity", tuple(v[order]))
        object.__setattr__(self, "mu", tuple(m[order]))
        if self.mu_s is None:
            object.__setattr__(self, "mu_s", float(m[order][0]))
        check_range("mu_s", self.mu_s, 0.0, 10.0)
        self._check()

    def kinetic(self, v: float) -> float:
        """Kinetic coefficient interpolated at speed ``v`` (m/s)."""
        return float(np.interp(abs(v), self.velocity, self.mu))


def make_friction_law(name: str, **kwargs) -> FrictionLaw:
    """Build a law by registry name (``constant``, ``velocity-weakening``, ``table``)."""
    return FRICTION_LAWS.get(name, "friction_law")(**kwargs)


def load_friction_law(path: str | Path, mu_s: float | None = None) -> FrictionLaw:
    """Read a friction law produced by the nanoscale model.

    Accepted files:

    * ``rates.json`` with a number ``mu`` -> :class:`ConstantFriction`;
    * JSON with lists ``velocity_m_s`` and ``mu`` -> :class:`TabulatedFriction`;
    * CSV with columns ``velocity_m_s`` and ``mu`` -> :class:`TabulatedFriction`.

    Raises
    ------
    DataFileError
        Unreadable file, missing fields or columns, non-numeric or negative values.
    """
    path = Path(path)
    name = str(path)
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise DataFileError(
            f"{name}: expected a readable rates.json or mu(v) "
            f"CSV, got {getattr(exc, 'strerror', None) or exc}"
        ) from None
    if path.suffix.lower() == ".json":
        try:
            data = json.loads(text)
        except json.JSONDecodeError as exc:
            raise DataFileError(
                f"{name}: expected valid JSON, got {exc.msg} at line {exc.lineno}"
            ) from None
        if not isinstance(data, dict):
            raise DataFileError(f"{name}: expected a JSON object, got {type(data).__name__}")
        if "velocity_m_s" in data and "mu" in data:
            v, m = data["velocity_m_s"], data["mu"]
            if not (isinstance(v, list) and isinstance(m, list)):
                raise DataFileError(
                    f"{name}: velocity_m_s, mu: expected two lists, "
                    f"got {type(v).__name__}, {type(m).__name__}"
                )
            try:
                return TabulatedFriction(
                    tuple(float(a) for a in v), tuple(float(b) for b in m), mu_s
                )
            except (TypeError, ValueError, ParameterError) as exc:
                raise DataFileError(
                    f"{name}: velocity_m_s, mu: expected finite non-negative numbers, got {exc}"
                ) from None
        mu = data.get("mu")
        if (
            isinstance(mu, bool)
            or not isinstance(mu, (int, float))
            or not math.isfinite(mu)
            or mu < 0
        ):
            raise DataFileError(f"{name}: mu: expected a finite number >= 0, got {mu!r}")
        return ConstantFriction(mu_s=float(mu) if mu_s is None else mu_s, mu_k=float(mu))
    rows = list(
        csv.reader(line for line in text.splitlines() if line.strip() and not line.startswith("#"))
    )
    header = [h.strip() for h in rows[0]] if rows else []
    for col in ("velocity_m_s", "mu"):
        if col not in header:
            raise DataFileError(
                f"{name}: column {col}: expected in the header, got columns {header}"
            )
    iv, im = header.index("velocity_m_s"), header.index("mu")
    v, m = [], []
    for lineno, row in enumerate(rows[1:], start=2):
        for idx, col, out in ((iv, "velocity_m_s", v), (im, "mu", m)):
            cell = row[idx].strip() if idx < len(row) else ""
            try:
                val = float(cell)
            except ValueError:
                raise DataFileError(
                    f"{name}: line {lineno}: {col}: expected a finite number, got {cell!r}"
                ) from None
            if not math.isfinite(val) or val < 0:
                raise DataFileError(
                    f"{name}: line {lineno}: {col}: expected a finite number >= 0, got {cell!r}"
                )
            out.append(val)
    if not v:
        raise DataFileError(f"{name}: expected at least one data row, got none")
    return TabulatedFriction(tuple(v), tuple(m), mu_s)
