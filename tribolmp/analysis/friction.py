"""Friction coefficient of an MCA run from ``friction.csv``.

``friction.csv`` is a thermo-style time series (one row per output step,
columns ``time_s,friction_N,normal_N,top_x_m``), not a per-atom trajectory, so
:class:`FrictionCoefficient` is not an MDAnalysis ``AnalysisBase``; it has the
same interface (construct, ``run()``, ``results``) so that all analyses of
:mod:`tribolmp.analysis` are used alike.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..errors import DataFileError
from ..params import check_range
from ..results import Result
from .outputs import read_friction_csv
from .stats import block_standard_error, mser_truncation

__all__ = ["FrictionCoefficient"]


def _ratio_mean(ft: np.ndarray, fn: np.ndarray) -> tuple[float, float, bool, float]:
    """Ratio-of-means mu = sum F_t / sum F_n with its blocking standard error.

    The error uses the linearisation (delta method) mu_hat - mu ~ mean(r) with
    r_i = (F_t,i - mu F_n,i) / mean(F_n), so correlated noise in both forces
    enters through :func:`block_standard_error` of r.

    Returns
    -------
    mu, se : float
        Estimate and its standard error (1).
    converged : bool
        Whether blocking reached a plateau (else ``se`` is a lower bound).
    n_independent : float
        Effective number of independent samples, var(r) / se**2.
    """
    mu = float(ft.sum() / fn.sum())
    r = (ft - mu * fn) / fn.mean()
    se, converged = block_standard_error(r)
    var = float(np.var(r, ddof=1)) if r.size > 1 else 0.0
    n_ind = var / se**2 if se > 0 else float(r.size)
    return mu, float(se), bool(converged), float(n_ind)


class FrictionCoefficient:
    """mu = <F_t>/<F_n> over the steady part, its start, error bar and steadiness.

    Parameters
    ----------
    friction : str, Path or dict
        ``friction.csv``, the output directory holding it, or the dict
        returned by :func:`~tribolmp.analysis.outputs.read_friction_csv`.
    start_s : float, optional
        Force the start of the averaging window (s); default: MSER-5 detection.
    min_normal_fraction : float
        Samples whose normal force is below this fraction of the median normal
        force are excluded (before contact is established mu is 0/0).
    batch : int
        Batch size of MSER.
    min_independent : float
        Smallest steady window, in effective independent samples, for the
        result to be called steady (default 20: then each half of the window
        holds ~10, so the halves' standard errors, themselves uncertain by
        ~1/sqrt(2*9) = 24 %, still make the 3-sigma drift test meaningful).

    Notes
    -----
    Estimator: mu = sum(F_t) / sum(F_n) over the window (the ratio of the mean
    forces, the same definition as Coulomb's law and as ``mu_raw`` of the
    driver).  The mean of the ratios F_t/F_n would be biased upwards whenever
    F_n fluctuates (Jensen: <1/F_n> > 1/<F_n>); mu(t) = F_t/F_n is kept only as
    the plotted series and the input of MSER.

    Sign: ``friction_N`` may be recorded as the force the bodies exert on the
    slider (opposing the motion) or as its magnitude.  mu is oriented so that
    it is positive for a resisting force; ``results.sign`` records the factor.

    ``results.steady`` is True only when *all* of these hold:

    * MSER-5 found the truncation point in the first half of the series (not at
      the search limit);
    * blocking reached a plateau on the steady window (the error bar is an
      estimate, not a lower bound), which needs >= 16 blocks longer than the
      correlation time;
    * the window holds at least ``min_independent`` independent samples;
    * the ratio means of the two halves of the window agree within 3 combined
      standard errors (drift test).

    Otherwise (a run shorter than a few correlation times, e.g. a stick-slip
    cycle that fills the run, or a drifting mu) there is no steady estimate:
    ``steady`` is False, ``estimator`` is ``"second_half_mean"``, mu is the
    ratio of mean forces over the second half of the loaded series (the plain
    estimate), ``steady_start_s`` is NaN, and ``mu_err`` is widened to
    max(blocking SE, |difference of the two quarter means| / 2) so that it
    covers the swing of mu within the window.  With a forced ``start_s`` the
    window is the user's (``estimator`` = ``"forced_start_mean"``), and the
    same tests decide ``steady``.
    """

    def __init__(
        self,
        friction,
        *,
        start_s: float | None = None,
        min_normal_fraction: float = 0.05,
        batch: int = 5,
        min_independent: float = 20.0,
    ):
        if isinstance(friction, (str, Path)):
            friction = read_friction_csv(friction)
        self._data = {k: np.asarray(v, dtype=float) for k, v in friction.items()}
        for key in ("time_s", "friction_N", "normal_N"):
            if key not in self._data:
                raise DataFileError(f"friction: expected column {key!r}, got {sorted(self._data)}")
        self._start = None if start_s is None else check_range("start_s", start_s, 0.0)
        self._frac = check_range("min_normal_fraction", min_normal_fraction, 0.0, 1.0)
        self._batch = int(batch)
        self._min_ind = check_range("min_independent", min_independent, 2.0)
        self.results = Result(method="mser+blocking, ratio of mean forces")

    def run(self) -> FrictionCoefficient:
        """Compute the results; returns ``self``."""
        r = self.results
        t = self._data["time_s"]
        ft = self._data["friction_N"]
        fn = self._data["normal_N"]
        ok = fn > self._frac * np.median(np.abs(fn))
        if ok.sum() < 8:
            raise DataFileError(
                "friction: normal_N: expected >= 8 samples with "
                f"contact (normal force > 0), got {int(ok.sum())}"
            )
        t, ft, fn = t[ok], ft[ok], fn[ok]
        mu_t = ft / fn
        if self._start is not None:
            d = int(np.searchsorted(t, self._start))
            mser_ok = d < t.size - 8
            mser_start = float("nan")
        else:
            d, mser_ok = mser_truncation(mu_t, batch=self._batch)
            mser_start = float(t[d])
        if t.size - d < 8:
            raise DataFileError(
                f"friction: start_s: expected >= 8 samples after it, got {t.size - d}"
            )
        msgs = []
        # the tests run on the candidate window (MSER or forced start); drift_sigma stays theirs
        is_steady, drift, converged, n_ind = self._assess(ft[d:], fn[d:], mser_ok, msgs)
        if self._start is not None:
            estimator, w = "forced_start_mean", d
        elif is_steady:
            estimator, w = "steady_mean", d
        else:
            # no steady state: the plain second-half estimate, flagged and with a widened error
            estimator = "second_half_mean"
            w = min(int(np.searchsorted(t, 0.5 * t[-1])), t.size - 8)
        sign = 1.0 if ft[w:].sum() >= 0 else -1.0
        fw, nw = sign * ft[w:], fn[w:]
        mean, err, conv_w, n_ind_w = _ratio_mean(fw, nw)
        half = fw.size // 2
        m1 = float(fw[:half].sum() / nw[:half].sum())
        m2 = float(fw[half:].sum() / nw[half:].sum())
        if estimator == "second_half_mean":
            converged, n_ind = conv_w, n_ind_w
            err = max(err, 0.5 * abs(m1 - m2))
        r.update(
            time_s=t,
            mu_t=sign * mu_t,
            mu=mean,
            mu_err=float(err),
            mu_std=float(np.std(fw / nw, ddof=1)),
            estimator=estimator,
            steady_start_s=float(t[d]) if is_steady else float("nan"),
            window_start_s=float(t[w]),
            mser_start_s=mser_start,
            steady_start_index=int(d),
            window_start_index=int(w),
            n_samples=int(fw.size),
            n_independent=float(n_ind),
            steady=is_steady,
            block_converged=bool(converged),
            mu_first_half=m1,
            mu_second_half=m2,
            drift_sigma=float(drift),
            mu_transient=float(ft[:w].sum() / fn[:w].sum()) * sign if w > 0 else float("nan"),
            sign=sign,
            normal_N=float(np.mean(nw)),
            nit=int(t.size),
            units={"time_s": "s", "mu_t": "1", "mu": "1", "mu_err": "1", "steady_start_s": "s",
                   "window_start_s": "s", "mser_start_s": "s", "normal_N": "N"},
        )
        if "top_x_m" in self._data:
            x = self._data["top_x_m"][ok]
            r["sliding_distance_m"] = float(x[-1] - x[0])
            r["window_sliding_distance_m"] = float(x[-1] - x[w])
            r.units["sliding_distance_m"] = r.units["window_sliding_distance_m"] = "m"
        if estimator == "second_half_mean":
            msgs.append(
                f"mu = {mean:.4g} +- {err:.2g} is the mean over the second half, NOT a steady value"
            )
        r.status = 1 if msgs else 0
        r.message = "; ".join(msgs) or f"mu = {mean:.4g} +- {err:.2g} after {t[d]:.3g} s"
        return self

    def _assess(self, ft, fn, mser_ok, msgs) -> tuple[bool, float, bool, float]:
        """Steadiness tests of the candidate window; appends the reasons it fails to ``msgs``."""
        sign = 1.0 if ft.sum() >= 0 else -1.0
        ft = sign * ft
        _, _, converged, n_ind = _ratio_mean(ft, fn)
        half = ft.size // 2
        m1, e1, *_ = _ratio_mean(ft[:half], fn[:half])
        m2, e2, *_ = _ratio_mean(ft[half:], fn[half:])
        comb = math.hypot(e1, e2)
        drift = abs(m1 - m2) / comb if comb > 0 else (0.0 if m1 == m2 else math.inf)
        if not mser_ok:
            msgs.append("no steady state detected (MSER minimum at the end of its search range)")
        if not converged:
            msgs.append(
                "blocking did not reach a plateau (the window "
                "is shorter than a few correlation times)"
            )
        elif n_ind < self._min_ind:
            msgs.append(
                f"window holds only {n_ind:.0f} independent samples (need {self._min_ind:.0f})"
            )
        if drift >= 3.0:
            msgs.append(f"halves of the window differ by {drift:.1f} standard errors")
        steady = bool(mser_ok and converged and n_ind >= self._min_ind and drift < 3.0)
        return steady, drift, converged, n_ind
