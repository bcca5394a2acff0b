"""Fig. 10 of the seed: the stationary spectrum of Eq. 23, and a running-in series.

Usage::

    python workflows/fig10_topography_spectrum.py [--quick] [--out fig10] [--seed 2006]

Writes into ``--out``:

* ``fig10_topography_spectrum.png`` -- (a) the simulated 1D PSD (replica
  average, exact OU from a flat start run for 5 relaxation times of the
  slowest mode) with the low-k plateau Dz/mu, the high-k plateau Dx l^2/D0,
  the kappa^-2 slope between the crossovers k1 = sqrt(mu/D0) and
  k2 = sqrt(Dz/(Dx l^2)), and the analytic curve; (b) a 2D surface: the
  radially averaged PSD (k^-2) and its line scans (k^-1), each with theory;
* ``running_in.png`` -- roughness Rq(t) from a flat and from a rough start
  with the exact theory, and the PSD at several times for both starts;
* ``fig10_psd.csv``, ``running_in.csv`` and ``summary.json`` (SI units),
  plus the final 2D surface as a height map (``surface_2d.npy`` + ``.json``).

Dimensionless units (dx = D0 = 1 s^-1 m^2 ... ) are used so the figure has
clean decades; every value is still SI-consistent.  No physics here: only
library calls (tribolmp.models.topography) and plotting.
"""

from __future__ import annotations

import argparse
import csv
import json
import math
from pathlib import Path

import numpy as np


def fig10_params(quick: bool):
    """Return the dimensionless 1D Eq. 23 problem of Fig. 10 (both plateaus and a k^-2 range)."""
    from tribolmp.models.topography import TopographyParams

    # k1 = sqrt(mu/D0) = 3.2e-3 1/m, k2 = sqrt(Dz/(Dx l^2)) = 0.2 1/m: a k^-2 range of 1.8 decades
    # inside 2 pi/L ... pi/dx, with both plateaus visible.
    n = 1 << 13 if quick else 1 << 15
    mu = 1e-5
    return TopographyParams(
        dim=1,
        grid_points=n,
        pixel_size=1.0,
        d0=1.0,
        dx_noise=1.0,
        dz=0.04,
        mu=mu,
        l=1.0,
        dt=5.0 / mu / 20,
        steps=20,
    )


