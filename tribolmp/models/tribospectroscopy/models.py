"""Forward models of tribospectroscopy: friction force against oscillation amplitude.

The probe of Popov & Starcevic (2005) touches the plate at both ends and its
length oscillates at 60-70 kHz.  Amplitude convention (PHYSICS.md section 5):
the probe length changes by ``dl`` peak to peak, so each end (each contact)
moves with amplitude ``a = dl / 4``; the measured end-face amplitude of the
paper is ``dl / 2 = 2 a`` ("probe" convention).  Every function here takes the
*per-contact* amplitude ``a``; :func:`to_per_contact` converts.

Two models are implemented.

* **Random pinning potential** (Popov & Dudko 2004).  Fast oscillation averages
  a random potential with the arcsine law, i.e. multiplies it by ``J0(k a)`` in
  Fourier space, so ``F^2(a) = 2 int dk/2pi k^2 Phi_U(k) J0^2(k a)``.  For a
  Gaussian correlation ``<U(x)U(0)> = U0^2 exp(-x^2 / 2 lambda^2)`` the shape
  ``G(a/lambda) = F^2(a)/F^2(0)`` drops by 69 % at ``a = lambda`` and then
  decays as ``sqrt(2) / (pi^1.5 a/lambda)``.
* **Contact stiffness / shakedown.**  A contact of tangential stiffness ``k``
  and Coulomb limit ``mu N`` under an oscillation of amplitude ``a`` and a slow
  drift carries the mean force ``mu N - k a`` (shakedown) or, above the
  limit ``a >= mu N / k``, none: ``F_s = 2 mu N max(0, 1 - k a / mu N)`` for
  the two contacts.  The micro-slip version applies the same rule to every MDR
  spring (:func:`microslip_force`).

References
----------
Popov VL, Starcevic J. Tech Phys Lett 31 (2005) 309, doi:10.1134/1.1920382.
Popov VL, Dudko OK. Tech Phys Lett 30 (2004) 174, doi:10.1134/1.1666964.
"""

from __future__ import annotations

import functools

import numpy as np

from ...errors import ParameterError

__all__ = [
    "CONVENTIONS",
    "CONVENTION_TEXT",
    "to_per_contact",
    "pinning_shape",
    "pinning_shape_kspace",
    "pinning_shape_fast",
    "pinning_shape_asymptote",
    "pinning_force_sq",
    "shakedown_force",
    "shakedown_limit",
    "microslip_force",
]

#: Amplitude conventions accepted by the CLI and the fit.
CONVENTIONS = ("per-contact", "probe")
#: Text stating the convention, copied into every output.
CONVENTION_TEXT = {
    "per-contact": "amplitude_m is the per-contact amplitude a = dl/4 "
                   "(dl = peak-to-peak change of the probe length)",
    "probe": "amplitude_m is the probe end-face amplitude dl/2 = 2a (a = per-contact amplitude)",
}


def to_per_contact(amplitude, convention: str = "per-contact"):
    """Convert amplitudes (m) given in ``convention`` to per-contact amplitudes ``a`` (m).

    Parameters
    ----------
    amplitude : float or array_like
        Amplitudes in m.
    convention : {"per-contact", "probe"}
        ``"probe"`` means the end-face amplitude ``dl/2``, which is ``2 a``.
    """
    if convention not in CONVENTIONS:
        raise ParameterError("convention", f"one of {list(CONVENTIONS)}", convention)
    a = np.asarray(amplitude, dtype=float)
    return a / 2.0 if convention == "probe" else a


# ------------------------------------------------------------ pinning model


