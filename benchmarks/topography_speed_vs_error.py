"""Speed against error of the Eq. 23 solvers (tribolmp.models.topography).

Three tables, each printed and written as CSV into ``benchmarks/results/``:

``_step``
    Cost of one 2D exact-OU step at n x n (default 1024) against one numpy
    ``rfft2`` + ``irfft2`` pair at the same size, measured in the same run
    (best of several repeats, so that the other load on the machine biases
    both alike), for double and single precision; "step" keeps the state in
    Fourier space, "step+h" also synthesises the heights (one inverse FFT).
    Memory is the tracemalloc peak of setting up and running the stepper, in
    units of one float64 grid (n*n*8 bytes).
``_schemes``
    Exact OU against Euler-Maruyama on the same 1D lattice problem over the
    same physical time: wall time, the analytic stationary spectral bias
    max_k |S_scheme/S_lattice - 1| (exact: 0; Euler: 1/(1 - gamma dt/2) - 1),
    and the measured max band deviation of the replica-mean periodogram from
    the scheme-free lattice theory (with its sampling sd).
``_sizes``
    1D exact-OU throughput and accuracy from N = 2^10 to 2^20: steps per
    second and the band test against the exact transient theory.

Usage: ``python benchmarks/topography_speed_vs_error.py [--quick] [--out DIR]``.
"""

from __future__ import annotations

import argparse
import math
import time
import tracemalloc
from dataclasses import replace
from pathlib import Path

import numpy as np

from tribolmp.benchmarking import print_table, write_csv
from tribolmp.models.topography import (
    TopographyParams,
    evolve,
    expected_periodogram,
    make_stepper,
    spectra,
)
from tribolmp.models.topography.spde import mode_ratios

NAME = "topography_speed_vs_error"


def best_time(func, repeats):
    """Return the best wall time (s) of ``repeats`` calls of ``func`` after one warm-up call."""
    func()  # warm-up (plans, page faults)
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        func()
        times.append(time.perf_counter() - t0)
    return min(times)


def table_step(n, repeats):
    """Time one 2D exact-OU step at ``n`` x ``n`` against one rfft2 + irfft2 pair (``_step`` rows).

    Double and single precision; memory peak in units of one float64 grid.
    """
    rng = np.random.default_rng(0)
    x = rng.standard_normal((n, n))
    pair = best_time(lambda: np.fft.irfft2(np.fft.rfft2(x), s=x.shape), repeats)
    rows = []
    grid_bytes = n * n * 8
    for precision in ("double", "single"):
        p = TopographyParams(
            dim=2,
            grid_points=n,
            pixel_size=1.0,
            d0=1.0,
            dx_noise=1.0,
            dz=1.0,
            mu=0.01,
            l=0.1,
            dt=1.0,
            steps=1,
            precision=precision,
        )
        tracemalloc.start()
        stepper = make_stepper(p, rng=np.random.default_rng(1))
        stepper.step()
        stepper.heights()
        _, peak = tracemalloc.get_traced_memory()
        tracemalloc.stop()
        step = best_time(stepper.step, repeats)
        step_h = best_time(lambda: (stepper.step(), stepper.heights()), repeats)
        rows.append(dict(n=n, precision=precision, fft_pair_ms=1e3 * pair, step_ms=1e3 * step,
                         step_ratio=step / pair, step_h_ms=1e3 * step_h, step_h_ratio=step_h / pair,
                         peak_memory_grids=peak / grid_bytes))
    return rows


