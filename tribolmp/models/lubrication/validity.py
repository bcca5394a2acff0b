"""Where the continuum film models stop being physics.

The reduced forces (damper, Cox–Brenner, Reynolds) treat the lubricant as a
continuum.  A film only a few molecules thick is layered (solvation forces,
a viscosity that grows by orders of magnitude), and below one molecular
diameter there is no film at all, only the solids' contact.  The models
themselves stay scale-free mathematics (their tests use h/R down to 1e-12),
so the check lives here and the command line and the chain apply it to the
user's physical input.

References
----------
Israelachvili, J. N. *Intermolecular and Surface Forces*, 3rd ed., ch. 15
(solvation forces and layering within ~5-10 molecular diameters).
"""

from __future__ import annotations

from ...errors import ParameterError

__all__ = ["MOLECULAR_SIZE_M", "CONTINUUM_DOUBTFUL_M", "check_film_gap"]

#: Diameter of a small lubricant molecule (water 0.28 nm, hexadecane ~0.45 nm across the chain).
MOLECULAR_SIZE_M = 0.5e-9
#: Below ~10 molecular diameters layering makes the continuum viscosity doubtful.
CONTINUUM_DOUBTFUL_M = 10 * MOLECULAR_SIZE_M


def check_film_gap(gap_m: float, field: str = "gap") -> list[str]:
    """Refuse a gap below one molecular size; warn where the continuum is doubtful.

    Parameters
    ----------
    gap_m : float
        Film thickness (m).
    field : str
        The option or key it came from, for the message.

    Returns
    -------
    list of str
        Warning lines (empty when the continuum models apply).

    Raises
    ------
    ParameterError
        ``gap_m`` below :data:`MOLECULAR_SIZE_M`: no continuum film exists there.
    """
    if not gap_m >= MOLECULAR_SIZE_M:
        raise ParameterError(
            field,
            f"a film gap >= {MOLECULAR_SIZE_M:.1e} m (one molecular size; below it there is "
            "no continuum film, only solid contact)",
            gap_m,
        )
    if gap_m < CONTINUUM_DOUBTFUL_M:
        return [
            f"{field} = {gap_m:.3g} m is below {CONTINUUM_DOUBTFUL_M:.0e} m (~10 molecular sizes): "
            "layering makes the continuum film force doubtful"
        ]
    return []