def run_fig10(args, out: Path, rng) -> dict:
    """Simulate the 1D and 2D spectra of Fig. 10, write the figure and CSV, return the summary."""
    from tribolmp.models.topography import evolve, save_height_map, spectra

    p = fig10_params(args.quick)
    res = evolve(p, rng=rng, replicas=8 if args.quick else 32)
    # A weak flux noise keeps the high-k plateau (k2 = 5 1/m) out of the line scans, whose
    # plateau term (Dx l^2/D0)/dx would otherwise flatten their k^-1 range.
    p2 = p.__class__(
        **{
            **p.__dict__,
            "dim": 2,
            "n": 256 if args.quick else 512,
            "steps": 5,
            "dz": 0.25,
            "dx_noise": 0.01,
        }
    )
    res2 = evolve(p2, rng=rng, replicas=2 if args.quick else 4)
    save_height_map(out / "surface_2d.npy", res2.h[0], p2.dx)
    k1, k2 = p.crossovers()
    kb, sb, counts = spectra.log_bin(res.k, res.psd, 12)
    _, tb, _ = spectra.log_bin(res.k, res.psd_theory, 12)
    fit = spectra.hurst_fit(res.k, res.psd, kmin=4 * k1, kmax=k2 / 4, dim=1)
    fit_th = spectra.hurst_fit(res.k, res.psd_stationary, kmin=4 * k1, kmax=k2 / 4, dim=1)
    krange = dict(kmin=4 * p2.crossovers()[0], kmax=0.3)
    fit2 = spectra.hurst_fit(res2.k, res2.psd, dim=2, **krange)
    fit2_th = spectra.hurst_fit(res2.k, res2.psd_theory, dim=2, **krange)
    fit_line = spectra.hurst_fit(res2.line_k, res2.line_psd, dim=1, **krange)
    fit_line_th = spectra.hurst_fit(res2.line_k, res2.line_psd_theory, dim=1, **krange)
    with open(out / "fig10_psd.csv", "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["k_1_per_m", "psd_m3", "psd_theory_m3", "psd_stationary_m3"])
        w.writerows(zip(res.k, res.psd, res.psd_theory, res.psd_stationary))

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 4.8))
    ax.loglog(
        res.k,
        res.psd,
        ".",
        color="0.75",
        ms=2,
        label=f"simulated periodogram ({res.replicas} profiles)",
    )
    ax.loglog(kb, sb, "o", color="C0", ms=4, label="simulated, log-binned")
    ax.loglog(res.k, res.psd_stationary, "-", color="C3", lw=1.5, label="analytic $S(k)$")
    low, high = p.dz / p.mu, p.dx_noise * p.l**2 / p.d0
    kk = np.array([k1 / 3, k2 * 3])
    ax.loglog(kk, p.dz / (p.d0 * kk**2), ":", color="k", lw=1.5, label=r"$\kappa^{-2}$ (fractal)")
    ax.axhline(low, color="C2", lw=0.8, ls="--", label=r"plateaus $D_z/\mu$, $D_x l^2/D_0$")
    ax.axhline(high, color="C2", lw=0.8, ls="--")
    for kc, name in ((k1, "$k_1$"), (k2, "$k_2$")):
        ax.axvline(kc, color="0.5", lw=0.8)
        ax.text(kc * 1.1, low * 3, name)
    ax.set(xlabel="wavenumber k (1/m)", ylabel=r"PSD S(k) (m$^3$)",
           title=f"Fig. 10: Eq. 23 stationary spectrum (fit: $k^{{-{fit.alpha:.2f}}}$)")
    ax.legend(fontsize=8, loc="lower left")
    bx.loglog(res2.k, res2.psd, "o", ms=3, color="C0", label=r"2D radial average (m$^4$)")
    bx.loglog(res2.k, res2.psd_theory, "-", color="C3", label="theory (radial)")
    bx.loglog(res2.line_k, res2.line_psd, "s", ms=3, color="C1", label=r"line scans (m$^3$)")
    bx.loglog(res2.line_k, res2.line_psd_theory, "-", color="C4", label="theory (line scans)")
    bx.set(
        xlabel="k (1/m)",
        ylabel="PSD",
        title=f"2D surface: radial $k^{{-{fit2.alpha:.2f}}}$, "
              f"line scans $k^{{-{fit_line.alpha:.2f}}}$",
    )
    bx.legend(fontsize=8, loc="lower left")
    fig.tight_layout()
    fig.savefig(out / "fig10_topography_spectrum.png", dpi=120)
    plt.close(fig)
    # Deviation of each log bin from theory in units of its sampling sd, 1/sqrt(modes * replicas).
    zdev = np.abs(sb / tb - 1) * np.sqrt(counts * res.replicas)
    # The measured high-k plateau: mean periodogram over k >= 5 k2 (thousands of modes), against
    # the analytic plateau Dx l^2/D0 (the theory there is within 4 % of it: S/high = (1 + k2^2/K^2)
    # / (1 + k1^2/K^2) with the same lattice K^2 in both).  The low-k plateau Dz/mu holds only
    # ~1 mode below k1/3 in these boxes and is not measured.
    hk = res.k >= 5 * k2
    return {
        "k1_1_per_m": k1,
        "k2_1_per_m": k2,
        "low_plateau_m3": low,
        "high_plateau_m3": high,
        "high_plateau_measured_m3": float(np.mean(res.psd[hk])),
        "high_plateau_theory_same_modes_m3": float(np.mean(res.psd_theory[hk])),
        "high_plateau_sampling_sd": float(1.0 / np.sqrt(hk.sum() * res.replicas)),
        "slope_1d": -fit.alpha,
        "slope_1d_err": fit.alpha_err,
        "slope_1d_theory_same_range": -fit_th.alpha,
        "slope_2d_radial": -fit2.alpha,
        "slope_2d_radial_theory": -fit2_th.alpha,
        "slope_2d_line_scans": -fit_line.alpha,
        "slope_2d_line_scans_theory": -fit_line_th.alpha,
        "max_logbin_deviation_sd": float(zdev.max()),
        "replicas": res.replicas,
        "n": p.grid_points,
        "wall_s": res.time_s + res2.time_s,
    }


