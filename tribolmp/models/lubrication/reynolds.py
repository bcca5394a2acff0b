"""Reference Reynolds solver for the squeeze film between a sphere and a plane (SI).

The thin-film (Reynolds) equation for a gap h(x, y) that closes at the
approach speed V = -dh/dt reads, for a power-law fluid tau = K |g|^(n-1) g,

    -div( Phi(h, |grad p|) grad p / |grad p| ) = V ,      p = 0 on the outer boundary,

where Phi is the slot flux of :func:`~.reference.power_law_slot_flux`
(Phi = h^3 |grad p| / (12 eta) for n = 1).  The equation is the
Euler-Lagrange equation of the convex functional

    E[p] = int Psi(h, |grad p|) dA - int V p dA,   Psi(h, G) = int_0^G Phi(h, s) ds,

so it is discretised with piecewise-linear pressure on a graded mesh
(vertex-centred finite volumes: on a rectangle grid cut into triangles, the
n = 1 case gives the classical five-point stencil) and the *nonlinear*
power-law problem is solved by Newton's method on E with the exact Hessian
and a backtracking line search.  Convexity makes this globally convergent.
The start is the Newtonian solution scaled by the exact minimising factor of
E along it (E is homogeneous of degree 1 + 1/n in p).

Two geometries (``method``):

``"axisymmetric"``
    1D in r with the area weight 2 pi r; outer radius r_max.
``"xy"``
    2D Cartesian square [-L, L]^2 (tensor grid, each rectangle cut into two
    triangles); checks the axisymmetric reduction and carries any h(x, y).

The mesh is graded as x = r_c sinh(xi) with r_c = sqrt(2 R h0) the Reynolds
contact radius and xi uniform, so the resolution near the gap minimum scales
with the number of cells and the domain can be many r_c wide at log cost.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from ...errors import ConvergenceError, ParameterError
from ...params import param, renamed, validate_dataclass
from ..base import MethodRegistry, Result, timed

__all__ = [
    "ReynoldsParams",
    "REYNOLDS",
    "solve",
    "graded_nodes",
    "quadrature_force",
    "quadrature_force_many",
]

REYNOLDS = MethodRegistry("reynolds")


# ``velocity`` kept: CLI --velocity (errors name it as given), docs/conventions.md
@renamed(velocity="approach_velocity")
@dataclass(frozen=True)
class ReynoldsParams:
    """Parameters of a Reynolds squeeze-film solve (SI units).

    Attributes
    ----------
    radius : float
        Sphere radius R in m.
    gap : float
        Minimum gap h0 in m.
    approach_velocity : float
        Approach speed V = -dh/dt in m/s (V > 0: the gap closes).
    viscosity : float
        Newtonian viscosity eta in Pa s (used as K when ``consistency`` is None).
    power_law_index : float
        Flow index n > 1/3 (1 = Newtonian).
    consistency : float or None
        Power-law consistency K in Pa s^n.
    cells : int
        Cells per radius (axisymmetric) or per half-side (xy).
    domain : float
        Outer radius / half-width in units of r_c = sqrt(2 R h0).
    gap_shape : str
        ``"paraboloid"`` (h0 + r^2/2R, the lubrication form) or ``"sphere"``
        (exact sphere surface; needs the domain inside r < R).
    sliding_velocity : float
        Speed U (m/s) of the sphere along +x over the fixed plane (``"xy"``,
        Newtonian only); adds the Couette source (U/2) dh/dx and returns the drag.
    tol : float
        Newton stop: squared Newton decrement below tol * |E|.
    max_iter : int
        Maximum Newton iterations.
    """

    radius: float = param(1e-3, unit="m", lo=0.0, lo_open=True, hi=1e3)
    gap: float = param(1e-6, unit="m", lo=0.0, lo_open=True, hi=1e3)
    approach_velocity: float = param(1e-3, unit="m/s", lo=-1e6, hi=1e6)
    viscosity: float = param(0.1, unit="Pa s", lo=0.0, lo_open=True, hi=1e9)
    power_law_index: float = param(1.0, lo=1.0 / 3.0, lo_open=True, hi=5.0)
    consistency: float | None = param(None, unit="Pa s^n", lo=0.0, lo_open=True, hi=1e9)
    cells: int = param(200, lo=4, hi=20_000)
    domain: float = param(30.0, lo=1.0, hi=1e9)
    gap_shape: str = param("paraboloid", choices=("paraboloid", "sphere"))
    sliding_velocity: float = param(0.0, unit="m/s", lo=-1e6, hi=1e6)
    tol: float = param(1e-18, lo=0.0, lo_open=True, hi=1e-3)
    max_iter: int = param(200, lo=1, hi=10_000)

    def __post_init__(self) -> None:
        validate_dataclass(self)
        if self.sliding_velocity != 0.0 and self.power_law_index != 1.0:
            raise ParameterError(
                "sliding_velocity",
                "0 for a power-law fluid (sliding is Newtonian only)",
                self.sliding_velocity,
            )
        if self.gap_shape == "sphere" and self.domain * self.contact_radius >= self.radius:
            raise ParameterError(
                "domain",
                "an outer radius < R for gap_shape='sphere' "
                f"(domain < {self.radius / self.contact_radius:g})",
                self.domain,
            )

    @property
    def contact_radius(self) -> float:
        """Reynolds contact radius r_c = sqrt(2 R h0) in m."""
        return math.sqrt(2.0 * self.radius * self.gap)

    @property
    def K(self) -> float:
        """Consistency K (Pa s^n); the viscosity when not given."""
        return self.viscosity if self.consistency is None else self.consistency


def graded_nodes(cells: int, outer: float, scale: float) -> np.ndarray:
    """Nodes 0 ... outer with x = scale sinh(xi), xi uniform (m)."""
    xi = np.linspace(0.0, math.asinh(outer / scale), cells + 1)
    x = scale * np.sinh(xi)
    x[-1] = outer
    return x


def _gap(p: ReynoldsParams, r: np.ndarray) -> np.ndarray:
    if p.gap_shape == "paraboloid":
        return p.gap + r * r / (2.0 * p.radius)
    # exact sphere: h0 + R - sqrt(R^2 - r^2), written without cancellation
    return p.gap + r * r / (p.radius + np.sqrt(p.radius**2 - r * r))


def _gap_dx(p: ReynoldsParams, x: np.ndarray, r: np.ndarray) -> np.ndarray:
    """dh/dx of the gap (paraboloid: x/R; sphere: x/sqrt(R^2 - r^2))."""
    if p.gap_shape == "paraboloid":
        return x / p.radius
    return x / np.sqrt(p.radius**2 - r * r)


def _mobility(p: ReynoldsParams, h: np.ndarray) -> np.ndarray:
    """a(h) with slot flux Phi = a(h) G^(1/n) (m^(2+1/n) / (Pa^(1/n) s))."""
    n = p.power_law_index
    return (
        n
        / (2.0 * n + 1.0)
        * h ** ((2.0 * n + 1.0) / n)
        * 2.0 ** (-(n + 1.0) / n)
        * p.K ** (-1.0 / n)
    )


class _Energy:
    """Discrete convex functional E(p) = sum_e W_e |B_e p|^s / s - S.p on free nodes."""

    def __init__(self, conn, B, W, S, n_nodes, free, s):
        self.conn, self.B, self.W, self.S = conn, B, W, S  # B: (ne, d, k)
        self.n_nodes, self.free, self.s = n_nodes, free, s
        self.free_index = -np.ones(n_nodes, dtype=int)
        self.free_index[free] = np.arange(free.size)

    def grads(self, p_full):
        return np.matmul(self.B, p_full[self.conn][:, :, None])[:, :, 0]

    def value(self, p_full):
        g = self.grads(p_full)
        G = np.sqrt(np.sum(g * g, axis=1))
        return float(np.sum(self.W * G**self.s) / self.s - self.S @ p_full)

    def grad_hess(self, p_full):
        from scipy import sparse

        s = self.s
        g = self.grads(p_full)
        G2 = np.sum(g * g, axis=1)
        G = np.sqrt(G2)
        # Regularise |g|^(s-2) only where the gradient is ~0 (centre of symmetry);
        # the Hessian stays SPD, so the step is still a descent direction.
        d = g.shape[1]
        if s == 2.0:  # linear (Newtonian) problem: constant Hessian
            c = self.W
            M = np.broadcast_to(np.eye(d), (g.shape[0], d, d))
            flux = self.W[:, None] * g
        else:
            Gr2 = G2 + max((1e-12 * G.max()) ** 2, 1e-300)
            c = self.W * Gr2 ** ((s - 2.0) / 2.0)
            flux = (self.W * G ** (s - 2.0) if s > 2 else c)[:, None] * g
            ghat = g / np.sqrt(Gr2)[:, None]
            M = np.eye(d)[None] + (s - 2.0) * ghat[:, :, None] * ghat[:, None, :]
        local_grad = np.matmul(flux[:, None, :], self.B)[:, 0, :]
        # B^T M B per element with batched matmul (einsum over four operands is slow)
        local_H = c[:, None, None] * np.matmul(self.B.transpose(0, 2, 1), np.matmul(M, self.B))
        grad = np.bincount(self.conn.ravel(), local_grad.ravel(), minlength=self.n_nodes) - self.S
        k = self.conn.shape[1]
        rows = np.repeat(self.conn, k, axis=1).ravel()
        cols = np.tile(self.conn, (1, k)).ravel()
        fi_r, fi_c = self.free_index[rows], self.free_index[cols]
        keep = (fi_r >= 0) & (fi_c >= 0)
        nf = self.free.size
        H = sparse.csc_matrix((local_H.ravel()[keep], (fi_r[keep], fi_c[keep])), shape=(nf, nf))
        return grad[self.free], H


def _newton(energy: _Energy, p0_full, tol, max_iter):
    """Damped Newton on the convex energy; returns (p, iterations, decrement)."""
    from scipy.sparse.linalg import spsolve

    p = p0_full.copy()
    E = energy.value(p)
    dec = math.inf
    for it in range(1, max_iter + 1):
        grad, H = energy.grad_hess(p)
        dp = -spsolve(H, grad, permc_spec="MMD_AT_PLUS_A")  # symmetric ordering
        dec = float(-grad @ dp)
        if not math.isfinite(dec):
            raise ConvergenceError(
                "Reynolds Newton step is not finite (mesh too coarse or parameters extreme)"
            )
        # The decrement ~ 2 (E - E_min); below ~1e-14 |E| it is float round-off.
        if dec <= max(tol, 1e-14) * max(abs(E), 1e-300):
            return p, it, dec
        t = 1.0
        while True:
            trial = p.copy()
            trial[energy.free] += t * dp
            E_new = energy.value(trial)
            if E_new <= E - 1e-4 * t * dec or t < 1e-10:
                break
            t *= 0.5
        if t < 1e-10:  # no more decrease possible at float precision: converged to round-off
            return p, it, dec
        p, E = trial, E_new
    raise ConvergenceError(
        f"Reynolds Newton did not converge in {max_iter} iterations (decrement {dec:.3g})"
    )


def _solve_energy(p: ReynoldsParams, conn, B, area_weights, coeff, S, n_nodes, free):
    """Newtonian start scaled optimally, then Newton for the power-law problem."""
    from scipy.sparse.linalg import spsolve

    n = p.power_law_index
    s = 1.0 + 1.0 / n
    # Newtonian problem with the same K as viscosity: linear, one solve.
    lin = _Energy(conn, B, area_weights * coeff["newton"], S, n_nodes, free, 2.0)
    p_full = np.zeros(n_nodes)
    grad, H = lin.grad_hess(p_full)
    p_full[free] = -spsolve(H, grad, permc_spec="MMD_AT_PLUS_A")
    if n == 1.0:
        return p_full, 1
    energy = _Energy(conn, B, area_weights * coeff["power"], S, n_nodes, free, s)
    # E(c p0) = c^s A - c Bv is minimised by c = (Bv / A)^(1/(s-1)).
    A = energy.value(p_full) + energy.S @ p_full
    Bv = energy.S @ p_full
    if A > 0 and Bv > 0:
        p_full *= (Bv / A) ** (1.0 / (s - 1.0))
    p_full, nit, _ = _newton(energy, p_full, p.tol, p.max_iter)
    return p_full, nit + 1


def _coefficients(p: ReynoldsParams, h: np.ndarray) -> dict[str, np.ndarray]:
    newton = h**3 / (12.0 * p.K)
    return {"newton": newton, "power": newton if p.power_law_index == 1.0 else _mobility(p, h)}


@REYNOLDS.register("axisymmetric")
def _axisymmetric(p: ReynoldsParams) -> Result:
    if p.sliding_velocity != 0.0:
        raise ParameterError(
            "sliding_velocity", "0 for method 'axisymmetric' (use method 'xy')", p.sliding_velocity
        )
    rc = p.contact_radius
    r = graded_nodes(p.cells, p.domain * rc, rc)
    ne = r.size - 1
    conn = np.stack([np.arange(ne), np.arange(1, ne + 1)], axis=1)
    dr = np.diff(r)
    B = np.stack([-1.0 / dr, 1.0 / dr], axis=1)[:, None, :]
    # 2-point Gauss rule for int a(h(r)) 2 pi r dr over each element.
    gq = np.array([0.5 - 0.5 / math.sqrt(3.0), 0.5 + 0.5 / math.sqrt(3.0)])
    coeff = {"newton": np.zeros(ne), "power": np.zeros(ne)}
    for q in gq:
        rq = r[:-1] + q * dr
        cq = _coefficients(p, _gap(p, rq))
        for key in coeff:
            coeff[key] += 0.5 * cq[key] * 2.0 * math.pi * rq * dr
    # Source S_i = int V phi_i 2 pi r dr (exact for hat functions).
    r0, r1 = r[:-1], r[1:]
    left = 2.0 * math.pi * p.approach_velocity * dr * (2.0 * r0 + r1) / 6.0
    right = 2.0 * math.pi * p.approach_velocity * dr * (r0 + 2.0 * r1) / 6.0
    S = np.bincount(conn[:, 0], left, minlength=r.size) + np.bincount(
        conn[:, 1], right, minlength=r.size
    )
    free = np.arange(r.size - 1)  # p(r_max) = 0
    pr, nit = _solve_energy(p, conn, B, np.ones(ne), coeff, S, r.size, free)
    force = float(
        np.sum(math.pi * dr * ((2.0 * r0 + r1) * pr[:-1] + (r0 + 2.0 * r1) * pr[1:]) / 3.0)
    )
    return dict(
        force=force,
        r=r,
        pressure=pr,
        gap=_gap(p, r),
        r_max=float(r[-1]),
        nit=nit,
        units={"force": "N", "r": "m", "pressure": "Pa", "gap": "m", "r_max": "m"},
    )


@REYNOLDS.register("xy")
def _xy(p: ReynoldsParams) -> Result:
    rc = p.contact_radius
    half = graded_nodes(p.cells, p.domain * rc, rc)
    x = np.concatenate([-half[:0:-1], half])
    nx = x.size
    X, Y = np.meshgrid(x, x, indexing="ij")
    idx = np.arange(nx * nx).reshape(nx, nx)
    a, b = idx[:-1, :-1].ravel(), idx[1:, :-1].ravel()
    c, d = idx[1:, 1:].ravel(), idx[:-1, 1:].ravel()
    # Alternate the diagonal (union-jack pattern) so the mesh keeps the 4-fold symmetry.
    ii, jj = np.meshgrid(np.arange(nx - 1), np.arange(nx - 1), indexing="ij")
    flip = ((ii + jj) % 2 == 1).ravel()
    t1 = np.where(flip[:, None], np.stack([a, b, d], 1), np.stack([a, b, c], 1))
    t2 = np.where(flip[:, None], np.stack([b, c, d], 1), np.stack([a, c, d], 1))
    conn = np.concatenate([t1, t2])
    px, py = X.ravel()[conn], Y.ravel()[conn]
    # P1 gradient operator of each triangle.
    det = (px[:, 1] - px[:, 0]) * (py[:, 2] - py[:, 0]) - (px[:, 2] - px[:, 0]) * (
        py[:, 1] - py[:, 0]
    )
    area = 0.5 * np.abs(det)
    B = np.empty((conn.shape[0], 2, 3))
    B[:, 0, :] = (
        np.stack([py[:, 1] - py[:, 2], py[:, 2] - py[:, 0], py[:, 0] - py[:, 1]], 1) / det[:, None]
    )
    B[:, 1, :] = (
        np.stack([px[:, 2] - px[:, 1], px[:, 0] - px[:, 2], px[:, 1] - px[:, 0]], 1) / det[:, None]
    )
    # 3-point (edge-midpoint) rule, exact for quadratics, for int a(h) dA.
    coeff = {"newton": np.zeros(conn.shape[0]), "power": np.zeros(conn.shape[0])}
    S = np.bincount(conn.ravel(), np.repeat(p.approach_velocity * area / 3.0, 3), minlength=nx * nx)
    U = p.sliding_velocity
    mids = []
    for i, j in ((0, 1), (1, 2), (2, 0)):
        mx, my = 0.5 * (px[:, i] + px[:, j]), 0.5 * (py[:, i] + py[:, j])
        mr = np.hypot(mx, my)
        mids.append((i, j, mx, mr))
        cq = _coefficients(p, _gap(p, mr))
        for key in coeff:
            coeff[key] += cq[key] * area / 3.0
        if U != 0.0:
            # Couette source (U/2) dh/dx; hat functions are 1/2 at the edge midpoints
            src = 0.5 * U * _gap_dx(p, mx, mr) * area / 3.0 * 0.5
            S += np.bincount(conn[:, i], src, minlength=nx * nx) + np.bincount(
                conn[:, j], src, minlength=nx * nx
            )
    boundary = np.zeros((nx, nx), dtype=bool)
    boundary[[0, -1], :] = True
    boundary[:, [0, -1]] = True
    free = idx[~boundary]
    pr, nit = _solve_energy(p, conn, B, np.ones(conn.shape[0]), coeff, S, nx * nx, free)
    force = float(np.sum(area * pr[conn].mean(axis=1)))
    drag = 0.0
    if U != 0.0:
        # drag on the sphere = int [eta U / h + (1/2) p dh/dx] dA (Couette shear on the sphere
        # plus the pressure on its tilted surface, after one integration by parts)
        for i, j, mx, mr in mids:
            pm = 0.5 * (pr[conn[:, i]] + pr[conn[:, j]])
            drag += float(
                np.sum(area / 3.0 * (p.viscosity * U / _gap(p, mr) + 0.5 * pm * _gap_dx(p, mx, mr)))
            )
    return dict(
        force=force,
        x=x,
        pressure=pr.reshape(nx, nx),
        half_width=float(x[-1]),
        drag=drag,
        nit=nit,
        units={"force": "N", "x": "m", "pressure": "Pa", "half_width": "m", "drag": "N"},
    )


@functools.lru_cache(maxsize=64)
def _gauss_legendre(n: int):
    x, w = np.polynomial.legendre.leggauss(n)
    return 0.5 * (x + 1.0), 0.5 * w


def quadrature_force(p: ReynoldsParams, nodes: int | None = None):
    """Axisymmetric Reynolds squeeze force (N) by its exact first integral.

    Any gap h(r), Newtonian or power law.

    Mass conservation fixes the radial flux through every circle, q = V r / 2,
    and the slot flux q = a(h) G^(1/n) gives the pressure gradient
    G = -dp/dr = (V r / (2 a(h)))^n exactly; with p(r_max) = 0, integrating
    F = int 2 pi r p dr by parts gives

        F = int_0^r_max pi r^2 (V r / (2 a(h(r))))^n dr

    (6 pi eta V int r^3/h^3 dr for n = 1).  The Reynolds boundary-value
    problem thus reduces to one quadrature, done by Gauss-Legendre in
    xi = asinh(r / r_c) (the mesh grading of the finite-element solver),
    where the integrand is smooth.  ``nodes`` (default ``params.cells``)
    sets the accuracy.  Vectorised over an array ``params.gap`` is not
    supported; see :func:`quadrature_force_many` for batches.
    """
    rc = p.contact_radius
    n_nodes = int(nodes if nodes is not None else p.cells)
    xg, wg = _gauss_legendre(n_nodes)
    xi_max = math.asinh(p.domain)
    xi = xg * xi_max
    r = rc * np.sinh(xi)
    drdxi = rc * np.cosh(xi) * xi_max
    h = _gap(p, r)
    n = p.power_law_index
    a = h**3 / (12.0 * p.K) if n == 1.0 else _mobility(p, h)
    G = (abs(p.approach_velocity) * r / (2.0 * a)) ** n
    return math.copysign(float(np.sum(wg * math.pi * r * r * G * drdxi)), p.approach_velocity)


def quadrature_force_many(
    radius, viscosity, gap, velocity, nodes: int = 16, domain: float = 1000.0
):
    """Batch version of :func:`quadrature_force`.

    Newtonian paraboloid gap; arrays of gap and velocity.

    Returns the squeeze force (N) for every ``gap`` (m) at once: one
    (gaps x nodes) array operation, for benchmarks against the damper on
    equal terms (both vectorised).
    """
    h0 = np.asarray(gap, dtype=float)[..., None]
    xg, wg = _gauss_legendre(int(nodes))
    xi_max = math.asinh(domain)
    rc = np.sqrt(2.0 * radius * h0)
    r = rc * np.sinh(xg * xi_max)
    h = h0 + r * r / (2.0 * radius)
    integrand = r**3 / h**3 * rc * np.cosh(xg * xi_max) * xi_max
    return (
        6.0
        * math.pi
        * viscosity
        * np.asarray(velocity, dtype=float)
        * np.sum(wg * integrand, axis=-1)
    )


@REYNOLDS.register("axisymmetric-quadrature")
def _axisymmetric_quadrature(p: ReynoldsParams) -> Result:
    if p.sliding_velocity != 0.0:
        raise ParameterError(
            "sliding_velocity",
            "0 for method 'axisymmetric-quadrature' (use method 'xy')",
            p.sliding_velocity,
        )
    return dict(
        force=quadrature_force(p),
        r_max=p.domain * p.contact_radius,
        nit=1,
        units={"force": "N", "r_max": "m"},
    )


def solve(params: ReynoldsParams, *, method: str = "axisymmetric", rng=None) -> Result:
    """Solve the squeeze-film Reynolds equation and return the force on the sphere.

    Parameters
    ----------
    params : ReynoldsParams
        Geometry, fluid and mesh.
    method : {"axisymmetric", "axisymmetric-quadrature", "xy"}
        ``axisymmetric``: finite elements on a graded radial mesh (Newton for
        power laws); ``axisymmetric-quadrature``: the exact first integral of
        the axisymmetric problem by Gauss-Legendre with ``cells`` nodes (the
        fast solve; any gap shape, Newtonian or power law); ``xy``: 2D.
    rng : ignored
        Deterministic solver; accepted for the common model signature.

    Returns
    -------
    Result
        ``force`` (N, opposing approach), pressure field (Pa) and its mesh,
        ``nit`` (Newton iterations), ``time_s``, ``cells``.
    """
    impl = REYNOLDS.get(method)
    res = Result(method=method)
    with timed(res):
        res.update(impl(params))
    res["cells"] = params.cells
    res["message"] = f"Reynolds {method}: {res['nit']} iteration(s)"
    return res
