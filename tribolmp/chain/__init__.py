"""The multiscale chain: planner, stage cache, stages and report.

One scene goes through up to six stages, each scale feeding the next with
explicit hand-off files in SI units::

    nanoscale (LAMMPS MCA) --rates.json--> topography (Eq. 23) --height map-->
    contact (MDR / BEM) --stiffness--> macroscale (stick-slip), tribospectroscopy (F^2(a));
    lubrication wherever the scene has a [lubricant].

>>> from tribolmp.scene import default_scene
>>> from tribolmp.chain import plan_scene
>>> [s.name for s in plan_scene(default_scene()).stages][:2]
['nanoscale', 'topography']
"""

from .planner import STAGES, Plan, StagePlan, choose_contact_method, plan_scene

__all__ = ["STAGES", "Plan", "StagePlan", "plan_scene", "choose_contact_method", "run_chain"]


def run_chain(*args, **kwargs):
    """Run a scene through the chain; see :func:`tribolmp.chain.runner.run_chain`."""
    from .runner import run_chain as _run

    return _run(*args, **kwargs)
