"""The seed's Eq. 13 pair law between surface elements, for normal (squeeze) motion only.

Two surface elements dA, dA' at distance r interact through a central dashpot

    dF = (6 eta R / pi) v_n / r^4 dA dA' ,

with v_n the rate at which they approach along the line joining them and R
the curvature radius of the particle.  Integrated over a sphere of radius R
and a plane it gives 6 pi eta R^2 V / h0 / (1 + h0/2R): the corrected squeeze
damper (PHYSICS.md section 1), *not* the seed's Eq. 11.  It is wrong for
tangential motion (it gives ~R^2/h0 instead of ~R ln(R/h0)), so only the
normal component is provided here.

The discrete sum is accurate only if every element is at most half as large
as its distance to the other body; :func:`check_element_size` refuses
coarser meshes and :func:`sphere_plane_rings` refines them automatically.

The quadrature for a sphere above a plane uses coaxial rings whose azimuthal
integral is done in closed form,

    int_0^2pi dphi / (A - B cos phi)^3 = pi (2A^2 + B^2) / (A^2 - B^2)^(5/2),

so only the radial direction is discretised, with ring widths graded to a
fixed fraction of the local gap.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...errors import ParameterError
from ..base import Result, check_positive, check_range, timed

__all__ = [
    "pair_forces",
    "check_element_size",
    "sphere_plane_rings",
    "ring_squeeze_force",
    "sphere_plane_pair_force",
    "pairlaw_sphere_plane_exact",
    "MAX_ELEMENT_RATIO",
]

#: Largest allowed element size as a fraction of the local gap.
MAX_ELEMENT_RATIO = 0.5


def check_element_size(size, gap, *, what: str = "element size") -> None:
    """Refuse elements larger than half the local gap (ParameterError, one line).

    Parameters
    ----------
    size : float or ndarray
        Element sizes in m (sqrt of the area, or the ring width).
    gap : float or ndarray
        Distance of each element to the other body in m.
    """
    size = np.asarray(size, dtype=float)
    gap = np.asarray(gap, dtype=float)
    ratio = size / gap
    worst = int(np.argmax(ratio)) if ratio.ndim else 0
    r = float(ratio.ravel()[worst]) if ratio.ndim else float(ratio)
    if not r <= MAX_ELEMENT_RATIO:
        g = float(np.broadcast_to(gap, ratio.shape).ravel()[worst]) if ratio.ndim else float(gap)
        s = float(np.broadcast_to(size, ratio.shape).ravel()[worst]) if ratio.ndim else float(size)
        raise ParameterError(what, f"<= h/2 = {0.5 * g:.4g} m (refine the mesh)", s)


def pair_forces(pos_a, area_a, vel_a, pos_b, area_b, vel_b, viscosity, radius, *, chunk=2048):
    """Pair-law forces (N) on elements ``a`` from all elements ``b`` (Eq. 13, central).

    Parameters
    ----------
    pos_a, pos_b : ndarray, shape (N, 3), (M, 3)
        Element centres in m.
    area_a, area_b : ndarray, shape (N,), (M,)
        Element areas in m^2.
    vel_a, vel_b : ndarray, shape (N, 3) or (3,), (M, 3) or (3,)
        Element velocities in m/s.
    viscosity : float
        eta in Pa s.
    radius : float
        Curvature radius R of the particle (m) in the prefactor 6 eta R / pi.
    chunk : int
        Rows of ``a`` processed at once (memory bound).

    Returns
    -------
    ndarray, shape (N, 3)
        Force on each element of ``a``; repulsive while the elements approach.

    Notes
    -----
    Valid for the normal (squeeze) part only; elements must satisfy
    :func:`check_element_size` against the other body.
    """
    pos_a, pos_b = np.atleast_2d(np.asarray(pos_a, float)), np.atleast_2d(np.asarray(pos_b, float))
    area_a, area_b = np.asarray(area_a, float), np.asarray(area_b, float)
    vel_a = np.broadcast_to(vel_a, pos_a.shape)
    vel_b = np.broadcast_to(vel_b, pos_b.shape)
    pref = 6.0 * viscosity * radius / math.pi
    out = np.empty_like(pos_a, dtype=float)
    for s in range(0, pos_a.shape[0], chunk):
        d = pos_a[s : s + chunk, None, :] - pos_b[None, :, :]
        r2 = np.sum(d * d, axis=2)
        dv = vel_a[s : s + chunk, None, :] - vel_b[None, :, :]
        # approach rate along the joining line: -(dv . d)/r
        vn_over_r = -np.sum(dv * d, axis=2) / r2
        w = pref * vn_over_r / (r2 * r2) * area_b[None, :]  # force = w * d  (d/r * vn / r^4)
        out[s : s + chunk] = np.einsum("ij,ijk->ik", w, d) * np.asarray(area_a)[s : s + chunk, None]
    return out


@dataclass(frozen=True)
class Rings:
    """Coaxial ring mesh: radii (m), heights (m), areas (m^2), widths (m), gaps (m)."""

    r: np.ndarray
    z: np.ndarray
    area: np.ndarray
    width: np.ndarray
    gap: np.ndarray


def sphere_plane_rings(radius, gap, *, refine=0.25, plane_extent=30.0, max_rings=200_000):
    """Graded ring meshes of a sphere (radius R, lowest point at height h0) and a plane z = 0.

    Ring widths are ``refine`` times the distance of the ring to the other body,
    so the mesh satisfies the element-size rule for ``refine <= 0.5``.

    Parameters
    ----------
    radius, gap : float
        R and h0 in m.
    refine : float
        Width / local gap (<= 0.5).
    plane_extent : float
        Plane radius in units of R (truncation error ~ (R/extent)^4).
    max_rings : int
        Refuse meshes larger than this (ParameterError).

    Returns
    -------
    (Rings, Rings)
        Sphere rings and plane rings.
    """
    R, h0 = float(radius), float(gap)

    def grade(dist, s_end):
        # march s (arc length) with ds = refine * dist(s); midpoints carry the rings
        edges = [0.0]
        s = 0.0
        while s < s_end:
            ds = refine * dist(s)
            # a step never more than refine times the gap at its far end either
            ds = min(ds, refine * dist(min(s + ds, s_end)))
            s = min(s + ds, s_end)
            edges.append(s)
            if len(edges) > max_rings:
                raise ParameterError(
                    "refine",
                    f"a mesh of <= {max_rings} rings (h/R = {h0 / R:.3g} too small for refine)",
                    refine,
                )
        return np.asarray(edges)

    # sphere: arc length s = R theta from the lowest point; height z = h0 + R (1 - cos theta)
    es = grade(lambda s: h0 + R * (1.0 - math.cos(s / R)), math.pi * R)
    th0, th1 = es[:-1] / R, es[1:] / R
    thm = 0.5 * (th0 + th1)
    sphere = Rings(
        r=R * np.sin(thm),
        z=h0 + R * (1.0 - np.cos(thm)),
        area=2.0 * math.pi * R * R * (np.cos(th0) - np.cos(th1)),
        width=np.diff(es),
        gap=h0 + R * (1.0 - np.cos(thm)),
    )
    # plane: distance of a plane point at radius b to the sphere surface
    ep = grade(lambda b: math.hypot(b, R + h0) - R, plane_extent * R)
    b0, b1 = ep[:-1], ep[1:]
    bm = 0.5 * (b0 + b1)
    plane = Rings(
        r=bm,
        z=np.zeros_like(bm),
        area=math.pi * (b1 * b1 - b0 * b0),
        width=np.diff(ep),
        gap=np.hypot(bm, R + h0) - R,
    )
    return sphere, plane


def ring_squeeze_force(sphere: Rings, plane: Rings, viscosity, radius, velocity, *, chunk=1024):
    """Return the normal pair-law force (N) between coaxial ring meshes, exact in azimuth.

    The sphere moves towards the plane at ``velocity`` (m/s); each sphere
    element at height z sees a plane element at horizontal distance rho with
    approach rate V z / r, and the z-component of the central force is
    (6 eta R / pi) V z^2 / r^6 dA dA'.
    """
    pref = 6.0 * viscosity * radius / math.pi * velocity
    total = 0.0
    for s in range(0, sphere.r.size, chunk):
        a = sphere.r[s : s + chunk, None]
        z = sphere.z[s : s + chunk, None]
        A = a * a + plane.r[None, :] ** 2 + z * z
        B = 2.0 * a * plane.r[None, :]
        # (1/2pi) int dphi / (A - B cos)^3 = (2A^2 + B^2) / (2 (A^2 - B^2)^(5/2))
        AmB = (A - B) * (A + B)
        kern = (2.0 * A * A + B * B) / (2.0 * AmB * AmB * np.sqrt(AmB))
        total += float(np.sum(sphere.area[s : s + chunk] * (z[:, 0] ** 2) * (kern @ plane.area)))
    return pref * total


def pairlaw_sphere_plane_exact(radius, viscosity, gap, velocity):
    """Exact integral of the pair law over a whole sphere and an infinite plane (N).

    ``6 pi eta R^2 V / h0 * 1 / (1 + h0 / 2R)`` (each sphere element at height z
    receives 3 eta R V / z^2 from the plane, and dA = 2 pi R dz on a sphere).
    """
    return 6.0 * math.pi * viscosity * radius**2 * velocity / gap / (1.0 + gap / (2.0 * radius))


def sphere_plane_pair_force(
    radius, viscosity, gap, velocity, *, refine=0.25, plane_extent=30.0, max_pairs=4e8
) -> Result:
    """Pair-law squeeze force of a sphere above a plane by ring quadrature.

    Parameters
    ----------
    radius, viscosity, gap, velocity : float
        R (m), eta (Pa s), h0 (m), approach speed V (m/s).
    refine : float
        Ring width / local gap; must be <= 0.5 (element-size rule).
    plane_extent : float
        Plane radius in units of R.
    max_pairs : float
        Refuse (ParameterError) quadratures with more ring pairs (cost ~ R/h).

    Returns
    -------
    Result
        ``force`` (N), ``exact`` (N, :func:`pairlaw_sphere_plane_exact`),
        ``rel_error``, ``rings`` (number of sphere + plane rings), ``time_s``.
    """
    check_positive("radius", radius, "m")
    check_positive("viscosity", viscosity, "Pa s")
    check_positive("gap", gap, "m")
    check_range("velocity", velocity, unit="m/s")
    check_range("refine", refine, 0.0, MAX_ELEMENT_RATIO, lo_open=True)
    res = Result(method="pairlaw-rings")
    with timed(res):
        sphere, plane = sphere_plane_rings(radius, gap, refine=refine, plane_extent=plane_extent)
        pairs = sphere.r.size * plane.r.size
        if pairs > max_pairs:
            raise ParameterError(
                "gap",
                f"h/R large enough for <= {max_pairs:.0e} ring "
                f"pairs at refine={refine:g} (needs {pairs:.1e})",
                gap,
            )
        check_element_size(sphere.width, sphere.gap, what="sphere ring width")
        check_element_size(plane.width, plane.gap, what="plane ring width")
        force = ring_squeeze_force(sphere, plane, viscosity, radius, velocity)
    exact = pairlaw_sphere_plane_exact(radius, viscosity, gap, velocity)
    res.update(
        force=force,
        exact=exact,
        rel_error=force / exact - 1.0 if exact else 0.0,
        rings=int(sphere.r.size + plane.r.size),
        units={"force": "N", "exact": "N"},
    )
    return res
