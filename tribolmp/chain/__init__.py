"""The multiscale chain: stages (one file each), their registry, planner, runner, cache and report.

One scene goes through up to six stages, each scale feeding the next with
typed hand-off files in SI units::

    nanoscale (LAMMPS MCA) --rates--> topography (Eq. 23) --surface-->
    contact (MDR / BEM) --stiffness--> macroscale (stick-slip), tribospectroscopy (F^2(a));
    lubrication wherever the scene has a [lubricant].

The stage contract is :mod:`tribolmp.chain.stage`; the order is
:mod:`tribolmp.chain.registry`.

>>> from tribolmp.scene import default_scene
>>> from tribolmp.chain import plan_scene
>>> [s.name for s in plan_scene(default_scene()).stages][:2]
['nanoscale', 'topography']
"""

from .planner import STAGES, Plan, StagePlan, choose_contact_method, plan_scene
from .registry import REGISTRY, Registry
from .runner import run_chain

__all__ = [
    "STAGES",
    "REGISTRY",
    "Registry",
    "Plan",
    "StagePlan",
    "plan_scene",
    "choose_contact_method",
    "run_chain",
]
