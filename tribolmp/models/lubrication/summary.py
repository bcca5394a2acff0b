"""Lubrication summary of a scene, for the multiscale chain (SI units)."""

from __future__ import annotations

import numpy as np

from ..base import Result, timed
from . import reduced
from .reference import brenner_force, damper_coefficient

__all__ = ["lubrication_summary"]


def lubrication_summary(scene, *, gaps_over_radius=None, reynolds_cells: int = 400) -> Result:
    """Damper coefficient, squeeze force against gap and the reduced models' errors.

    Parameters
    ----------
    scene : tribolmp.scene.Scene
        Needs ``[lubricant]``; the sphere radius is ``[geometry].radius``.
    gaps_over_radius : sequence of float, optional
        h/R values of the curve (default 1e-4 ... 0.3, 9 points, plus the
        scene's film thickness).
    reynolds_cells : int
        Mesh of the Reynolds reference.

    Returns
    -------
    Result
        ``alpha`` (N s, 6 pi eta R^2), ``gap`` (m), ``force_damper``,
        ``force_reynolds`` and (Newtonian) ``force_brenner`` (N, at the
        scene's approach speed ``velocity``), ``error_damper_vs_stokes`` (relative:
        **the damper's error**, against Brenner's exact Stokes series, Newtonian
        only), ``reynolds_grid_error`` = ``error_damper_vs_reynolds`` (relative: the
        damper *is* the exact thin-film solution of the paraboloid gap, so this
        difference is the numerical Reynolds solve's grid and truncation error,
        the same at every h/R because the problem is self-similar; it says
        nothing about the damper), ``reynolds_truncation_error`` (share
        of the infinite-domain force outside the Reynolds mesh: part of the
        damper-vs-Reynolds difference for power-law fluids), ``power_law_index``.
        For a power-law fluid ``force_damper`` is the closed-form power-law force
        and ``alpha`` refers to the Newtonian ``viscosity``.
    """
    p = reduced.params_from_scene(scene)
    p = reduced.Params(**{**p.__dict__, "reynolds_cells": reynolds_cells})
    eps = (
        np.geomspace(1e-4, 0.3, 9)
        if gaps_over_radius is None
        else np.asarray(gaps_over_radius, float)
    )
    eps = np.unique(np.append(eps, p.gap / p.radius))
    res = Result(method="lubrication-summary")
    with timed(res):
        gaps = eps * p.radius
        fd, fr, fb, tr = [], [], [], []
        for h in gaps:
            ph = reduced.with_gap(p, float(h))
            fd.append(reduced.squeeze_force(ph, "damper").force)
            rey = reduced.squeeze_force(ph, "reynolds")
            fr.append(rey.force)
            tr.append(rey.truncation_error)
            if p.newtonian:
                fb.append(
                    float(brenner_force(p.radius, p.viscosity, float(h), p.approach_velocity))
                )
        fd, fr = np.array(fd), np.array(fr)
        res.update(
            alpha=damper_coefficient(p.radius, p.viscosity),
            radius=p.radius,
            velocity=p.approach_velocity,
            power_law_index=p.power_law_index,
            gap=gaps,
            gap_over_radius=eps,
            force_damper=fd,
            force_reynolds=fr,
            # kept for the JSON contract; = reynolds_grid_error
            error_damper_vs_reynolds=fd / fr - 1.0,
            reynolds_grid_error=fd / fr - 1.0,
            reynolds_truncation_error=np.array(tr),
        )
        if p.newtonian:
            fb = np.array(fb)
            res.update(force_brenner=fb, error_damper_vs_stokes=fd / fb - 1.0)
    res["units"] = {
        "alpha": "N s", "radius": "m", "velocity": "m/s", "gap": "m", "force_damper": "N",
        "force_reynolds": "N", "force_brenner": "N",
    }
    res["message"] = (
        f"damper alpha = {res['alpha']:.4g} N s; Reynolds reference with {reynolds_cells} cells"
    )
    return res