def table_schemes(quick):
    """Compare exact OU and Euler-Maruyama on one 1D lattice problem (``_schemes`` rows).

    Wall time, analytic stationary bias and the measured band deviation of the
    replica-mean periodogram, over the same physical time for every scheme.
    """
    n = 64 if quick else 256
    R = 32 if quick else 64
    base = TopographyParams(
        dim=1,
        grid_points=n,
        pixel_size=1.0,
        d0=1.0,
        dx_noise=1.0,
        dz=1.0,
        mu=0.05,
        l=1.0,
        dt=1.0,
        steps=1,
        operator="lattice",
    )
    T = 60.0 if quick else 200.0  # 6 ... 20 relaxation times of the k = 0 mode
    kmag = 2 * np.pi * np.fft.rfftfreq(n, base.pixel_size)
    lat_stat = spectra.stationary_psd(kmag, lattice_dx=base.pixel_size, **base.theory_kwargs())
    rows = []
    configs = [("exact", 1), ("exact", 10), ("exact", 100)]
    fracs = (0.4, 0.1, 0.02) if quick else (0.4, 0.1, 0.02, 0.005)
    configs += [("euler", f) for f in fracs]
    for scheme, x in configs:
        if scheme == "exact":
            steps = x
        else:
            steps = int(math.ceil(T / (x * base.pixel_size**2 / base.d0)))
        p = replace(base, dt=T / steps, steps=steps)
        t0 = time.perf_counter()
        res = evolve(
            p,
            rng=np.random.default_rng(2),
            scheme=scheme,
            replicas=R,
            h0="stationary" if scheme == "exact" else None,
        )
        wall = time.perf_counter() - t0
        if scheme == "exact":
            bias = 0.0
        else:
            bias = float(
                np.max(
                    spectra.euler_psd(
                        kmag, math.inf, p.dt, lattice_dx=p.pixel_size, **p.theory_kwargs()
                    )
                    / lat_stat
                    - 1
                )
            )
        exp = expected_periodogram(p, math.inf if scheme == "exact" else p.duration, lattice=True)
        test = spectra.psd_consistency(mode_ratios(p, res.h, exp), bands=4)
        rows.append(
            dict(
                scheme=scheme,
                n=n,
                replicas=R,
                t_s=T,
                dt_s=p.dt,
                dt_over_dx2_d0=p.dt * p.d0 / p.pixel_size**2,
                steps=steps,
                wall_s=wall,
                analytic_bias=bias,
                measured_max_band_dev=float(np.max(np.abs(test.band_mean - 1))),
                band_sd=float(test.rel_sigma.max()),
                band_test_passed=test.passed,
            )
        )
    return rows


def table_sizes(quick):
    """Measure 1D exact-OU throughput and the band test from N = 2^10 up (``_sizes`` rows)."""
    sizes = (
        [1 << 10, 1 << 14, 1 << 17]
        if quick
        else [1 << 10, 1 << 12, 1 << 14, 1 << 16, 1 << 18, 1 << 20]
    )
    rows = []
    for n in sizes:
        p = TopographyParams(
            dim=1,
            grid_points=n,
            pixel_size=1.0,
            d0=1.0,
            dx_noise=1.0,
            dz=1.0,
            mu=1e-4,
            l=0.1,
            dt=100.0,
            steps=20,
        )
        R = max(1, (1 << 16) // n)
        res = evolve(p, rng=np.random.default_rng(3), replicas=R)
        test = spectra.psd_consistency(
            mode_ratios(p, res.h, expected_periodogram(p, p.duration, lattice=False)), bands=8
        )
        rows.append(
            dict(
                n=n,
                replicas=R,
                steps=p.steps,
                wall_s=res.time_s,
                steps_per_s=res.steps_per_s,
                ns_per_point_step=1e9 / (res.steps_per_s * n * R),
                max_band_dev=float(np.max(np.abs(test.band_mean - 1))),
                band_sd=float(test.rel_sigma.max()),
                band_test_passed=test.passed,
            )
        )
    return rows


def main(argv=None):
    """Run the benchmark; ``--quick`` for a small version.  Returns 0."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="small sizes (about 20 s)")
    ap.add_argument(
        "--n", type=int, default=None, help="2D grid for the step table (default 1024, quick 256)"
    )
    ap.add_argument("--repeats", type=int, default=None, help="timing repeats (best of)")
    ap.add_argument(
        "--out", default=str(Path(__file__).resolve().parent / "results"), help="CSV folder"
    )
    args = ap.parse_args(argv)
    out = Path(args.out)
    n = args.n or (256 if args.quick else 1024)
    repeats = args.repeats or (5 if args.quick else 7)
    tables = {
        "step": (
            "2D exact-OU step vs one numpy rfft2+irfft2 pair (same run)",
            table_step(n, repeats),
        ),
        "schemes": (
            "exact OU vs Euler-Maruyama, same lattice problem and time",
            table_schemes(args.quick),
        ),
        "sizes": ("1D exact OU: throughput and band test vs exact theory", table_sizes(args.quick)),
    }
    for key, (title, rows) in tables.items():
        print_table(title, rows)
        write_csv(out / f"{NAME}_{key}.csv", rows)
    print(f"\nCSV written to {out}/{NAME}_*.csv")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
