"""Driver of the MCA friction experiment on LAMMPS, one module per job.

* :mod:`.params` -- :class:`MCAParams` (SI, defaults shared with the scene), :data:`PRESETS`,
  :func:`preset_params`, :func:`params_from_scene`;
* :mod:`.deck` -- :func:`deck_variables`: SI -> ``-var`` values of ``mca_friction.in``
  (conversions through :mod:`tribolmp.units`);
* :mod:`.prepare` -- the system (ASE, :mod:`tribolmp.lammps.build`), ``system.data``, ``meta.json``;
* :mod:`.restart` -- atomic restart files and outputs, resume and repair of a folder;
* :mod:`.faults` -- LAMMPS failures as one-line errors naming step and cause;
* :mod:`.runner` -- the run loop in chunks of one restart interval;
* :mod:`.mpi` -- the relaunch under the mpich wheel's ``mpiexec``;
* :mod:`.rates` -- the call into :mod:`tribolmp.analysis.rates`;
* :mod:`.driver` -- :func:`run_mca`, which composes them.

The interaction laws come from :mod:`tribolmp.lammps.laws` (one registry).

Output directory contract (read by :mod:`tribolmp.analysis`):
``traj.lammpstrj`` (``id mol type x y z vx vy vz radius c_nbond``, LAMMPS nano
units), ``friction.csv`` (``time_s,friction_N,normal_N,top_x_m``, SI),
``run.log``, ``restart.<step>.bin``, ``meta.json``, ``rates.json`` and
``profile.npz`` (written by :mod:`tribolmp.analysis.rates`).
"""

from .deck import deck_variables
from .driver import run_mca
from .faults import classify
from .mpi import main
from .params import PRESETS, MCAParams, params_from_scene, preset_params
from .prepare import MOLECULES
from .restart import restart_files

__all__ = [
    "MOLECULES",
    "PRESETS",
    "MCAParams",
    "classify",
    "deck_variables",
    "main",
    "params_from_scene",
    "preset_params",
    "restart_files",
    "run_mca",
]
