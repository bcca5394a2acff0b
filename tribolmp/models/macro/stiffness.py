"""Tangential stiffness of the apparent contact from a patch's stiffness-against-pressure table.

The conversion the chain hands the rigid body (moved here from the chain's
glue, unchanged; issue 15 replaces its physics with the interfacial stiffness in
series with the bodies' compliance).
"""

from __future__ import annotations

import numpy as np

from ...errors import ParameterError

__all__ = ["apparent_tangential_stiffness", "tangential_stiffness_from_table"]


def tangential_stiffness_from_table(
    pressure, stiffness, force, *, normal_force: float, apparent_area: float, shear_to_normal: float
) -> tuple[float, str]:
    """Tangential stiffness (N/m) of an apparent contact from a patch's normal-stiffness table.

    The table gives the normal stiffness ``k_n(p)`` of a patch of area
    ``A_patch = force / pressure`` at nominal pressures ``p``.  The interface
    stiffness per unit area ``k_n / A_patch`` is intensive, so it is
    interpolated (log-log) at the macroscale pressure ``p = N / A_apparent``
    and multiplied by ``A_apparent``; the MDR rule ``dk_x / dk_z = G* / E*`` of
    sticking springs (PHYSICS.md section 2) turns it into the tangential
    stiffness.  Pressures outside the tabulated range are refused.

    Parameters
    ----------
    pressure, stiffness, force : array_like
        The table: nominal pressure (Pa), normal stiffness (N/m), normal force (N) of the patch.
    normal_force : float
        Macroscale normal load N (N).
    apparent_area : float
        Apparent contact area (m^2).
    shear_to_normal : float
        G* / E* (dimensionless).

    Returns
    -------
    k_t : float
        Tangential stiffness (N/m).
    source : str
        One line saying how it was obtained.
    """
    p = np.asarray(pressure, float)
    k = np.asarray(stiffness, float)
    area_patch = np.asarray(force, float) / p
    p_macro = normal_force / apparent_area
    if not (p.min() <= p_macro <= p.max()):
        raise ParameterError(
            "[load].normal_force",
            "a nominal pressure N/(apparent_length*apparent_width) within [load].pressures "
            f"[{p.min():g}, {p.max():g}] Pa",
            f"{p_macro:g} Pa",
        )
    order = np.argsort(p)
    k_per_area = np.exp(
        np.interp(np.log(p_macro), np.log(p[order]), np.log((k / area_patch)[order]))
    )
    k_t = float(k_per_area * apparent_area * shear_to_normal)
    return k_t, f"contact stage at p = {p_macro:g} Pa over {apparent_area:g} m^2, times G*/E*"


def apparent_tangential_stiffness(
    pressure, stiffness, force, *, normal_force: float, apparent_area: float, E_star: float,
    shear_to_normal: float,
) -> tuple[float, str, dict[str, float]]:
    """Tangential stiffness (N/m) of the apparent contact: interface and bodies in series.

    The patch table gives the interfacial stiffness per unit area ``K_int`` at
    the macroscale pressure ``N / A`` (log-log interpolation, refused outside
    the table, as :func:`tangential_stiffness_from_table`); the apparent
    contact is ``K_int A`` in series with the bonded punch ``2 E* sqrt(A/pi)``
    (:func:`tribolmp.models.bridges.apparent_contact_stiffness`, PHYSICS.md
    section 8), so it never exceeds the punch.  The MDR rule ``dk_x/dk_z =
    G*/E*`` of sticking springs scales both terms of the series alike.

    Returns
    -------
    k_t : float
        Tangential stiffness (N/m).
    source : str
        One line saying how it was obtained.
    extra : dict
        ``normal`` (N/m), ``bound`` (N/m, the bonded punch), ``k_int_per_area`` (N/m^3),
        ``interface_share`` (fraction of the compliance in the interface).
    """
    from ..bridges import apparent_contact_stiffness, interfacial_stiffness_per_area

    p = np.asarray(pressure, float)
    area_patch = float(np.asarray(force, float)[0] / p[0])
    p_macro = normal_force / apparent_area
    kpa = interfacial_stiffness_per_area(p, np.asarray(stiffness, float), area_patch, p_macro)
    app = apparent_contact_stiffness(kpa, apparent_area, E_star)
    extra = {"normal": float(app["stiffness"]), "bound": float(app["bound"]),
             "k_int_per_area": float(kpa), "interface_share": float(app["interface_share"])}
    src = (f"interfacial stiffness at p = {p_macro:g} Pa x {apparent_area:g} m^2 in series with "
           "the bonded punch 2E*sqrt(A/pi), times G*/E*")
    return float(app["stiffness"] * shear_to_normal), src, extra
