"""Tangential stiffness of the apparent contact from a patch's stiffness-against-pressure table.

The conversion the chain hands the rigid body (moved here from the chain's
glue, unchanged; issue 15 replaces its physics with the interfacial stiffness in
series with the bodies' compliance).
"""

from __future__ import annotations

import numpy as np

from ...errors import ParameterError

__all__ = ["tangential_stiffness_from_table"]


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