def _h(c: np.ndarray) -> np.ndarray:
    """Normalised ``int_0^inf q^2 e^{-q^2/2} J0(c q) dq / sqrt(pi/2) = 1F1(3/2; 1; -c^2/2)``.

    Closed form (Gradshteyn & Ryzhik 6.631) written with exponentially scaled
    Bessel functions, ``(1 - 2z) e^{-z} I0(z) + 2z e^{-z} I1(z)`` with
    ``z = c^2/4``.  Its two terms cancel for large ``c``, so beyond ``c = 60``
    the asymptotic series of 1F1 is used (truncation error < 1e-10 there).
    """
    from scipy.special import ive

    c = np.asarray(c, dtype=float)
    out = np.empty_like(c)
    big = c > 60.0
    z = 0.25 * c[~big] ** 2
    out[~big] = (1.0 - 2.0 * z) * ive(0, z) + 2.0 * z * ive(1, z)
    u = 1.0 / c[big] ** 2
    # -sqrt(2/pi) c^-3 sum_n ((3/2)_n)^2 / n! (2/c^2)^n
    out[big] = (
        -np.sqrt(2.0 / np.pi)
        * u
        * np.sqrt(u)
        * (1.0 + u * (4.5 + u * (225.0 / 8.0 + u * 229.6875)))
    )
    return out


@functools.lru_cache(maxsize=None)
def _graded_nodes(n_panels: int = 34, order: int = 16) -> tuple[np.ndarray, np.ndarray]:
    # Panels on phi in (0, pi/2] graded geometrically towards 0: the integrand
    # varies on the scale phi ~ 1/s, so every s from 1e-3 to 1e6 is resolved.
    x, w = np.polynomial.legendre.leggauss(order)
    edges = (np.pi / 2) * 0.5 ** np.arange(n_panels + 1)[::-1]
    edges[0] = 0.0
    lo, hi = edges[:-1, None], edges[1:, None]
    nodes = 0.5 * (hi - lo) * x[None, :] + 0.5 * (hi + lo)
    weights = 0.5 * (hi - lo) * w[None, :]
    return nodes.ravel(), weights.ravel()


def pinning_shape(s) -> np.ndarray:
    """Exact normalised pinning-model curve ``G(s) = F^2(a) / F^2(0)``, ``s = a / lambda``.

    Uses Neumann's formula ``J0(x)^2 = (2/pi) int_0^{pi/2} J0(2 x sin phi) dphi``,
    which turns the oscillatory k-integral into a smooth phi-integral of the
    closed form :func:`_h`; relative accuracy ~1e-12 for ``0 <= s <= 1e6``.

    Parameters
    ----------
    s : float or array_like
        Amplitude over correlation length, dimensionless, ``>= 0``.

    Returns
    -------
    ndarray
        ``G(s)``, with ``G(0) = 1``.
    """
    s = np.asarray(s, dtype=float)
    phi, w = _graded_nodes()
    vals = _h(2.0 * s[..., None] * np.sin(phi)) @ w
    return vals * (2.0 / np.pi)


def pinning_shape_kspace(s: float, q_max: float = 14.0) -> float:
    """Independent reference for :func:`pinning_shape`: direct oscillatory k-quadrature.

    Integrates ``q^2 exp(-q^2/2) J0(q s)^2`` on ``[0, q_max]`` with Gauss-Legendre
    panels shorter than a quarter period of ``J0^2``; the Gaussian tail beyond
    ``q_max = 14`` is below 1e-40.  Slow; meant for tests.
    """
    from scipy.special import j0

    n_panels = int(np.ceil(q_max * max(s, 1.0) / (0.25 * np.pi))) + 8
    x, w = np.polynomial.legendre.leggauss(20)
    edges = np.linspace(0.0, q_max, n_panels + 1)
    lo, hi = edges[:-1, None], edges[1:, None]
    q = (0.5 * (hi - lo) * x + 0.5 * (hi + lo)).ravel()
    wq = (0.5 * (hi - lo) * w).ravel()
    num = np.sum(wq * q**2 * np.exp(-0.5 * q**2) * j0(q * s) ** 2)
    return float(num / np.sqrt(np.pi / 2.0))


def pinning_shape_asymptote(s) -> np.ndarray:
    """Large-amplitude limit ``G(s) ~ sqrt(2) / (pi^1.5 s)`` (``J0^2`` replaced by its mean)."""
    return np.sqrt(2.0) / (np.pi**1.5 * np.asarray(s, dtype=float))


