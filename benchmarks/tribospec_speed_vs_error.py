"""Speed against error: tribospectroscopy curves, the multirate scheme and stiff stick-slip.

Tables (printed and written as CSV into ``benchmarks/results/``):

1. ``tribospec_curve``: wall time per F(a) curve of 50 amplitudes and its
   error -- pinning model (exact quadrature, table) against the direct
   k-space quadrature; micro-slip shakedown model (averaged, closed form per
   spring) against brute-force quasi-static integration of the oscillating
   MDR contact with a slow drift, at several steps per cycle.
2. ``tribospec_multirate``: averaged vs brute force over windows of slow drift
   at 65 kHz; steps and wall time, error of the cycle-mean force.
3. ``tribospec_stiff``: stick-slip with a contact spring of growing stiffness:
   implicit/explicit integrators, function evaluations, wall time, error of
   the slip-end force against the rigid-contact closed form.

Usage: ``python benchmarks/tribospec_speed_vs_error.py [--quick] [--out DIR]``.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

from tribolmp.benchmarking import print_table, write_csv

E_STAR = 206e9 / (2 * (1 - 0.3**2))
G_STAR = 1.0 / (2 * (2 - 0.3) / (4 * 206e9 / 2.6))


def _timed(fun, repeat=1):
    best = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fun()
        best = min(best, time.perf_counter() - t0)
    return out, best


def curve_table(quick: bool):
    """Time F(a) curves of 50 amplitudes and their errors (``tribospec_curve`` rows).

    Pinning model against the direct k-space quadrature; micro-slip shakedown
    model against brute-force quasi-static integration at several steps per cycle.
    """
    from tribolmp.models.macro import (
        ContactSprings,
        DriftParams,
        drift_under_oscillation,
        profile_from_geometry,
    )
    from tribolmp.models.tribospectroscopy import models as M

    rows = []
    s = np.linspace(0.0, 10.0, 50)  # a / lambda for 50 amplitudes up to 0.5 um at lambda = 50 nm
    ref = np.array([M.pinning_shape_kspace(v) for v in s])
    M.pinning_shape_fast(s)  # build the table once (cached), timed separately below
    for name, fun in (
        ("exact-quadrature", lambda: M.pinning_shape(s)),
        ("table", lambda: M.pinning_shape_fast(s)),
    ):
        g, t = _timed(fun, 5)
        rows.append(dict(model="potential", method=name, n_amp=50, steps_per_cycle=0, time_s=t,
                         max_rel_error=float(np.max(np.abs(g / ref - 1)))))
    _, t_tab = _timed(lambda: M._shape_spline.__wrapped__(), 1)
    rows.append(
        dict(
            model="potential",
            method="table-build(once)",
            n_amp=0,
            steps_per_cycle=0,
            time_s=t_tab,
            max_rel_error=float("nan"),
        )
    )

    N, R, mu = 5.0, 5e-3, 0.3
    n_spr = 61 if quick else 101
    x, g = profile_from_geometry("sphere", N, E_STAR, n_springs=n_spr, radius=R)
    c = ContactSprings(x, g, E_STAR, G_STAR, mu)
    q, k = c.springs(N)
    L = mu * N / c.stiffness(N)
    n_amp = 4 if quick else 50
    amps = np.linspace(0.0, 1.6 * L, n_amp)
    f_avg, t_avg = _timed(lambda: M.microslip_force(amps, q, k, mu), 5)
    rows.append(
        dict(
            model="stiffness-microslip",
            method="averaged",
            n_amp=n_amp,
            steps_per_cycle=0,
            time_s=t_avg,
            max_rel_error=0.0,
        )
    )
    # brute force: drift (0.5 % of the amplitude scale per cycle) until the contact slides steadily
    V_per_cycle = 0.01 * L
    n_cyc = int(2.5 * L / V_per_cycle)
    for spc in ((8,) if quick else (8, 16)):
        def brute():
            out = []
            for a in amps:
                p = DriftParams(
                    normal_force=N,
                    amplitude=float(a),
                    frequency=65e3,
                    sliding_velocity=V_per_cycle * 65e3,
                    duration=n_cyc / 65e3,
                    steps_per_cycle=spc,
                )
                out.append(drift_under_oscillation(p, c, scheme="brute").force[-5:].mean())
            return np.array(out)

        fb, tb = _timed(brute)
        rows.append(
            dict(
                model="stiffness-microslip",
                method="brute-force",
                n_amp=n_amp,
                steps_per_cycle=spc,
                time_s=tb,
                max_rel_error=float(np.max(np.abs(fb - f_avg)) / (2 * mu * N)),
            )
        )
    return rows


def multirate_table(quick: bool):
    """Averaged against brute-force drift under 65 kHz oscillation (``tribospec_multirate`` rows).

    Steps, wall time and the error of the cycle-mean force per window of slow drift.
    """
    from tribolmp.models.macro import (
        ContactSprings,
        DriftParams,
        drift_under_oscillation,
        profile_from_geometry,
    )

    N, R, mu = 5.0, 5e-3, 0.3
    x, g = profile_from_geometry("sphere", N, E_STAR, n_springs=101, radius=R)
    c = ContactSprings(x, g, E_STAR, G_STAR, mu)
    L = mu * N / c.stiffness(N)
    rows = []
    for dur in ((0.5e-3, 1e-3) if quick else (0.5e-3, 1e-3, 2e-3, 4e-3)):
        p = DriftParams(
            normal_force=N,
            amplitude=0.5 * L,
            frequency=65e3,
            sliding_velocity=1e-4,
            duration=dur,
            steps_per_cycle=32,
            slow_steps=max(2, int(dur * 65e3 / 4)),
        )
        b, tb = _timed(lambda: drift_under_oscillation(p, c, scheme="brute"))
        a, ta = _timed(lambda: drift_under_oscillation(p, c, scheme="averaged"))
        err = float(np.max(np.abs(b.force - np.interp(b.t, a.t, a.force))) / (2 * mu * N))
        rows.append(dict(window_s=dur, brute_steps=b.steps, brute_time_s=tb, averaged_steps=a.steps,
                         averaged_time_s=ta, max_err_over_2muN=err,
                         brute_steps_per_s_drift=65e3 * 32.0, brute_s_per_s_drift=tb / dur))
    return rows


def stiff_table(quick: bool):
    """Stick-slip with a growing contact stiffness (``tribospec_stiff`` rows).

    Integrators, function evaluations, wall time and the error of the slip-end
    force against the rigid-contact closed form.
    """
    from tribolmp.models.macro import ConstantFriction, StickSlipParams, stick_slip
    from tribolmp.models.macro.reference import stick_slip_cycle

    ref = stick_slip_cycle(0.1, 1e5, 0.01, 10.0, 0.4, 0.3)["force_min"]
    law = ConstantFriction(0.4, 0.3)
    rows = []
    grid = {"radau-rk45": (1e8, 1e10, 1e12), "rk45": (1e8, 1e10) if quick else (1e8, 1e10, 1e12)}
    for method, kcs in grid.items():
        for kc in kcs:
            p = StickSlipParams(
                mass=0.1,
                drive_stiffness=1e5,
                drive_velocity=0.01,
                normal_force=10.0,
                duration=0.01 if quick else 0.02,
                contact_stiffness=kc,
                rtol=1e-8,
            )
            r, t = _timed(lambda: stick_slip(p, law, method=method))
            stops = [e["force_N"] for e in r.events if e["to_phase"] == "stick"]
            err = max(abs(f - ref) for f in stops) / ref if stops else float("nan")
            rows.append(
                dict(
                    method=method,
                    contact_stiffness=kc,
                    nfev=r.nfev,
                    time_s=t,
                    rel_err_slip_end_force=err,
                )
            )
    return rows


def main(argv=None) -> int:
    """Run the benchmark tables; ``--quick`` for a small version."""
    ap = argparse.ArgumentParser(description="tribospectroscopy / macro speed against error")
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--out", default=str(Path(__file__).resolve().parent / "results"))
    args = ap.parse_args(argv)
    out = Path(args.out)
    for name, fun in (("tribospec_curve", curve_table), ("tribospec_multirate", multirate_table),
                      ("tribospec_stiff", stiff_table)):
        rows = fun(args.quick)
        print_table(name, rows)
        write_csv(out / f"{name}{'_quick' if args.quick else ''}.csv", rows)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
