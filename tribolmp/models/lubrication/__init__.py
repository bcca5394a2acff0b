"""Lubrication models (SI units).

Reduced squeeze/sliding forces, the Eq. 13 pair law, a Reynolds reference,
film dynamics, mixed lubrication and lubricated polishing.

Modules: :mod:`.reference` (exact/asymptotic forces), :mod:`.reduced` (named
reduced models, ``Params``, ``solve``, ``squeeze_damper_force``,
``params_from_scene``), :mod:`.pairlaw`, :mod:`.reynolds`, :mod:`.dynamics`,
:mod:`.polishing`, :mod:`.summary`.
"""

from .reduced import Params, params_from_scene, solve, squeeze_damper_force
from .summary import lubrication_summary

__all__ = ["Params", "params_from_scene", "solve", "squeeze_damper_force", "lubrication_summary"]
