"""Speed of the MCA trajectory analysis against its error, on synthetic walkers of known D.

For growing trajectories (automata x frames) it measures

* reading every frame with MDAnalysis's stock ``LAMMPSDUMP`` reader (Python
  loop over atoms) and with :mod:`tribolmp.analysis.outputs`'s numpy-parsed
  ``MCADUMP`` reader (same frames, positions checked equal);
* the whole :class:`~tribolmp.analysis.diffusion.LateralDiffusion` run and
  the relative error of its D against the exact value.

Usage: ``python benchmarks/analysis_throughput.py [--quick] [--out CSV]``.
"""

from __future__ import annotations

import argparse
import csv
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np

SIZES = ((100, 40), (400, 80), (1500, 160))
QUICK = ((50, 20), (200, 40))


def _read_all(u) -> float:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the stock reader warns that it has no dt
        t0 = time.perf_counter()
        for _ts in u.trajectory:
            pass
        return time.perf_counter() - t0


def main(argv=None) -> int:
    """Run the benchmark, print the table and write the CSV."""
    import MDAnalysis as mda

    from tribolmp.analysis.diffusion import LateralDiffusion
    from tribolmp.analysis.outputs import open_trajectory, read_meta
    from tribolmp.analysis.synthetic import make_walkers

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="small sizes only")
    ap.add_argument(
        "--out", default=str(Path(__file__).parent / "results" / "analysis_throughput.csv")
    )
    args = ap.parse_args(argv)
    rows = []
    header = (
        "walkers",
        "atoms",
        "frames",
        "stock_read_s",
        "mca_read_s",
        "speedup",
        "diffusion_s",
        "D_rel_err",
    )
    print(" ".join(f"{h:>13s}" for h in header))
    with tempfile.TemporaryDirectory() as tmp:
        for n_walkers, n_frames in QUICK if args.quick else SIZES:
            d = Path(tmp) / f"w{n_walkers}"
            exp = make_walkers(
                d, np.random.default_rng(n_walkers), n_walkers=n_walkers, n_frames=n_frames
            )
            meta = read_meta(d)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                stock = mda.Universe(str(d / "traj.lammpstrj"), format="LAMMPSDUMP",
                                     additional_columns=["mol", "radius", "c_nbond"])
            u = open_trajectory(d, meta)
            t_stock = _read_all(stock)
            t_mca = _read_all(u)
            # same coordinates up to the origin shift the stock reader applies
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                a = stock.trajectory[-1].positions + u.trajectory[-1].data["box_lo"]
            assert np.allclose(a, u.trajectory[-1].positions, atol=1e-4)
            t0 = time.perf_counter()
            r = LateralDiffusion(u, meta).run().results
            t_d = time.perf_counter() - t0
            err = r.diffusion_m2_s / exp["diffusion_m2_s"] - 1
            row = (n_walkers, u.atoms.n_atoms, n_frames, t_stock, t_mca, t_stock / t_mca, t_d, err)
            rows.append(row)
            print(
                " ".join(f"{v:>13.4g}" if isinstance(v, float) else f"{v:>13d}" for v in row),
                flush=True,
            )
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    with out.open("w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(header)
        w.writerows(rows)
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
