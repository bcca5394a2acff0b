"""Print the MCA campaign CSV as the markdown table of docs/mca_study.md.

Usage::

    python workflows/mca_campaign_table.py [--campaign docs/data/mca_campaign.csv] [--law mca]

One row per run (law, dim, P, V, seed, simulated time, mu +- err, steady, layer depth +- err,
localized, mixed width, cross-body links and transfer per ns, MSD exponent, the four Eq. 23
coefficients with their errors or ``null`` where not valid, modes used, wall time, status).
No physics: formatting only.
"""

from __future__ import annotations

import argparse
import csv
import sys

HEADER = (
    "| law | dim | P (MPa) | V (m/s) | seed | η (Pa s) | t (ns) | μ ± err | steady | layer (nm) "
    "| localized | mixed (nm) | cross links (1/ns) | transfer (1/ns) | MSD exp. | μ_per_s (1/s) "
    "| D0 (m²/s) | Dz (m³/s) | Dx l² (m⁵/s) | modes | wall (s) | status |"
)


def _f(text: str, scale: float = 1.0, fmt: str = "{:.3f}") -> str:
    try:
        return fmt.format(float(text) * scale)
    except (TypeError, ValueError):
        return "–"


def _coef(row: dict, key: str) -> str:
    if row.get(f"valid_{key}") != "True" or not row.get(key):
        return "null"
    return f"{float(row[key]):.3g} ± {float(row[key + '_err']):.3g}"


def markdown(rows: list[dict]) -> str:
    """Return the markdown table of campaign rows."""
    out = [HEADER, "|" + "---|" * (HEADER.count("|") - 1)]
    for r in rows:
        status = r.get("status") or ""
        status = status if status.startswith("failed") else (status.split(",")[0] or "ok")
        out.append(
            "| " + " | ".join([
                r["law"], r["dim"] or "2", _f(r["pressure_Pa"], 1e-6, "{:g}"),
                _f(r["sliding_velocity_m_s"], 1.0, "{:g}"), r["seed"],
                _f(r.get("contact_viscosity_Pa_s"), 1.0, "{:g}"),
                _f(r["time_s"], 1e9, "{:.0f}"),
                f"{_f(r['mu'])} ± {_f(r['mu_err'])}", r["mu_steady"] or "–",
                f"{_f(r['layer_depth_m'], 1e9, '{:.1f}')} ± "
                f"{_f(r['layer_depth_err_m'], 1e9, '{:.1f}')}",
                r["localized"] or "–", _f(r["mixed_width_m"], 1e9, "{:.1f}"),
                _f(r["cross_body_links_per_ns"], 1.0, "{:.0f}"),
                f"{_f(r['transfer_per_ns'], 1.0, '{:.2f}')} ± "
                f"{_f(r['transfer_per_ns_err'], 1.0, '{:.2f}')}",
                _f(r["diffusion_exponent"], 1.0, "{:.2f}"),
                _coef(r, "mu_per_s"), _coef(r, "d0_m2_s"), _coef(r, "dz"), _coef(r, "dx_l2"),
                r["modes_used"] or "0", _f(r["wall_time_s"], 1.0, "{:.0f}"), status[:90],
            ]) + " |"
        )
    return "\n".join(out)


def grid(rows: list[dict]) -> str:
    """Return the P x V table of 2D rows: mu +- err / layer depth (nm) / localized, per seed."""
    rows = [r for r in rows if (r["dim"] or "2") == "2" and r["mu"]]
    ps = sorted({float(r["pressure_Pa"]) for r in rows})
    vs = sorted({float(r["sliding_velocity_m_s"]) for r in rows})
    out = ["| P (MPa) | " + " | ".join(f"V = {v:g} m/s" for v in vs) + " |",
           "|---|" + "---|" * len(vs)]
    for p in ps:
        cells = []
        for v in vs:
            here = [r for r in rows if float(r["pressure_Pa"]) == p
                    and float(r["sliding_velocity_m_s"]) == v]
            here.sort(key=lambda r: int(r["seed"]))
            if not here:
                cells.append("–")
                continue
            mu = ", ".join(f"{float(r['mu']):.3f} ± {float(r['mu_err']):.3f}" for r in here)
            lay = ", ".join(_f(r["layer_depth_m"], 1e9, "{:.1f}") for r in here)
            loc = ", ".join("yes" if r["localized"] == "True" else "**no**" for r in here)
            seeds = f" ({len(here)} seeds)" if len(here) > 1 else ""
            cells.append(f"{mu}{seeds} / {lay} / {loc}")
        out.append(f"| {p / 1e6:g} | " + " | ".join(cells) + " |")
    return "\n".join(out)


def main(argv: list[str] | None = None) -> int:
    """Print the table of one law's rows (all laws without ``--law``)."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--campaign", default="docs/data/mca_campaign.csv")
    ap.add_argument("--law", default=None, help="only this law's rows")
    ap.add_argument("--grid", action="store_true",
                    help="the P x V grid (mu / layer / localized) of the 2D rows instead")
    args = ap.parse_args(argv)
    try:
        with open(args.campaign, newline="") as fh:
            rows = [r for r in csv.DictReader(fh) if args.law in (None, r["law"])]
    except OSError as exc:
        print(f"mca_campaign_table: --campaign: {exc}", file=sys.stderr)
        return 2
    print(grid(rows) if args.grid else markdown(rows))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
