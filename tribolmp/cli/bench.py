"""``tribolmp bench``: one report of every model's speed-against-error table."""

from __future__ import annotations

HELP = "gather the speed-against-error tables of every model"


def configure(parser) -> None:
    """Add arguments."""
    parser.add_argument(
        "--run",
        action="store_true",
        help="run each benchmarks/*.py first (with --quick unless --full)",
    )
    parser.add_argument(
        "--full", action="store_true", help="with --run: the full benchmarks instead of --quick"
    )
    parser.add_argument(
        "--only",
        action="append",
        metavar="NAME",
        help="only this benchmark (script stem); repeatable",
    )
    parser.add_argument(
        "--benchmarks",
        default=None,
        help="the benchmarks/ folder (default: ./benchmarks or the source tree's)",
    )
    parser.add_argument(
        "--out", default="tribolmp-bench", help="output folder for bench.md and bench.csv"
    )
    parser.add_argument(
        "--timeout", type=float, default=900.0, help="per-benchmark time limit in s (default 900)"
    )
    parser.add_argument("--json", action="store_true", help="print the gathered tables as JSON")
    parser.add_argument(
        "--contact-table",
        metavar="PATH",
        default=None,
        help="also write the planner's contact speed-error table "
             "(JSON) built from the contact benchmark's CSVs",
    )


def run(args) -> int:
    """Gather (and optionally run) the benchmarks; return 0, or 3 if a benchmark run failed."""
    from ..chain.bench import gather
    from ..errors import RunError, SetupError
    from . import emit_json

    if args.timeout <= 0:
        raise SetupError(f"--timeout: expected a number in (0, inf) s, got {args.timeout!r}")
    res = gather(
        args.out,
        benchmarks_dir=args.benchmarks,
        run=args.run,
        quick=not args.full,
        only=args.only,
        timeout=args.timeout,
    )
    if res["benchmarks_dir"] is None:
        raise SetupError(
            "--benchmarks: expected a folder with benchmarks/*.py, "
            "got none (run from the repository root)"
        )
    if args.contact_table:
        from pathlib import Path

        from ..chain.bench import build_contact_table
        from ..chain.cache import atomic_write_json

        table = build_contact_table(Path(res["benchmarks_dir"]) / "results")
        if not table["rows"]:
            raise SetupError(
                "--contact-table: expected tests/data/contact_references.json "
                "or contact_rough_mdr_vs_bem*.csv in benchmarks/results, got none"
            )
        atomic_write_json(args.contact_table, table)
        res["contact_table"] = args.contact_table
    if args.json:
        emit_json(res)
    else:
        for e in res["benchmarks"]:
            rows = sum(len(t["rows"]) for t in e["tables"])
            state = (
                ""
                if not e["ran"]
                else (" ok" if e["returncode"] == 0 else f" FAILED: {e['error']}")
            )
            print(f"{e['name']:28s} {len(e['tables'])} table(s), {rows} row(s){state}")
        print(f"report: {res['markdown']}  csv: {res['csv']}")
    failed = [e["name"] for e in res["benchmarks"] if e["ran"] and e["returncode"] != 0]
    if failed:
        raise RunError(
            f"benchmark(s) failed: {', '.join(failed)} "
            f"(tables of the others are in {res['markdown']})"
        )
    return 0
