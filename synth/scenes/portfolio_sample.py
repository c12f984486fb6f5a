"""``synth portfolio-sample N --out FILE``: a synthetic portfolio of N applications.

The applications span the input ranges of the thesis's applications (two
families: belt-in-oil with axial damping like case 1, dry with radial damping
only like case 3; see :mod:`synth.data.generated_applications`). ``--broken K``
breaks K rows on purpose (missing required field, out-of-range value, unknown
choice, non-numeric text) to try the error reporting of ``synth bulk``.
"""

from __future__ import annotations

from synth.bulk.portfolio import write_table
from synth.bulk.sample import sample_portfolio
from synth.bulk.portfolio import FORMATS
from synth.errors import InputError, Problem
from synth.io.limits import check_count

__all__ = ["register"]


def register(sub) -> None:
    p = sub.add_parser("portfolio-sample", help="write a synthetic portfolio of N applications (for synth bulk)")
    p.add_argument("n", metavar="N", help="number of applications (1-200000)")
    p.add_argument("--out", required=True, metavar="FILE", help="portfolio table (.csv, .xlsx, .ods or .parquet)")
    p.add_argument("--seed", default=0, help="random seed, 0 to 2**32-1 (the same seed gives the same portfolio)")
    p.add_argument("--broken", default=0, metavar="K", help="rows to break on purpose (bad data), 0 to N")
    p.set_defaults(func=_main)


def _main(args) -> int:
    from pathlib import Path

    n = check_count("N", args.n)
    seed = check_count("--seed", args.seed)
    broken = check_count("--broken", args.broken, hi=n)
    out = Path(args.out)
    if out.suffix.lower() not in FORMATS:
        raise InputError(Problem("--out", args.out, "a file ending in " + ", ".join(sorted(FORMATS))))
    if out.is_dir():
        raise InputError(Problem("--out", args.out, "a file name, not a folder"))
    table = sample_portfolio(n, seed=seed, broken=broken)
    path = write_table(table, out)
    print(f"synth portfolio-sample: {len(table)} applications ({broken} broken on purpose) -> {path}")
    return 0