def run_running_in(args, out: Path, rng) -> dict:
    """Simulate Rq(t) and the PSD from a flat and a rough start, write the figure and CSV."""
    from tribolmp.models.topography import evolve, spectra

    p = fig10_params(True)
    p = p.__class__(
        **{
            **p.__dict__,
            "grid_points": 1024 if args.quick else 4096,
            "mu": 1e-4,
            "dz": 0.04,
            "steps": 400,
            "dt": 3.0 / 1e-4 / 400,
        }
    )
    rec = [1, 2, 4, 10, 20, 40, 100, 200, 400]
    flat = evolve(p, rng=rng, replicas=8, record_steps=rec)
    # A rough start: a stationary surface of the same equation with 30x stronger transfer noise.
    rough0 = evolve(
        p.__class__(**{**p.__dict__, "dz": 30 * p.dz, "steps": 1}), rng=rng, h0="stationary"
    ).h
    rough = evolve(p, rng=rng, replicas=8, h0=rough0, record_steps=rec)

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 3, figsize=(15, 4.5))
    for res, name, c in ((flat, "flat start", "C0"), (rough, "rough start", "C1")):
        t = [h["t_s"] for h in res.history]
        axes[0].loglog(t, [h["rq"] for h in res.history], "o", color=c, label=f"{name}: simulated")
        axes[0].loglog(
            t, [h["rq_theory"] for h in res.history], "-", color=c, label=f"{name}: theory"
        )
    axes[0].set(xlabel="time t (s)", ylabel="Rq (m)", title="running-in: roughness")
    axes[0].legend(fontsize=8)
    cmap = plt.get_cmap("viridis")
    for ax, res, name in ((axes[1], flat, "flat"), (axes[2], rough, "rough")):
        for i, h in enumerate(res.history[::2]):
            col = cmap(i / max(1, len(res.history[::2]) - 1))
            kb, sb, _ = spectra.log_bin(h["k"], h["psd"], 10)
            _, tb, _ = spectra.log_bin(h["k"], h["psd_theory"], 10)
            ax.loglog(kb, sb, "o", ms=3, color=col)
            ax.loglog(kb, tb, "-", lw=1, color=col, label=f"t = {h['t_s']:.3g} s")
        ax.loglog(flat.k, flat.psd_stationary, "k--", lw=1, label="stationary")
        ax.set(
            xlabel="k (1/m)",
            ylabel=r"PSD (m$^3$)",
            title=f"PSD vs time, {name} start (log-binned; dots: simulated)",
        )
        ax.legend(fontsize=7, loc="lower left")
    fig.tight_layout()
    fig.savefig(out / "running_in.png", dpi=110)
    plt.close(fig)
    with open(out / "running_in.csv", "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["start", "t_s", "rq_m", "rq_theory_m"])
        for res, name in ((flat, "flat"), (rough, "rough")):
            for h in res.history:
                w.writerow([name, h["t_s"], h["rq"], h["rq_theory"]])
    return {
        "rq_final_flat": flat.rq,
        "rq_final_rough": rough.rq,
        "rq_stationary_theory": flat.rq_theory,
        "rq_initial_rough": float(np.std(rough0)),
    }


def main(argv=None) -> int:
    """Write the Fig. 10 and running-in figures; return 0."""
    ap = argparse.ArgumentParser(
        description="Fig. 10: stationary spectrum of Eq. 23 and running-in"
    )
    ap.add_argument(
        "--quick", action="store_true", help="smaller grids and fewer replicas (a few seconds)"
    )
    ap.add_argument("--out", default="fig10", help="output folder")
    ap.add_argument("--seed", type=int, default=2006, help="random seed")
    args = ap.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    rng = np.random.default_rng(args.seed)
    summary = {"fig10": run_fig10(args, out, rng), "running_in": run_running_in(args, out, rng),
               "seed": args.seed, "quick": args.quick}
    (out / "summary.json").write_text(json.dumps(summary, indent=1, default=float))
    f = summary["fig10"]
    print(
        f"Fig. 10: slope {f['slope_1d']:.3f} +- {f['slope_1d_err']:.3f} "
        f"(theory {f['slope_1d_theory_same_range']:.3f}) "
        f"in [4 k1, k2/4], k1 = {f['k1_1_per_m']:.3g}, k2 = {f['k2_1_per_m']:.3g} 1/m; 2D radial "
        f"{f['slope_2d_radial']:.2f} (theory {f['slope_2d_radial_theory']:.2f}), line scans "
        f"{f['slope_2d_line_scans']:.2f} (theory {f['slope_2d_line_scans_theory']:.2f}); "
        f"max log-bin deviation {f['max_logbin_deviation_sd']:.2f} sd"
    )
    print(f"figures in {out}/ (fig10_topography_spectrum.png, running_in.png)")
    return 0 if math.isfinite(f["slope_1d"]) else 3


if __name__ == "__main__":
    raise SystemExit(main())
