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
from ..models.base import Result, check_range
from .outputs import read_friction_csv
from .stats import block_standard_error, mser_truncation

__all__ = ["FrictionCoefficient"]


class FrictionCoefficient:
    """mu(t) = F_t/F_n, its steady-state start, steady mean and error bar.

    Parameters
    ----------
    friction : str, Path or dict
        ``friction.csv``, the output directory holding it, or the dict
        returned by :func:`~tribolmp.analysis.outputs.read_friction_csv`.
    start_s : float, optional
        Force the start of the steady part (s); default: MSER-5 detection.
    min_normal_fraction : float
        Samples whose normal force is below this fraction of the median normal
        force are excluded (before contact is established mu is 0/0).
    batch : int
        Batch size of MSER.

    Notes
    -----
    Sign: ``friction_N`` may be recorded as the force the bodies exert on the
    slider (opposing the motion) or as its magnitude.  mu(t) is oriented so
    that the steady mean is the resisting friction, i.e. positive for a
    resisting force; ``results.sign`` records the factor applied.

    The steady part is the series after the MSER truncation point.  The error
    bar is the blocking standard error of its mean.  ``results.steady`` is
    True when MSER found a truncation point in the first half of the series
    *and* the means of the two halves of the steady part agree within 3
    combined standard errors (a drift test).
    """

    def __init__(self, friction, *, start_s: float | None = None, min_normal_fraction: float = 0.05, batch: int = 5):
        if isinstance(friction, (str, Path)):
            friction = read_friction_csv(friction)
        self._data = {k: np.asarray(v, dtype=float) for k, v in friction.items()}
        for key in ("time_s", "friction_N", "normal_N"):
            if key not in self._data:
                raise DataFileError(f"friction: expected column {key!r}, got {sorted(self._data)}")
        self._start = None if start_s is None else check_range("start_s", start_s, 0.0)
        self._frac = check_range("min_normal_fraction", min_normal_fraction, 0.0, 1.0)
        self._batch = int(batch)
        self.results = Result(method="mser+blocking")

    def run(self) -> FrictionCoefficient:
        """Compute the results; returns ``self``."""
        r = self.results
        t = self._data["time_s"]
        ft = self._data["friction_N"]
        fn = self._data["normal_N"]
        ok = fn > self._frac * np.median(np.abs(fn))
        if ok.sum() < 8:
            raise DataFileError(f"friction: normal_N: expected >= 8 samples with contact (normal force > 0), got {int(ok.sum())}")
        t, ft, fn = t[ok], ft[ok], fn[ok]
        mu_t = ft / fn
        if self._start is not None:
            d = int(np.searchsorted(t, self._start))
            mser_ok = d < t.size - 8
        else:
            d, mser_ok = mser_truncation(mu_t, batch=self._batch)
        steady = mu_t[d:]
        if steady.size < 8:
            raise DataFileError(f"friction: start_s: expected >= 8 samples after it, got {steady.size}")
        sign = 1.0 if steady.mean() >= 0 else -1.0
        mu_t = sign * mu_t
        steady = sign * steady
        mean = float(steady.mean())
        err, converged = block_standard_error(steady)
        half = steady.size // 2
        m1, m2 = float(steady[:half].mean()), float(steady[half:].mean())
        e1, _ = block_standard_error(steady[:half])
        e2, _ = block_standard_error(steady[half:])
        comb = math.hypot(e1, e2)
        drift = abs(m1 - m2) / comb if comb > 0 else (0.0 if m1 == m2 else math.inf)
        is_steady = bool(mser_ok and drift < 3.0)
        r.update(
            time_s=t,
            mu_t=mu_t,
            mu=mean,
            mu_err=float(err),
            mu_std=float(steady.std(ddof=1)),
            steady_start_s=float(t[d]),
            steady_start_index=int(d),
            n_samples=int(steady.size),
            steady=is_steady,
            block_converged=bool(converged),
            mu_first_half=m1,
            mu_second_half=m2,
            drift_sigma=float(drift),
            mu_transient=float(mu_t[:d].mean()) if d > 0 else float("nan"),
            sign=sign,
            normal_N=float(np.mean(fn[d:])),
            nit=int(t.size),
            units={"time_s": "s", "mu_t": "1", "mu": "1", "mu_err": "1", "steady_start_s": "s", "normal_N": "N"},
        )
        if "top_x_m" in self._data:
            x = self._data["top_x_m"][ok]
            r["sliding_distance_m"] = float(x[-1] - x[0])
            r.units["sliding_distance_m"] = "m"
        msgs = []
        if not mser_ok:
            msgs.append("no steady state detected (MSER minimum in the second half of the run)")
        if drift >= 3.0:
            msgs.append(f"halves of the steady part differ by {drift:.1f} standard errors")
        if not converged:
            msgs.append("blocking did not reach a plateau; mu_err is a lower bound")
        r.status = 1 if msgs else 0
        r.message = "; ".join(msgs) or f"mu = {mean:.4g} +- {err:.2g} after {t[d]:.3g} s"
        return self
