"""Unit system of tribolmp.

tribolmp works in SI throughout (m, kg, s, N, Pa, J, Pa s).  The only place
where other units appear is the boundary to LAMMPS, which the MCA decks run in
``units nano``: lengths in nm, times in ns, masses in attograms.  Conversions
happen only in :mod:`tribolmp.lammps`, through :data:`LAMMPS_NANO`.

In ``units nano`` a velocity of 1 nm/ns equals 1 m/s, a force unit is
1 ag nm/ns^2 = 1e-12 N and a pressure unit is 1 ag/(nm ns^2) = 1e6 Pa.
"""

from __future__ import annotations

from types import MappingProxyType

__all__ = ["LAMMPS_NANO", "to_lammps", "from_lammps", "GPa", "MPa", "nm", "um", "ns"]

GPa = 1e9
MPa = 1e6
nm = 1e-9
um = 1e-6
ns = 1e-9

#: SI value of one LAMMPS ``units nano`` unit, per quantity.
LAMMPS_NANO = MappingProxyType(
    {
        "length": 1e-9,  # nm
        "time": 1e-9,  # ns
        "mass": 1e-21,  # attogram
        "velocity": 1.0,  # nm/ns
        "force": 1e-12,  # ag nm / ns^2
        "energy": 1e-21,  # ag nm^2 / ns^2
        "pressure": 1e6,  # ag / (nm ns^2)
        "density": 1e6,  # ag / nm^3
        "stiffness": 1e-3,  # force/length: 1e-12 N / 1e-9 m
        "viscosity": 1e-3,  # pressure*time: 1e6 Pa * 1e-9 s
        "damping": 1e-12,  # force/velocity: ag/ns
        "diffusion": 1e-9,  # nm^2/ns
    }
)


def to_lammps(value, quantity: str):
    """Convert an SI value to LAMMPS ``units nano``.

    Parameters
    ----------
    value : float or ndarray
        Value in SI units.
    quantity : str
        A key of :data:`LAMMPS_NANO`.

    Returns
    -------
    float or ndarray
        The value in LAMMPS nano units.
    """
    return value / LAMMPS_NANO[quantity]


def from_lammps(value, quantity: str):
    """Convert a LAMMPS ``units nano`` value to SI (inverse of :func:`to_lammps`)."""
    return value * LAMMPS_NANO[quantity]
