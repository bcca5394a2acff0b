"""Force, contact radius and stiffness of an axisymmetric contact over a range of loads."""

from __future__ import annotations

import dataclasses

import numpy as np

from ..base import Result, timed
from .solve import AxisymmetricParams, solve

__all__ = ["LOAD_FRACTIONS", "axisymmetric_load_sweep"]

#: Loads of the sweep as fractions of the scene's normal force: two decades, log-spaced, so that
#: the stiffness-against-pressure curve spans the power law k ~ F^(1/3) of a Hertzian contact.
LOAD_FRACTIONS = tuple(float(f) for f in np.geomspace(0.01, 1.0, 9))


def axisymmetric_load_sweep(
    params: AxisymmetricParams,
    *,
    method: str = "mdr",
    fractions: tuple[float, ...] = LOAD_FRACTIONS,
) -> Result:
    """Solve the axisymmetric contact at ``fractions`` of ``params.normal_force``.

    Parameters
    ----------
    params : AxisymmetricParams
        The contact at its full load (``normal_force`` in N must be set).
    method : str
        Solver (see :func:`tribolmp.models.contact.solve.solve`).
    fractions : tuple of float
        Load fractions in (0, 1].

    Returns
    -------
    Result
        ``force`` (N), ``contact_radius`` (m), ``indentation`` (m), ``pressure``
        (mean contact pressure F / (pi a^2), Pa), ``stiffness`` (N/m, when the
        solver gives it) and ``springs`` (MDR springs of the full-load solve).
    """
    from ...errors import ParameterError

    if params.normal_force is None:
        raise ParameterError(
            "[load].normal_force", "a value > 0 N for a stiffness-vs-load curve", None
        )
    res = Result(method=method)
    with timed(res):
        loads = params.normal_force * np.asarray(fractions, float)
        rows = [
            solve(dataclasses.replace(params, normal_force=float(F)), method=method) for F in loads
        ]
        res["force"] = np.array([r.force for r in rows])
        res["contact_radius"] = np.array([r.contact_radius for r in rows])
        res["indentation"] = np.array([r.indentation for r in rows])
        if all("stiffness" in r for r in rows):
            res["stiffness"] = np.array([r.stiffness for r in rows])
        res["pressure"] = res["force"] / (np.pi * res["contact_radius"] ** 2)
        res["springs"] = int(rows[-1].get("springs", 0)) or None
        res["units"] = {
            "force": "N",
            "contact_radius": "m",
            "indentation": "m",
            "stiffness": "N/m",
            "pressure": "Pa",
        }
        res["message"] = f"{method}: {len(loads)} loads up to {params.normal_force:g} N"
    return res
