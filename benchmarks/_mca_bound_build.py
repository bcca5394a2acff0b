r"""A timing-only build of the mca plugin: the pair loop without any pair-state traffic.

An upper bound on what any redesign of the pair state's storage could gain (structure of
arrays, fewer values per pair, single precision): in this build the common case of the pair
loop reads every pair's state from one constant entry that stays in the L1 cache (an
unbreakable attachment with no stored response, its previous separation equal to the current
one) and writes the advanced state to another, so the per-pair state costs no memory traffic at
all.  ``--no-partners`` in addition reads no partner row and adds nothing into the partner's
sums (run it on a block at rest).  Everything else runs as shipped: the vectorised law, the
sums into the automaton's own row, the stress update.  ``--no-staging`` in addition copies
no constant inputs into the batch (run it on a block at rest too).  The physics is *not* the
law's (every pair acts as a fresh attachment), so the build is only for timing, never for
results::

    python benchmarks/_mca_bound_build.py --out /tmp/bound
    python benchmarks/mca_throughput.py --blocks 2:120,3:17 --no-rotational \
        --reference-plugin /tmp/bound/mcaplugin.so --reference-label bound-no-pair-state \
        --reference-ghost-vel no

The edits are anchored on the source text of ``pair_mca.cpp``: if the pair loop changes so
that an anchor no longer matches exactly once, the script stops with one line (exit 2) instead
of building something else.  Measured in docs/mca.md, "Bounds: what the pair loop's memory
traffic costs".

``--probe KIND:K`` builds the shipped law (same numbers) with K extra operations of one kind per
evaluated pair, inserted at the start of the pair's gather (pass 1a): ``store`` (scalar stores,
each to its own cache line), ``vstore`` (256-bit stores, each to its own line), ``load``
(scalar loads into four independent sums), ``gather`` (AVX2 gathers of four doubles from four
cache lines, into four independent sums), ``add`` (register additions, eight independent
chains) or ``nop``.  The time each kind adds per operation says which resource the loop is
bound by, where the host has no hardware counters (docs/mca.md, "What the pair loop is bound
by")::

    python benchmarks/_mca_bound_build.py --out /tmp/probe_store --probe store:40
"""

from __future__ import annotations

import argparse
import shutil
import sys
import tempfile
from pathlib import Path

#: (anchor in pair_mca.cpp, replacement): pass 1a reads a constant entry, pass 2b writes to one
EDITS: tuple[tuple[str, str], ...] = (
    (
        "        const double *sl = &psc_i[jj * NP];\n",
        "        // TIMING BOUND (benchmarks/_mca_bound_build.py): a constant attachment in L1\n"
        "        static double bound_entry[16] = {0.0, double(FS::ATTACH)};\n"
        "        const double *sl = bound_entry;\n"
        "        (void) psc_i;\n",
    ),
    (
        "        B.rp0[ip] = sl[FS::S_RP];\n        B.rp1[ip] = sl[FS::S_RP + 1];\n",
        "        B.rp0[ip] = R0;\n        B.rp1[ip] = R1;\n",
    ),
    ("          B.rp2[ip] = sl[FS::S_RP + 2];\n", "          B.rp2[ip] = R2;\n"),
    (
        "        double *s = psc + B.soff[ip];\n        if (jlocal && mirrorflat[e] < 0) {\n",
        "        static double bound_sink[16];\n"
        "        double *s = bound_sink;\n"
        "        if (jlocal && mirrorflat[e] < 0) {\n",
    ),
)


