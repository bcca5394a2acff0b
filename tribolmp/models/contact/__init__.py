"""Contact mechanics: MDR (normal, tangential, adhesive, rough) and a 3D half-space BEM.

Modules
-------
``reference``
    Analytic Hertz, cone, flat punch, power law, JKR and Mindlin solutions.
``mdr``
    The Method of Dimensionality Reduction for axisymmetric and 1D profiles.
``rough``
    1D MDR profiles of rough surfaces (from a PSD or a height map) and
    ensemble stiffness-force-approach curves.
``bem``
    FFT + constrained conjugate gradient half-space solver (periodic and
    zero-padded), the 3D reference.
``solve``
    Parameter dataclasses, the method registry and the scene adapter.
``interfacial``
    Periodic-BEM interfacial stiffness per unit area (contract C5).
``choice``
    The measured speed-error table and the method choice behind ``"auto"``.

Everything is pure numpy/scipy and in SI units.
"""

from __future__ import annotations

from .choice import choose_method
from .interfacial import interfacial_stiffness
from .mdr import TangentialMDR, axisymmetric_profile, normal_force
from .solve import (
    AxisymmetricParams,
    RoughParams,
    params_from_scene,
    rough_params_from_scene,
    solve,
    solve_rough,
    stiffness_vs_pressure,
)

__all__ = [
    "axisymmetric_profile",
    "normal_force",
    "TangentialMDR",
    "AxisymmetricParams",
    "RoughParams",
    "params_from_scene",
    "rough_params_from_scene",
    "solve",
    "solve_rough",
    "stiffness_vs_pressure",
    "interfacial_stiffness",
    "choose_method",
]
