"""Surface topography by the stochastic diffusion-wear equation (Eq. 23 of the seed).

Public API (the cross-model contract):

* :class:`TopographyParams` -- grid, rates, time stepping (SI);
* :func:`evolve` / :func:`solve` -- exact Ornstein-Uhlenbeck or Euler-Maruyama
  integration returning a :class:`~tribolmp.models.base.Result` with ``h``,
  ``k``, ``psd``, ``psd_theory``;
* :func:`params_from_rates` / :func:`params_from_scene` -- parameters from the
  nanoscale model's rates or a scene;
* :mod:`.spectra` -- analytic spectra, PSD estimators, roughness, Hurst fit;
* :func:`save_height_map` / :func:`load_height_map` / :func:`save_ascii_grid`.

Pure numpy: nothing heavy is imported.
"""

from .io import load_height_map, save_ascii_grid, save_height_map
from .rates import params_from_rates, params_from_scene
from .spde import (
    SCHEMES,
    TopographyParams,
    euler_dt_limit,
    evolve,
    expected_periodogram,
    make_stepper,
    solve,
)

Params = TopographyParams

__all__ = [
    "TopographyParams",
    "Params",
    "SCHEMES",
    "evolve",
    "solve",
    "euler_dt_limit",
    "expected_periodogram",
    "make_stepper",
    "params_from_rates",
    "params_from_scene",
    "save_height_map",
    "load_height_map",
    "save_ascii_grid",
]