#: further edits of ``--no-partners``: no partner row read, nothing added into the partner's
#: sums (every pair of an automaton reads its own row and sits at rest at contact distance)
PARTNER_EDITS: tuple[tuple[str, str], ...] = (
    (
        "      const int a = i_is_a ? i : j, b = i_is_a ? j : i;\n"
        "      // canonical relative position a -> b and velocities",
        "      const int a = i, b = i;    // TIMING BOUND: no partner row\n"
        "      (void) j;\n"
        "      // canonical relative position a -> b and velocities",
    ),
    (
        "      const double rsq = D3 ? R0 * R0 + R1 * R1 + R2 * R2 : R0 * R0 + R1 * R1;\n"
        "      const int k1 = cache_i[jj];\n",
        "      R0 = dbar;    // TIMING BOUND: at rest at contact distance (no partner position)\n"
        "      R1 = R2 = 0.0;\n"
        "      const double rsq = D3 ? R0 * R0 + R1 * R1 + R2 * R2 : R0 * R0 + R1 * R1;\n"
        "      const int k1 = cache_i[jj];\n",
    ),
    (
        "      apply(j, false, dx, dy, dz);\n",
        "      (void) dx, (void) dy, (void) dz;    // TIMING BOUND: nothing into j's sums\n",
    ),
)


#: where ``--probe`` inserts its operations: right after a pair is taken into the batch
PROBE_ANCHOR = "      const int ip = npre++;\n"

#: the probe's kinds: C++ before the operations, of operation q (a ``str.format`` template; o:
#: its offset in the buffer, a and b: its accumulator) and after them.  The buffer is a global
#: of 16384 doubles, so the compiler keeps every store; ``ip & 7`` keeps consecutive stores from
#: being merged, and the empty asm keeps each addition from being folded.
PROBE_CODE: dict[str, tuple[str, str, str]] = {
    "store": ("", "      mca_probe_buf[{o} + (ip & 7)] = R0;\n", ""),
    "vstore": (
        "      {\n        const __m256d pv = _mm256_set1_pd(R0);\n",
        "        _mm256_storeu_pd(&mca_probe_buf[{o}], pv);\n",
        "      }\n",
    ),
    "load": (
        "      {\n        double a[4] = {0.0, 0.0, 0.0, 0.0};\n",
        "        a[{a}] += mca_probe_buf[{o} + (ip & 7)];\n",
        "        for (int q = 0; q < 4; q++) mca_probe_sink[q] += a[q];\n      }\n",
    ),
    "add": (
        "      {\n        double a[8] = {R0, R1, R0, R1, R0, R1, R0, R1};\n",
        '        a[{b}] += 1.0;\n        asm volatile("" : "+x"(a[{b}]));\n',
        "        for (int q = 0; q < 8; q++) mca_probe_sink[q & 3] += a[q];\n      }\n",
    ),
    "gather": (
        "      {\n        __m256d ga[4] = {_mm256_setzero_pd(), _mm256_setzero_pd(),\n"
        "                         _mm256_setzero_pd(), _mm256_setzero_pd()};\n"
        "        const __m128i gi = _mm_setr_epi32(0, 8, 16, 24);\n",
        "        ga[{a}] = _mm256_add_pd(\n"
        "            ga[{a}], _mm256_i32gather_pd(&mca_probe_buf[{o4} + (ip & 7)], gi, 8));\n",
        "        for (int q = 0; q < 4; q++) mca_probe_sink[q] += _mm256_cvtsd_f64(ga[q]);\n"
        "      }\n",
    ),
    "nop": ('      asm volatile("', "nop\\n\\t", '");\n'),
}
PROBE_KINDS = tuple(PROBE_CODE)

#: declared before the source's ``using namespace LAMMPS_NS;`` by ``--probe``
PROBE_GLOBALS = (
    "#include <immintrin.h>\n"
    "// TIMING PROBE (_mca_bound_build.py --probe): globals, so no store is dropped\n"
    "double mca_probe_buf[16384];\ndouble mca_probe_sink[4];\n"
)


