"""Eq. 23 fit (tribolmp.analysis.eq23): accuracy, error coverage and cost against run length.

Synthetic profiles h(x, t) from the exact OU integrator of Eq. 23
(tribolmp.models.topography), sampled like an MCA run (40 columns of 2.5 nm, a
frame every 0.05 ns, 1 nm white measurement noise), with known mu = 2e9 1/s,
D0 = 1e-7 m^2/s, Dz = 1e-16 m^3/s, Dx l^2 = 1e-33 m^5/s.  For each run length:
wall time of one fit, bias and scatter of each coefficient, fraction valid, and
the coverage of the reported +-1 and +-2 errors (nominal for 20 jackknife
blocks, Student t with 19 dof: 0.670 and 0.940).

    python benchmarks/eq23_fit_coverage.py [--quick] [--plot docs/analysis_eq23_coverage.png]

Writes benchmarks/results/eq23_fit_coverage.csv (or _quick.csv).
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

from tribolmp.analysis.eq23 import COEFFICIENTS, fit_eq23
from tribolmp.benchmarking import print_table, write_csv
from tribolmp.models.topography.spde import TopographyParams, make_stepper

TRUE = {"mu_per_s": 2e9, "d0_m2_s": 1e-7, "dz": 1e-16, "dx_l2": 1e-33}
NX, DX, DT, NOISE, L_STEP = 40, 2.5e-9, 5e-11, 1e-9, 2.5e-9


def synth(rng, replicas, nt):
    """Return x (m), t (s) and h (m, replicas x nt x NX) of independent stationary runs."""
    p = TopographyParams(
        dim=1,
        n=NX,
        dx=DX,
        d0=TRUE["d0_m2_s"],
        dx_noise=TRUE["dx_l2"] / L_STEP**2,
        dz=TRUE["dz"],
        mu=TRUE["mu_per_s"],
        l=L_STEP,
        dt=DT,
        steps=1,
    )
    st = make_stepper(p, rng=rng, replicas=replicas, h0="stationary")
    h = np.empty((replicas, nt, NX))
    for i in range(nt):
        st.step()
        h[:, i] = st.heights()
    return np.arange(NX) * DX, np.arange(nt) * DT, h + NOISE * rng.standard_normal(h.shape)


def main(argv=None) -> int:
    """Run the table (and the figure with --plot)."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--plot", default=None)
    args = ap.parse_args(argv)
    rng = np.random.default_rng(2026)
    lengths = (100, 400, 800) if args.quick else (100, 200, 400, 800, 1600)
    reps = 60 if args.quick else 200
    rows, zs = [], {}
    for nt in lengths:
        x, t, h = synth(rng, reps, nt)
        t0 = time.perf_counter()
        fits = [fit_eq23(x, t, hr) for hr in h]
        wall = (time.perf_counter() - t0) / reps
        row = {"frames": nt, "duration_ns": nt * DT * 1e9, "fit_wall_s": wall}
        for c in COEFFICIENTS:
            ok = [f for f in fits if f["valid"][c]]
            row[f"{c}_valid"] = len(ok) / reps
            if ok:
                v = np.array([f[c] for f in ok])
                e = np.array([f[f"{c}_err"] for f in ok])
                z = (v - TRUE[c]) / e
                zs[(nt, c)] = z
                row[f"{c}_bias"] = float(v.mean() / TRUE[c] - 1)
                row[f"{c}_scatter"] = float(v.std() / TRUE[c])
                row[f"{c}_cov1"] = float(np.mean(np.abs(z) < 1))
                row[f"{c}_cov2"] = float(np.mean(np.abs(z) < 2))
        rows.append(row)
    print_table("Eq. 23 fit on exact-OU profiles (nominal coverage 0.670 / 0.940)", rows)
    out = (
        Path(__file__).parent
        / "results"
        / ("eq23_fit_coverage_quick.csv" if args.quick else "eq23_fit_coverage.csv")
    )
    write_csv(out, rows)
    print(f"wrote {out}")
    if args.plot:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        from scipy.stats import t as student

        nt = max(n for n in lengths if all((n, c) in zs for c in COEFFICIENTS))
        fig, axes = plt.subplots(1, 5, figsize=(16, 3.2))
        zz = np.linspace(-4, 4, 200)
        for ax, c in zip(axes[:4], COEFFICIENTS):
            ax.hist(
                np.clip(zs[(nt, c)], -4, 4),
                bins=24,
                range=(-4, 4),
                density=True,
                alpha=0.6,
                label="fits",
            )
            ax.plot(zz, student.pdf(zz, 19), "k-", lw=1, label="t(19)")
            ax.set_title(f"{c}: (fit - true)/err")
            ax.set_xlabel(f"{nt} frames = {nt * DT * 1e9:.0f} ns")
        axes[0].legend(fontsize=7)
        ax = axes[4]
        for c in COEFFICIENTS:
            # coverage only where >= 20 % of the runs were valid (else it is a handful of fits)
            use = [r for r in rows if f"{c}_cov1" in r and r[f"{c}_valid"] >= 0.2]
            ax.plot([r["duration_ns"] for r in use], [r[f"{c}_cov1"] for r in use], "o-", label=c)
        ax.axhline(0.670, color="k", lw=0.8, ls="--")
        ax.set_ylim(0, 1)
        ax.set_xlabel("run length (ns)")
        ax.set_title("coverage of +-1 err")
        ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(args.plot, dpi=80)
        print(f"wrote {args.plot}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
