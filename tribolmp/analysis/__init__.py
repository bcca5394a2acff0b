"""Analysis of MCA (LAMMPS) friction runs with MDAnalysis, and the rates they yield.

Modules (imported explicitly; importing this package loads nothing heavy):

* :mod:`~tribolmp.analysis.outputs` -- the output-directory contract
  (``meta.json``, ``friction.csv``, ``traj.lammpstrj``) and the unit boundary
  (dump nm / nm/ns -> SI, real time axis);
* :mod:`~tribolmp.analysis.friction` -- :class:`FrictionCoefficient` (mu(t),
  steady state by MSER, error bar by blocking);
* :mod:`~tribolmp.analysis.profiles` -- :class:`VelocityProfile` (sheared
  layer depth) and :class:`CompositionProfile` (mixing, penetration);
* :mod:`~tribolmp.analysis.diffusion` -- :class:`LateralDiffusion`;
* :mod:`~tribolmp.analysis.transfer` -- :class:`BondTurnover` and
  :class:`MassTransfer` (transfer, wear, detachment, reattachment);
* :mod:`~tribolmp.analysis.rates` -- :func:`compute_rates` -> ``rates.json``;
* :mod:`~tribolmp.analysis.plots` -- mu(t), Fig. 9-like snapshot, profiles;
* :mod:`~tribolmp.analysis.stats` -- MSER, blocking, isotonic fit, FFT MSD;
* :mod:`~tribolmp.analysis.synthetic` -- synthetic output directories with
  known answers (the references of the tests).

The trajectory analyses are MDAnalysis ``AnalysisBase`` subclasses:
construct with ``(universe, meta)`` or ``Class.from_output(out_dir)``, then
``.run(start=, stop=, step=, frames=)`` and read ``.results``.
"""


def read_atoms(dump, index=-1, *, meta=None):
    """Frames of an MCA dump as ASE ``Atoms`` in ASE units.

    See :func:`tribolmp.analysis.handoff.read_atoms`.
    """
    from .handoff import read_atoms as _read_atoms

    return _read_atoms(dump, index, meta=meta)