#: further edits of ``--no-staging``: pass 1a copies into the batch only the indices, the
#: geometry, the kind and the previous separation (rp = R, as in EDITS), not the constant
#: entry's values, the partners' angular velocities, the plastic offsets or the damping
#: constants (22 fewer stores per pair in 3D).  The batch is zeroed once and its damping
#: lanes filled once, so a block at rest computes what it would with them staged (zeros and
#: the same constants, up to the rows' round-off), an upper bound on what a kernel that loads
#: its inputs straight into registers saves in staging
_UNSTAGED = (
    "        B.pn[ip] = sl[FS::S_PN];\n",
    "        B.xi0[ip] = sl[FS::S_XI];\n",
    "        B.xi1[ip] = sl[FS::S_XI + 1];\n",
    "        B.th2[ip] = sl[FS::S_TH + 2];\n",
    "        B.oa2[ip] = oa[2];\n",
    "        B.ob2[ip] = ob[2];\n",
    "        B.Xbar[ip] = 0.5 * (pa[0] + pb[0]);\n",
    "        B.D0[ip] = 0.5 * (pa[1] + pb[1]);\n",
    "        B.D1[ip] = 0.5 * (pa[2] + pb[2]);\n",
    "        B.D3[ip] = 0.5 * (pa[4] + pb[4]);\n",
    "          B.xi2[ip] = sl[FS::S_XI + 2];\n",
    "          B.th0[ip] = sl[FS::S_TH];\n",
    "          B.th1[ip] = sl[FS::S_TH + 1];\n",
    "          B.oa0[ip] = oa[0];\n",
    "          B.oa1[ip] = oa[1];\n",
    "          B.ob0[ip] = ob[0];\n",
    "          B.ob1[ip] = ob[1];\n",
    "          B.D2[ip] = 0.5 * (pa[3] + pb[3]);\n",
    "          B.D4[ip] = 0.5 * (pa[5] + pb[5]);\n",
    "          B.D5[ip] = 0.5 * (pa[6] + pb[6]);\n",
)
STAGING_EDITS: tuple[tuple[str, str], ...] = tuple((line, "") for line in _UNSTAGED) + (
    (
        "        if (muni) {\n          B.cd[ip] = cd_u;\n          B.cr[ip] = cr_u;\n"
        "        } else {",
        "        (void) oa, (void) ob, (void) pa, (void) pb;    // TIMING BOUND: not staged\n"
        "        if (muni) {\n          (void) 0;\n        } else {",
    ),
    (
        "  int ii = 0, jj0 = 0;\n",
        "  static bool bound_staged = false;    // TIMING BOUND: the batch filled once\n"
        "  if (!bound_staged) {\n"
        "    std::memset(bat, 0, sizeof(Batch));\n"
        "    for (int q = 0; q < NBCAP; q++) bat->cd[q] = cd_u, bat->cr[q] = cr_u;\n"
        "    bound_staged = true;\n"
        "  }\n"
        "  int ii = 0, jj0 = 0;\n",
    ),
)


class AnchorError(ValueError):
    """An edit's anchor does not occur exactly once in the source."""


def _apply(text: str, edits, what: str) -> str:
    """Replace each anchor of ``edits``, which must occur exactly once."""
    for k, (anchor, replacement) in enumerate(edits):
        n = text.count(anchor)
        if n != 1:
            first = anchor.strip().splitlines()[0]
            raise AnchorError(
                f"edit {k}: expected the line '{first}' once in pair_mca.cpp, found it {n} times "
                f"(the pair loop changed: update {what} in this script)"
            )
        text = text.replace(anchor, replacement)
    return text


def check_probe(kind: str, count: int) -> None:
    """Raise ValueError (one line naming ``--probe``) for an unknown kind or count."""
    if kind not in PROBE_KINDS:
        raise ValueError(f"--probe: expected a kind in {', '.join(PROBE_KINDS)}, got {kind!r}")
    if not 1 <= count <= 512:
        raise ValueError(f"--probe: expected 1-512 operations per pair, got {count}")


def probe_source(text: str, kind: str, count: int) -> str:
    """Insert ``count`` operations of ``kind`` per evaluated pair into ``pair_mca.cpp``.

    Parameters
    ----------
    text : str
        The shipped ``pair_mca.cpp``.
    kind : str
        One of ``PROBE_KINDS`` (see the module's docstring).
    count : int
        Operations per evaluated pair, 1-512.

    Raises
    ------
    ValueError
        Unknown kind or count out of range.
    AnchorError
        The anchor occurs zero or several times (the pair loop changed).
    """
    check_probe(kind, count)
    head, op, tail = PROBE_CODE[kind]
    # (operation q touches its own cache lines: o = 8 q doubles = 64 q bytes into the buffer,
    # a gather's four lines from o4 = 32 q)
    body = (
        head + "".join(op.format(o=8 * q, o4=32 * q, a=q % 4, b=q % 8) for q in range(count)) + tail
    )
    return _apply(
        text,
        (
            ("using namespace LAMMPS_NS;\n", PROBE_GLOBALS + "using namespace LAMMPS_NS;\n"),
            (PROBE_ANCHOR, PROBE_ANCHOR + f"      // TIMING PROBE: {count} x {kind}\n" + body),
        ),
        "PROBE_ANCHOR",
    )


