"""Bridges between the scales: nanoscale rates, contact and friction at the machine part.

Pure numpy/scipy functions that carry a quantity measured at one scale to the
conditions of the next (PHYSICS.md section 8).  Every assumption is stated in
the docstring of the function that makes it, and listed with the test that
exercises it in ``docs/chain.md`` ("Cross-scale assumptions").

* :func:`eq23_from_rates` -- the Eq. 23 coefficients of the MCA's 1D surface
  profile at the MCA's conditions, from a ``rates.json`` / ``[rates]`` mapping
  (contract C1 fields, or the legacy transfer/wear/diffusion fields, flagged);
* :func:`rates_at_part` -- those coefficients at the part: per sliding
  distance in contact (factor ``phi V_part / V_MCA``) and from the MCA's slab
  to the 2D surface (factor ``w``, the slab thickness);
* :func:`contact_fraction_estimate` -- the real-contact fraction where the
  contact model reports no area (MDR);
* :func:`punch_bound`, :func:`apparent_contact_stiffness` -- the stiffness of
  the apparent contact: interfacial stiffness in series with the bonded punch;
* :func:`friction_at_part` -- the friction coefficient at the MCA condition
  matching the part's (static and kinetic), extrapolation flagged;
* :func:`correlation_length` -- the 1/e length of a surface's autocorrelation.

SI units throughout.
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import DataFileError, ParameterError
from .base import Result

__all__ = [
    "BEM_AREA_SLOPE",
    "C1_FIELDS",
    "apparent_contact_stiffness",
    "contact_fraction_estimate",
    "correlation_length",
    "eq23_from_rates",
    "friction_at_part",
    "interfacial_stiffness_per_area",
    "load_nanoscale_table",
    "mca_band_applies",
    "nanoscale_table_profile_length",
    "punch_bound",
    "rates_at_part",
    "rms_gradient",
    "table_at_part",
]

#: Eq. 23 coefficients of the 1D profile measured by the analysis (contract C1), with units.
C1_FIELDS = {"mu_per_s": "1/s", "d0_m2_s": "m^2/s", "dz": "m^3/s", "dx_l2": "m^5/s"}

#: Slope kappa of A_real/A0 = kappa p / (E* |grad h|_rms) at small load, measured by 3D
#: boundary-element calculations of self-affine surfaces (Hyun, Pei, Molinari & Robbins,
#: PRE 70 (2004) 026117: kappa ~ 2; Persson's theory gives sqrt(8/pi) = 1.6).
BEM_AREA_SLOPE = 2.0


def _num(rates: Mapping[str, Any], key: str, *, allow_zero: bool = True) -> float | None:
    """Return a finite non-negative number from ``rates`` (None when missing or null)."""
    v = rates.get(key)
    if v is None:
        return None
    if (
        isinstance(v, bool)
        or not isinstance(v, (int, float))
        or not math.isfinite(v)
        or v < 0
        or (not allow_zero and v == 0)
    ):
        raise ParameterError(
            f"rates.{key}", "a finite number " + (">= 0" if allow_zero else "> 0"), v
        )
    return float(v)


def _condition(rates: Mapping[str, Any], *keys: str) -> float | None:
    """Return a condition of the MCA run: top level or inside a ``conditions`` block (C1)."""
    cond = rates.get("conditions") if isinstance(rates.get("conditions"), Mapping) else {}
    for k in keys:
        for src in (rates, cond):
            if src.get(k) is not None:
                return _num(src, k, allow_zero=False)
    return None


def _as_mapping(rates: Any) -> Mapping[str, Any]:
    """Return a plain mapping of a Rates record (its given fields), or the mapping itself."""
    if hasattr(rates, "to_dict") and hasattr(rates, "flagged"):
        d = {k: v for k, v in rates.to_dict(with_units=False).items() if v is not None}
        d["valid"] = {k: False for k in rates.flagged}
        return d
    return rates


def eq23_from_rates(
    rates: Any,
    *,
    fallback: Mapping[str, Any] | None = None,
    table: Mapping[str, Any] | None = None,
) -> Result:
    """Eq. 23 coefficients of the MCA's 1D surface profile, at the MCA's conditions.

    Each coefficient (``mu``, ``D0``, ``Dz``, ``Dx l^2``) comes from the first
    of these that gives it; ``sources`` records which:

    1. **Measured (contract C1):** ``mu_per_s`` (1/s), ``d0_m2_s`` (m^2/s),
       ``dz`` (m^3/s), ``dx_l2`` (m^5/s), unless null or marked invalid by the
       analysis (``valid[field] is False`` / the record's ``flagged``).
    2. **Legacy fields**, with this stated mapping (1D, block picture of the
       seed, one time convention: the analysis' ``tau = l^2 / D``):

       * ``D0 = diffusion_m2_s``; an explicit 0 is the value 0 (no surface
         diffusion), refused only together with a flux noise (no stationary
         high-k spectrum then);
       * ``Dx l^2 = l^3 D0``: the high-k plateau ``Dx l^2 / D0 = l^3`` is one
         block's height at the block scale (the seed's picture, now with the
         same ``tau`` as the analysis);
       * ``Dz = l^3 nu_z / 2`` with ``nu_z = detachment_rate +
         reattachment_rate`` when measured, else ``transfer_rate * V_MCA`` --
         the MCA's own velocity, never the part's;
       * ``mu = wear_rate`` (1/s at V_MCA).

       When ``mu`` and ``nu_z`` come from the same measured quantity (the
       analysis set ``wear_rate = transfer_rate * V``), the spectrum's shape is
       fixed by that identity (plateau ratio 2, ``k2 = k1 / sqrt 2``, no
       ``k^-2`` range); ``shape_fixed_by_identity`` is then True and a warning
       says so.  Only the C1 coefficients measure the shape.
    3. ``table``: coefficients in the C1 names and units interpolated from
       the shipped nanoscale table at the part's condition
       (:func:`table_at_part`, already moved to the velocity these rates
       were measured at), with ``table["source"]`` naming them;
    4. ``fallback``: coefficients in the C1 names and units given by the
       caller (e.g. the scene's ``[topography]`` values, an assumption the
       report states), with ``fallback["source"]`` naming them.

    The conditions (``pressure_Pa``, ``sliding_velocity_m_s`` or the
    analysis' ``velocity_m_s``; top level or in ``conditions``) are recorded;
    the velocity is needed to turn a ``transfer_rate`` into a frequency and,
    in :func:`rates_at_part`, to move the rates to the part: a rate without
    the velocity it was measured at cannot be moved (an error there).

    Parameters
    ----------
    rates : Rates or mapping
        The :class:`~tribolmp.records.Rates` record, ``rates.json`` content or ``[rates]`` as a
        dict.
    fallback, table : mapping, optional
        ``mu_per_s``, ``d0_m2_s``, ``dz``, ``dx_l2`` (C1 units, any may be
        missing or None) and ``source`` (str).

    Returns
    -------
    Result
        ``mu`` (1/s), ``d0`` (m^2/s), ``dz`` (m^3/s), ``dx_l2`` (m^5/s),
        ``step_length_m`` (m or None), ``pressure_Pa``, ``velocity_m_s``,
        ``k1``, ``k2`` (1/m), ``source`` (one line), ``sources`` (per
        coefficient), ``shape_fixed_by_identity`` (bool), ``warnings``.
    """
    rates = _as_mapping(rates)
    if not isinstance(rates, Mapping):
        raise ParameterError(
            "rates", "a mapping (rates.json content or [rates])", type(rates).__name__
        )
    velocity = _condition(rates, "sliding_velocity_m_s", "velocity_m_s")
    pressure = _condition(rates, "pressure_Pa")
    warnings: list[str] = []
    step = _num(rates, "step_length_m", allow_zero=False)
    valid = rates.get("valid") if isinstance(rates.get("valid"), Mapping) else {}
    names = {"mu_per_s": "mu", "d0_m2_s": "d0", "dz": "dz", "dx_l2": "dx_l2"}
    val: dict[str, float] = {}
    src: dict[str, str] = {}
    for key, short in names.items():
        if rates.get(key) is not None and valid.get(key) is not False:
            val[short], src[short] = _num(rates, key), "measured (C1)"
        elif rates.get(key) is not None:
            warnings.append(f"rates.{key} marked not valid by the analysis: not used")
    # Legacy derivations for what C1 did not give.
    d0_leg = _num(rates, "diffusion_m2_s")
    if "d0" not in val and d0_leg is not None:
        val["d0"], src["d0"] = d0_leg, "legacy diffusion_m2_s"
    nu_z = nu_src = None
    det, rea = _num(rates, "detachment_rate"), _num(rates, "reattachment_rate")
    transfer = _num(rates, "transfer_rate")
    if det is not None or rea is not None:
        nu_z, nu_src = (det or 0.0) + (rea or 0.0), "detachment_rate + reattachment_rate"
    elif transfer is not None and velocity is not None:
        nu_z, nu_src = transfer * velocity, "transfer_rate * V_MCA"
    if step is not None:
        if "dx_l2" not in val and "d0" in val:
            val["dx_l2"], src["dx_l2"] = step**3 * val["d0"], "legacy l^3 D0"
        if "dz" not in val and nu_z is not None:
            val["dz"], src["dz"] = step**3 * nu_z / 2.0, f"legacy l^3 ({nu_src}) / 2"
    wear = _num(rates, "wear_rate")
    if "mu" not in val and wear is not None:
        val["mu"], src["mu"] = wear, "legacy wear_rate"
    # The shipped table, then the scene's stated values, for whatever is still missing.
    for extra in (table, fallback):
        if extra is None:
            continue
        for key, short in names.items():
            if short not in val and extra.get(key) is not None:
                val[short], src[short] = float(extra[key]), str(extra.get("source", "fallback"))
    missing = [k for k, s in names.items() if s not in val]
    if "dz" in missing and transfer is not None and velocity is None:
        raise ParameterError(
            "rates.sliding_velocity_m_s",
            "the MCA's sliding velocity to turn transfer_rate into a frequency",
            None,
        )
    if missing:
        raise ParameterError(
            "rates",
            f"the Eq. 23 coefficients {sorted(names)} (C1), legacy fields, or a fallback",
            f"missing {missing}",
        )
    mu, d0, dz, dxl2 = val["mu"], val["d0"], val["dz"], val["dx_l2"]
    fixed = (
        src["mu"] == "legacy wear_rate"
        and src["dz"].startswith("legacy")
        and nu_z is not None
        and nu_z > 0
        and mu > 0
        and abs(mu - nu_z) <= 1e-6 * max(mu, nu_z)
    )
    if (
        src["mu"] == "legacy wear_rate"
        and nu_src == "transfer_rate * V_MCA"
        and not fixed
        and mu > 0
        and transfer
        and src["dz"].startswith("legacy")
    ):
        warnings.append(
            f"wear_rate/transfer_rate = {mu / transfer:.3g} m/s differs from "
            f"V_MCA = {velocity:g} m/s: the two rates were measured at different velocities"
        )
    if fixed:
        warnings.append(
            "legacy rates: mu (wear_rate) and Dz ("
            + str(nu_src)
            + ") are the same measured number, "
            "so the spectrum's shape is fixed by that identity (plateau ratio 2, k2 = k1/sqrt(2), "
            "no k^-2 range); measure the C1 coefficients (mu_per_s, d0_m2_s, dz, dx_l2)"
        )
    if d0 == 0 and dxl2 > 0:
        raise ParameterError(
            "rates.d0_m2_s" if src["d0"] == "measured (C1)" else "rates.diffusion_m2_s",
            "D0 > 0 when the flux noise Dx l^2 > 0 (no stationary high-k spectrum otherwise)",
            0.0,
        )
    kinds = sorted(set(src.values()))
    source = (
        "measured (C1)"
        if kinds == ["measured (C1)"]
        else "legacy"
        if all(k.startswith("legacy") for k in kinds)
        else "mixed: " + "; ".join(f"{k}: {v}" for k, v in src.items())
    )
    k1 = math.sqrt(mu / d0) if d0 > 0 else math.inf
    k2 = math.sqrt(dz / dxl2) if dxl2 > 0 else math.inf
    return Result(
        mu=mu,
        d0=d0,
        dz=dz,
        dx_l2=dxl2,
        step_length_m=step,
        pressure_Pa=pressure,
        velocity_m_s=velocity,
        k1=k1,
        k2=k2,
        source=source,
        sources=src,
        shape_fixed_by_identity=bool(fixed),
        warnings=warnings,
        units={
            "mu": "1/s",
            "d0": "m^2/s",
            "dz": "m^3/s",
            "dx_l2": "m^5/s",
            "step_length_m": "m",
            "pressure_Pa": "Pa",
            "velocity_m_s": "m/s",
            "k1": "1/m",
            "k2": "1/m",
        },
        method="eq23_from_rates",
        message=f"Eq. 23 coefficients ({source}) at V = {velocity} m/s",
    )


def rates_at_part(
    eq23: Mapping[str, Any], *, phi: float, velocity_m_s: float, slab_thickness_m: float
) -> Result:
    """Eq. 23 coefficients of the part's 2D surface from the MCA's 1D ones.

    Assumptions (PHYSICS.md section 8):

    * **Per sliding distance in contact.** The MCA surface is always in
      contact and slides at ``V_MCA``; a point of the part's surface is in
      real contact a fraction ``phi`` of the time and slides at ``V_part``.
      Every process is taken to scale with the distance slid in contact, so
      every rate (``mu``, ``D0``, ``Dz``, ``Dx l^2``) is multiplied by
      ``phi V_part / V_MCA``.  The crossovers ``k1 = sqrt(mu/D0)`` and
      ``k2 = sqrt(Dz/(Dx l^2))`` and the stationary spectrum are unchanged;
      only the time to reach it scales.
    * **Slab to surface.** A 2D MCA is a slab of thickness ``w`` (one
      automaton).  Its profile is the strip average of the 2D surface across
      ``w``, so a 2D noise of intensity ``D2`` (m^4/s) appears in the profile
      as ``D2 / w``: ``Dz_2D = w Dz_1D``, ``(Dx l^2)_2D = w (Dx l^2)_1D``;
      ``mu`` and ``D0`` are intensive and unchanged.  The plateaus of the 2D
      PSD are then ``w`` times those of the 1D one.
    * The surface is isotropic: the same coefficients along and across the
      sliding direction.

    Parameters
    ----------
    eq23 : mapping
        :func:`eq23_from_rates` result (``mu``, ``d0``, ``dz``, ``dx_l2``, ``velocity_m_s``).
    phi : float
        Real-contact area fraction, in [0, 1].
    velocity_m_s : float
        The part's sliding velocity (m/s), >= 0.
    slab_thickness_m : float
        The MCA slab thickness ``w`` (m), > 0.

    Returns
    -------
    Result
        ``mu`` (1/s), ``d0`` (m^2/s), ``dz`` (m^4/s), ``dx_l2`` (m^6/s),
        ``factor`` (``phi V_part/V_MCA``), ``phi``, ``slab_thickness_m``.
    """
    if not (isinstance(phi, (int, float)) and math.isfinite(phi) and 0.0 <= phi <= 1.0):
        raise ParameterError("phi", "a real-contact fraction in [0, 1]", phi)
    if not (
        isinstance(velocity_m_s, (int, float)) and math.isfinite(velocity_m_s) and velocity_m_s >= 0
    ):
        raise ParameterError("sliding_velocity", "a finite velocity >= 0 m/s", velocity_m_s)
    if not (
        isinstance(slab_thickness_m, (int, float))
        and math.isfinite(slab_thickness_m)
        and slab_thickness_m > 0
    ):
        raise ParameterError("slab_thickness_m", "a slab thickness > 0 m", slab_thickness_m)
    if eq23.get("velocity_m_s") is None:
        raise ParameterError(
            "rates.sliding_velocity_m_s",
            "the MCA's sliding velocity (m/s) the rates were measured at",
            None,
        )
    v_mca = float(eq23["velocity_m_s"])
    factor = float(phi) * float(velocity_m_s) / v_mca
    w = float(slab_thickness_m)
    return Result(
        mu=eq23["mu"] * factor,
        d0=eq23["d0"] * factor,
        dz=eq23["dz"] * w * factor,
        dx_l2=eq23["dx_l2"] * w * factor,
        factor=factor,
        phi=float(phi),
        slab_thickness_m=w,
        units={
            "mu": "1/s",
            "d0": "m^2/s",
            "dz": "m^4/s",
            "dx_l2": "m^6/s",
            "factor": "1",
            "phi": "1",
            "slab_thickness_m": "m",
        },
        method="per-distance-in-contact",
        message=f"rates x phi V/V_MCA = {factor:.3g}, noise x w = {w:g} m",
    )


def rms_gradient(heights, pixel_size: float) -> float:
    """Root-mean-square gradient magnitude of a periodic height map (spectral derivative, 1).

    Computed from the Fourier coefficients (``|grad h|^2 = sum_q q^2 |h_q|^2``),
    so it is the continuum value of the band-limited surface, not a finite
    difference (which underestimates it at the shortest wavelengths).
    """
    h = np.asarray(heights, dtype=float)
    n0, n1 = h.shape
    qx = 2 * np.pi * np.fft.fftfreq(n0, pixel_size)[:, None]
    qy = 2 * np.pi * np.fft.fftfreq(n1, pixel_size)[None, :]
    H = np.fft.fft2(h - h.mean()) / (n0 * n1)
    return float(np.sqrt(np.sum((qx**2 + qy**2) * np.abs(H) ** 2)))


def contact_fraction_estimate(pressure_Pa: float, E_star: float, grad_rms: float) -> float:
    """Real-contact fraction of a rough elastic contact where the model gives no area (MDR).

    ``phi = erf(sqrt(pi)/2 * kappa * p / (E* |grad h|_rms))`` with
    ``kappa = BEM_AREA_SLOPE = 2``: linear in ``p`` with the slope measured by
    3D boundary-element calculations at small load (Hyun et al. 2004), and
    saturating at full contact like Persson's theory.  An estimate, stated as
    such in the report: accurate to about 20 % for ``phi < 0.1`` on a
    resolved surface; it depends on the surface's rms gradient, i.e. on its
    shortest resolved wavelength.
    """
    if not grad_rms > 0:
        return 1.0
    x = (
        0.5
        * math.sqrt(math.pi)
        * BEM_AREA_SLOPE
        * float(pressure_Pa)
        / (float(E_star) * float(grad_rms))
    )
    return float(min(1.0, math.erf(x)))


def punch_bound(area_m2: float, E_star: float) -> float:
    """Return the normal stiffness (N/m) of a bonded flat circular punch of area A, 2 E* sqrt(A/pi).

    No contact of apparent area ``A`` is stiffer (PHYSICS.md section 8): a
    fully bonded, perfectly flat interface is the stiffest, and the circular
    punch of the same area stands for the apparent contact (a square punch of
    the same area is stiffer by less than 1.5 %).
    """
    if not (area_m2 > 0 and E_star > 0):
        raise ParameterError(
            "area", "an apparent area > 0 m^2 and a modulus > 0 Pa", (area_m2, E_star)
        )
    return 2.0 * float(E_star) * math.sqrt(float(area_m2) / math.pi)


def apparent_contact_stiffness(k_int_per_area: float, area_m2: float, E_star: float) -> Result:
    """Return the normal stiffness (N/m) of an apparent contact: interface and bodies in series.

    ``1/k = 1/(K_int A) + 1/k_punch``, ``k_punch = 2 E* sqrt(A/pi)``
    (PHYSICS.md section 8).  ``K_int`` (N/m^3) is the interfacial stiffness
    per unit nominal area, intensive, measured on a patch that represents the
    surface (larger than the roll-off wavelength).  The result never exceeds
    ``k_punch``; ``K_int = inf`` (closed interface) gives ``k_punch``.

    Returns
    -------
    Result
        ``stiffness`` (N/m), ``bound`` (N/m, ``k_punch``), ``interface`` (N/m,
        ``K_int A``), ``interface_share`` (fraction of the compliance in the
        interface, 1).
    """
    kp = punch_bound(area_m2, E_star)
    if not (isinstance(k_int_per_area, (int, float, np.floating)) and k_int_per_area > 0):
        raise ParameterError(
            "k_int_per_area", "an interfacial stiffness per area > 0 N/m^3", k_int_per_area
        )
    ki = float(k_int_per_area) * float(area_m2)
    c_int = 0.0 if math.isinf(ki) else 1.0 / ki
    k = 1.0 / (c_int + 1.0 / kp)
    return Result(
        stiffness=k,
        bound=kp,
        interface=ki,
        interface_share=c_int * k,
        units={"stiffness": "N/m", "bound": "N/m", "interface": "N/m", "interface_share": "1"},
        method="series",
        message=f"interface {ki:.3g} N/m in series with the bonded punch {kp:.3g} N/m",
    )


def interfacial_stiffness_per_area(
    pressures, stiffness, patch_area_m2: float, pressure_Pa: float
) -> float:
    """Interfacial stiffness per unit area (N/m^3) at ``pressure_Pa``, log-log interpolated.

    ``stiffness`` (N/m) of a periodic patch of area ``patch_area_m2`` at the
    nominal ``pressures`` (Pa); refused outside their range (no extrapolation).
    """
    p = np.asarray(pressures, float)
    # A closed periodic cell (BEM area fraction 1) has k = inf, which the stage's JSON stores as
    # null (read back as nan): the interface is then rigid, and the series with the punch is the
    # punch.
    vals = np.asarray(stiffness, dtype=object).ravel()
    k = np.asarray([np.inf if v is None else v for v in vals], float)
    k = np.where(np.isnan(k), np.inf, k) / float(patch_area_m2)
    if p.size == 1:
        if not math.isclose(p[0], pressure_Pa, rel_tol=1e-9):
            raise ParameterError("pressure", f"the solved pressure {p[0]:g} Pa", pressure_Pa)
        return float(k[0])
    if not (p.min() * (1 - 1e-12) <= pressure_Pa <= p.max() * (1 + 1e-12)):
        raise ParameterError(
            "[load].normal_force",
            f"a nominal pressure within [{p.min():g}, {p.max():g}] Pa",
            f"{pressure_Pa:g} Pa",
        )
    hit = np.isclose(p, pressure_Pa, rtol=1e-9, atol=0.0)
    if hit.any():
        # a solved pressure: its own value (a closed periodic cell above it has k = inf, which
        # would turn the log-log interpolation into inf * 0 = nan at the node)
        return float(k[np.argmax(hit)])
    o = np.argsort(p)
    return float(np.exp(np.interp(math.log(pressure_Pa), np.log(p[o]), np.log(k[o]))))


# ------------------------------------------------------------------ friction


def load_nanoscale_table(path: str | Path) -> list[dict[str, Any]]:
    """Read the rows of ``nanoscale_table.json``.

    Contract C6: ``{"rows": [{pressure_Pa, sliding_velocity_m_s, mu, ...}]}``.
    """
    path = Path(path)
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError) as exc:
        raise DataFileError(
            f"{path}: expected a readable JSON nanoscale table, got {' '.join(str(exc).split())}"
        ) from None
    rows = data.get("rows") if isinstance(data, dict) else None
    if not isinstance(rows, list) or not rows:
        raise DataFileError(f"{path}: rows: expected a non-empty list of measured conditions")
    out = []
    for i, r in enumerate(rows):
        try:
            p, v, m = (
                float(r["pressure_Pa"]),
                float(r.get("sliding_velocity_m_s", r.get("velocity_m_s"))),
                float(r["mu"]),
            )
        except (KeyError, TypeError, ValueError):
            raise DataFileError(
                f"{path}: rows[{i}]: expected numbers pressure_Pa, sliding_velocity_m_s, mu"
            ) from None
        if not (p > 0 and v > 0 and m >= 0 and all(map(math.isfinite, (p, v, m)))):
            raise DataFileError(
                f"{path}: rows[{i}]: expected pressure_Pa > 0, sliding_velocity_m_s > 0, mu >= 0"
            )
        out.append(dict(r, pressure_Pa=p, sliding_velocity_m_s=v, mu=m))
    return out


def nanoscale_table_profile_length(path: str | Path) -> float | None:
    """Return the length (m) of the MCA profiles the table's Eq. 23 rows were measured on.

    Read from ``provenance.profile_length_m``; None when the table does not state it.
    """
    try:
        data = json.loads(Path(path).read_text(encoding="utf-8"))
        value = float(data["provenance"]["profile_length_m"])
    except (OSError, ValueError, KeyError, TypeError):
        return None
    return value if math.isfinite(value) and value > 0 else None


def mca_band_applies(pixel_size: float, profile_length: float | None) -> Result:
    """Decide whether Eq. 23 coefficients measured on an MCA profile apply to a part's surface.

    The MCA measures the relaxation rate and the noise of the Fourier modes of its own surface
    profile: wavelengths from two automata up to the profile length ``profile_length`` (the
    MCA box).  The part's height map resolves wavelengths from ``2 pixel_size`` up to its side.
    When the part's shortest resolved wavelength is longer than the MCA's longest measured
    one, no mode of the part was measured: Eq. 23's mu (a relaxation rate of every mode, the
    same at every k) would be extrapolated from nanometre modes to micrometre ones, where it
    is not a measurement (a profile relaxation the MCA sees within ~1 ns of sliding would
    flatten a micrometre surface within the first interval).  Such coefficients are therefore
    not used for the part; the caller falls back to the next tier of its precedence and says
    why.  With an overlap they are used for all of the part's modes, an extrapolation to its
    longer wavelengths that the caller flags.

    Parameters
    ----------
    pixel_size : float
        Pixel of the part's height map (m).
    profile_length : float or None
        Length of the MCA profile the coefficients come from (m); None: not stated.

    Returns
    -------
    Result
        ``applies`` (bool), ``reason`` (str), ``part_shortest_wavelength_m``,
        ``mca_longest_wavelength_m``.
    """
    lam_part = 2.0 * float(pixel_size)
    if profile_length is None:
        ok, why = False, "the MCA profile length they were measured on is not stated"
    elif lam_part > profile_length:
        ok, why = False, (
            f"the MCA measured wavelengths up to {profile_length:.3g} m, the part's surface "
            f"resolves none below {lam_part:.3g} m (no common mode)"
        )
    else:
        ok, why = True, (
            f"the MCA's wavelengths (up to {profile_length:.3g} m) overlap the part's (from "
            f"{lam_part:.3g} m); used for all of the part's modes (extrapolated to its longer "
            "wavelengths)"
        )
    return Result(applies=ok, reason=why, part_shortest_wavelength_m=lam_part,
                  mca_longest_wavelength_m=profile_length)


def table_at_part(
    rows: Sequence[Mapping[str, Any]],
    field: str,
    *,
    pressure_Pa: float,
    velocity_m_s: float,
    log_values: bool = False,
) -> Result | None:
    """Interpolate one field of the nanoscale table at the part's condition (None: never measured).

    The rule of :func:`friction_at_part`, for any field: only the rows that
    measured it (value not null, ``<field>_valid`` not False); of those, the
    rows at the velocity closest to the part's in ``log V``; linear in
    ``log p`` between them (in ``log value`` too with ``log_values``, for the
    Eq. 23 rates that span decades; a zero then falls back to linear values),
    the nearest row outside their pressure range.  ``extrapolated`` is True
    when the pressure lies outside that range by more than 10 % or the
    velocity differs from the matched one by more than a factor 2.

    Returns
    -------
    Result or None
        ``value``, ``err`` (interpolated the same way, None if the rows give none),
        ``velocity_m_s`` (the matched rows' velocity), ``pressure_range_Pa``,
        ``extrapolated``, ``extrapolation`` (text), ``rows`` (number used).
    """
    if not (pressure_Pa > 0 and velocity_m_s > 0):
        raise ParameterError(
            "pressure, velocity",
            "a matching pressure > 0 Pa and a velocity > 0 m/s",
            (pressure_Pa, velocity_m_s),
        )
    use = [
        r for r in rows
        if r.get(field) is not None and r.get(f"{field}_valid", True) is not False
    ]
    if not use:
        return None
    V = np.array([float(r["sliding_velocity_m_s"]) for r in use])
    v_near = V[np.argmin(np.abs(np.log(V / velocity_m_s)))]
    sel = [r for r, v in zip(use, V) if math.isclose(v, v_near, rel_tol=1e-6)]
    sel.sort(key=lambda r: float(r["pressure_Pa"]))
    lp = np.log([float(r["pressure_Pa"]) for r in sel])
    vals = np.array([float(r[field]) for r in sel])
    errs = [r.get(f"{field}_err") for r in sel]
    x = math.log(pressure_Pa)
    logv = log_values and bool(np.all(vals > 0))
    value = float(np.exp(np.interp(x, lp, np.log(vals))) if logv else np.interp(x, lp, vals))
    err = None
    if all(e is not None for e in errs):
        e = np.array(errs, float)
        # relative errors interpolate like the values on a log scale
        err = float(np.interp(x, lp, e / vals) * value) if logv else float(np.interp(x, lp, e))
    p_lo, p_hi = float(np.exp(lp[0])), float(np.exp(lp[-1]))
    p_out = pressure_Pa < p_lo / 1.1 or pressure_Pa > p_hi * 1.1
    v_out = abs(math.log(v_near / velocity_m_s)) > math.log(2.0)
    why = []
    if p_out:
        why.append(
            f"pressure {pressure_Pa:.3g} Pa outside the measured [{p_lo:.3g}, {p_hi:.3g}] Pa"
        )
    if v_out:
        why.append(f"velocity {velocity_m_s:g} m/s vs measured {v_near:g} m/s")
    return Result(
        value=value,
        err=err,
        velocity_m_s=float(v_near),
        pressure_range_Pa=[p_lo, p_hi],
        extrapolated=bool(p_out or v_out),
        extrapolation="; ".join(why),
        rows=len(sel),
        method="nearest-velocity, log-pressure interpolation",
        message=f"{field} from {len(sel)} row(s) at {v_near:g} m/s",
    )


def friction_at_part(
    rows: Sequence[Mapping[str, Any]],
    *,
    pressure_Pa: float,
    velocity_m_s: float,
    mu_static: float | None = None,
    mu_kinetic: float | None = None,
    static_ratio: float = 1.0,
    pressure_source: str = "nominal",
    table: Sequence[Mapping[str, Any]] | None = None,
) -> Result:
    """Friction coefficients at the MCA condition that matches the part's.

    Rule (stated in the report):

    * the rows measured at the velocity closest to the part's (in
      ``log V``) are interpolated linearly in ``log p`` at ``pressure_Pa``
      (the part's nominal pressure, or its mean real-contact pressure
      ``p / phi``; ``pressure_source`` says which); outside their pressure
      range the nearest row is used;
    * ``extrapolated`` is True when the pressure lies outside the measured
      range by more than 10 % or the velocity differs from the nearest
      measured one by more than a factor 2 -- always the case for an MCA run
      at 1-20 m/s and a part at 1 cm/s (PHYSICS.md section 8: a coefficient
      measured at 5 m/s in a 100 nm box is not a static coefficient at 1 cm/s);
    * kinetic coefficient: ``mu_kinetic`` when given (the scene's), else the
      interpolated ``mu``; with rows at several velocities at the matched
      pressure a velocity-dependent table ``mu_k(v)`` is returned as well;
    * static coefficient: ``mu_static`` when given, else the measured ratio
      ``mu_static / mu_kinetic`` of the nanoscale ``table`` (rows that carry
      both, interpolated by :func:`table_at_part`) times ``mu_k``, else
      ``static_ratio * mu_k`` (the scene's stated assumption; ratio 1 = no
      static excess = no stick-slip from the data), never below ``mu_k``.

    Parameters
    ----------
    rows : sequence of mapping
        Measured conditions, each with ``pressure_Pa``, ``sliding_velocity_m_s`` and ``mu``.
    pressure_Pa, velocity_m_s : float
        The part's matching pressure (Pa) and sliding velocity (m/s).
    mu_static, mu_kinetic : float, optional
        Coefficients given by the scene (override the data).
    static_ratio : float
        ``mu_s / mu_k`` when ``mu_static`` is not given, >= 1.
    pressure_source : {"nominal", "real"}
        Recorded in the result.
    table : sequence of mapping, optional
        The nanoscale table's rows, read for a measured ``mu_static`` /
        ``mu_kinetic`` (``rows`` may be the table itself or one measured condition).

    Returns
    -------
    Result
        ``mu`` (interpolated data value), ``mu_kinetic``, ``mu_static``,
        ``extrapolated`` (bool), ``matched`` (the row(s) used),
        ``velocity_table`` (``(v, mu)`` lists or None), ``source`` (text).
    """
    if not rows:
        raise ParameterError("rates", "at least one measured friction condition", "none")
    if not (static_ratio >= 1.0 and math.isfinite(static_ratio)):
        raise ParameterError("[running_in].static_ratio", "a ratio mu_s/mu_k >= 1", static_ratio)
    if not (pressure_Pa > 0 and velocity_m_s > 0):
        raise ParameterError(
            "pressure, velocity",
            "a matching pressure > 0 Pa and a velocity > 0 m/s",
            (pressure_Pa, velocity_m_s),
        )
    P = np.array([float(r["pressure_Pa"]) for r in rows])
    V = np.array([float(r["sliding_velocity_m_s"]) for r in rows])
    M = np.array([float(r["mu"]) for r in rows])
    dv = np.abs(np.log(V / velocity_m_s))
    v_near = V[np.argmin(dv)]
    sel = np.isclose(V, v_near, rtol=1e-6)
    p_sel, m_sel = P[sel], M[sel]
    o = np.argsort(p_sel)
    p_sel, m_sel = p_sel[o], m_sel[o]
    mu = float(np.interp(math.log(pressure_Pa), np.log(p_sel), m_sel))
    p_out = pressure_Pa < p_sel[0] / 1.1 or pressure_Pa > p_sel[-1] * 1.1
    v_out = abs(math.log(v_near / velocity_m_s)) > math.log(2.0)
    extrapolated = bool(p_out or v_out)
    # Several velocities at (about) the matched pressure: a measured mu_k(v).
    i_p = np.argmin(np.abs(np.log(P / pressure_Pa)))
    at_p = np.isclose(P, P[i_p], rtol=1e-6)
    vt = None
    if np.unique(V[at_p]).size >= 2:
        ov = np.argsort(V[at_p])
        vt = ([float(x) for x in V[at_p][ov]], [float(x) for x in M[at_p][ov]])
    mu_k = float(mu_kinetic) if mu_kinetic is not None else mu
    ratio_src = f"{static_ratio:g} x mu_k (scene [running_in].static_ratio)"
    if mu_static is None and table:
        ts = table_at_part(table, "mu_static", pressure_Pa=pressure_Pa, velocity_m_s=velocity_m_s)
        tk = table_at_part(table, "mu_kinetic", pressure_Pa=pressure_Pa, velocity_m_s=velocity_m_s)
        if ts is not None and tk is not None and tk.value > 0:
            static_ratio = max(1.0, ts.value / tk.value)
            ratio_src = (
                f"{static_ratio:.3g} x mu_k (measured mu_s/mu_k of the nanoscale table at "
                f"{tk.velocity_m_s:g} m/s" + (", extrapolated)" if ts.extrapolated else ")")
            )
    mu_s = float(mu_static) if mu_static is not None else static_ratio * mu_k
    if mu_s < mu_k:
        raise ParameterError(
            "[running_in].mu_static", f"a static coefficient >= mu_kinetic ({mu_k:g})", mu_s
        )
    why = []
    if p_out:
        why.append(
            f"pressure {pressure_Pa:.3g} Pa ({pressure_source}) outside the measured "
            f"[{p_sel[0]:.3g}, {p_sel[-1]:.3g}] Pa"
        )
    if v_out:
        why.append(f"velocity {velocity_m_s:g} m/s vs measured {v_near:g} m/s")
    src_k = (
        "scene [running_in].mu_kinetic"
        if mu_kinetic is not None
        else f"MCA at {v_near:g} m/s, interpolated in log p"
    )
    src_s = "scene [running_in].mu_static" if mu_static is not None else ratio_src
    return Result(
        mu=mu,
        mu_kinetic=mu_k,
        mu_static=mu_s,
        extrapolated=extrapolated,
        extrapolation="; ".join(why),
        matched=[
            {"pressure_Pa": float(p), "sliding_velocity_m_s": float(v_near), "mu": float(m)}
            for p, m in zip(p_sel, m_sel)
        ],
        velocity_table=vt,
        pressure_Pa=float(pressure_Pa),
        pressure_source=pressure_source,
        source=f"mu_k: {src_k}; mu_s: {src_s}",
        units={"mu": "1", "mu_kinetic": "1", "mu_static": "1", "pressure_Pa": "Pa"},
        method="nearest-velocity, log-pressure interpolation",
        message=("extrapolated: " + "; ".join(why))
        if extrapolated
        else "within the measured conditions",
    )


# ------------------------------------------------------------------ surfaces


def correlation_length(heights, pixel_size: float) -> float:
    """Radial 1/e length (m) of a periodic surface's height autocorrelation.

    The autocorrelation is computed by FFT, averaged over angle, and the first
    crossing of ``C(r)/C(0) = 1/e`` is interpolated linearly; ``inf`` when it
    does not fall to 1/e within half the cell.
    """
    h = np.asarray(heights, dtype=float)
    h = h - h.mean()
    n0, n1 = h.shape
    acf = np.fft.ifft2(np.abs(np.fft.fft2(h)) ** 2).real
    acf /= acf[0, 0]
    i = np.fft.fftfreq(n0) * n0
    j = np.fft.fftfreq(n1) * n1
    r = np.hypot(i[:, None], j[None, :])
    rb = np.rint(r).astype(int)
    rmax = min(n0, n1) // 2
    mask = rb <= rmax
    prof = np.bincount(rb[mask], weights=acf[mask]) / np.maximum(np.bincount(rb[mask]), 1)
    below = np.flatnonzero(prof < math.exp(-1.0))
    if below.size == 0:
        return math.inf
    k = int(below[0])
    c0, c1 = prof[k - 1], prof[k]
    frac = (c0 - math.exp(-1.0)) / (c0 - c1)
    return float((k - 1 + frac) * pixel_size)