@functools.lru_cache(maxsize=1)
def _shape_spline():
    from scipy.interpolate import CubicSpline

    ls = np.linspace(np.log(1e-4), np.log(1e5), 1600)
    # interpolate s*G(s): bounded and smooth in ln s, tends to a constant
    return CubicSpline(ls, np.exp(ls) * pinning_shape(np.exp(ls)))


def pinning_shape_fast(s) -> np.ndarray:
    """Tabulated :func:`pinning_shape` (cubic interpolation in ln s), for fits.

    Below ``s = 1e-4`` the exact series ``1 - 3 s^2 / 2`` is used, above
    ``1e5`` the asymptote; the table error is below 1e-8 (checked in the tests).
    """
    s = np.asarray(s, dtype=float)
    out = np.empty_like(s)
    small, large = s < 1e-4, s > 1e5
    mid = ~(small | large)
    out[small] = 1.0 - 1.5 * s[small] ** 2
    out[large] = pinning_shape_asymptote(s[large])
    out[mid] = _shape_spline()(np.log(s[mid])) / s[mid]
    return out


def pinning_force_sq(
    a, correlation_length: float, force0: float, background_sq: float = 0.0
) -> np.ndarray:
    """Squared friction force ``F^2(a) = F0^2 G(a / lambda) + B`` of the pinning model (N^2).

    Parameters
    ----------
    a : array_like
        Per-contact amplitudes (m).
    correlation_length : float
        Correlation length ``lambda`` of the Gaussian pinning potential (m).
    force0 : float
        Friction force of both contacts without oscillation due to pinning (N).
    background_sq : float
        Amplitude-independent background ``B`` (N^2), e.g. from larger scales.
    """
    s = np.asarray(a, dtype=float) / correlation_length
    return force0**2 * pinning_shape_fast(s) + background_sq


# ------------------------------------------------------------ stiffness model


def shakedown_limit(mu_n: float, stiffness: float) -> float:
    """Per-contact amplitude ``mu N / k`` (m) above which the static force vanishes."""
    return mu_n / stiffness


def shakedown_force(a, mu_n: float, stiffness: float) -> np.ndarray:
    """Return the static friction force (N) of the two contacts under oscillation.

    ``F_s = 2 mu N max(0, 1 - k a / mu N)`` (PHYSICS.md section 5).

    Parameters
    ----------
    a : array_like
        Per-contact amplitude (m).
    mu_n : float
        Coulomb limit ``mu N`` of one contact (N).
    stiffness : float
        Tangential stiffness ``k`` of one contact (N/m).
    """
    a = np.asarray(a, dtype=float)
    return 2.0 * mu_n * np.maximum(0.0, 1.0 - stiffness * a / mu_n)


def microslip_force(a, spring_normal, spring_stiffness: float, mu: float) -> np.ndarray:
    """Shakedown force of two MDR contacts with per-spring Coulomb slip (N).

    Each MDR spring ``i`` (normal force ``q_i``, tangential stiffness
    ``k_i = G* dx``) under oscillation ``a`` plus a slow drift carries on
    average ``max(0, mu q_i - k_i a)``: it shakes down to elastic cycling if
    ``k_i a < mu q_i`` and alternates forward/backward slip (zero mean) otherwise.
    For a Hertz contact this gives ``2 mu N (1 - a / a_s)^{3/2}`` with
    ``a_s = mu E* d / G*``, i.e. the linear model's initial slope with a
    limit 3/2 times larger.

    Parameters
    ----------
    a : array_like
        Per-contact amplitudes (m).
    spring_normal : array_like
        Normal force of every spring of one contact (N).
    spring_stiffness : float
        Tangential stiffness of one spring, ``G* dx`` (N/m).
    mu : float
        Coulomb coefficient.
    """
    a = np.asarray(a, dtype=float)
    q = np.asarray(spring_normal, dtype=float)
    per = np.maximum(0.0, mu * q[None, :] - spring_stiffness * a.reshape(-1, 1)).sum(axis=1)
    return 2.0 * per.reshape(a.shape)