def bound_source(text: str, *, partners: bool = True, staging: bool = True) -> str:
    """Apply the timing bound's edits to the source of ``pair_mca.cpp``.

    Parameters
    ----------
    text : str
        The shipped ``pair_mca.cpp``.
    partners : bool
        False: also leave out the partners' rows (``PARTNER_EDITS``).
    staging : bool
        False: also stage no constant inputs in pass 1a (``STAGING_EDITS``).

    Raises
    ------
    AnchorError
        An anchor occurs zero or several times (the pair loop changed).
    """
    edits = EDITS + (() if partners else PARTNER_EDITS) + (() if staging else STAGING_EDITS)
    return _apply(text, edits, "EDITS, PARTNER_EDITS or STAGING_EDITS")


def main(argv: list[str] | None = None) -> int:
    """Build the bound into ``--out`` and print its path (exit 2: the edits no longer apply)."""
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", required=True, help="folder for the bound's mcaplugin.so")
    ap.add_argument(
        "--no-partners",
        action="store_true",
        help="also no partner rows: each pair reads its own automaton's row, at rest at contact "
        "distance, and adds nothing into the partner's sums (run it on a block at rest: "
        "-var vshear 0 -var temp 0, or its automata drift and the lists rebuild)",
    )
    ap.add_argument(
        "--no-staging",
        action="store_true",
        help="also stage no constant inputs in pass 1a (the batch filled once; run it on a block "
        "at rest: -var vshear 0 -var temp 0)",
    )
    ap.add_argument(
        "--probe",
        metavar="KIND:K",
        help="instead of the bound: the shipped law with K extra operations of KIND "
        f"({', '.join(PROBE_KINDS)}) per evaluated pair (timing only)",
    )
    args = ap.parse_args(argv)
    probe = None
    if args.probe is not None:
        kind, _, count = args.probe.partition(":")
        if args.no_partners or args.no_staging:
            print(
                "--probe: builds the shipped law; it does not combine with --no-partners or "
                "--no-staging",
                file=sys.stderr,
            )
            return 2
        try:
            probe = (kind, int(count))
        except ValueError:
            print(f"--probe: expected KIND:K with K an integer, got {args.probe}", file=sys.stderr)
            return 2
        try:
            check_probe(*probe)  # (before --out is created)
        except ValueError as exc:
            print(exc, file=sys.stderr)
            return 2
    try:
        Path(args.out).mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        print(
            f"--out: expected a writable folder, got {args.out} ({exc.strerror})", file=sys.stderr
        )
        return 2
    from tribolmp.errors import MissingFeatureError
    from tribolmp.lammps.plugin import SOURCE_DIR, build_plugin

    with tempfile.TemporaryDirectory(prefix="mca_bound_src_") as tmp:
        src = Path(tmp) / "plugin_src"
        shutil.copytree(SOURCE_DIR, src)
        pair = src / "pair_mca.cpp"
        try:
            text = pair.read_text()
            if probe is not None:
                pair.write_text(probe_source(text, *probe))
            else:
                pair.write_text(
                    bound_source(text, partners=not args.no_partners, staging=not args.no_staging)
                )
        except AnchorError as exc:
            print(f"mca_bound_build: {exc}", file=sys.stderr)
            return 2
        try:
            so = build_plugin(Path(args.out), source_dir=src, force=True)
        except MissingFeatureError as exc:
            print(f"mca_bound_build: {exc}", file=sys.stderr)
            return exc.exit_code
    print(so)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
