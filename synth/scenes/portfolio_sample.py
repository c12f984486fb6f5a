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

__all__ = ["register"]


def register(sub) -> None:
    p = sub.add_parser("portfolio-sample", help="write a synthetic portfolio of N applications (for synth bulk)")
    p.add_argument("n", type=int, metavar="N", help="number of applications")
    p.add_argument("--out", required=True, metavar="FILE", help="portfolio table (.csv, .xlsx or .parquet)")
    p.add_argument("--seed", type=int, default=0, help="random seed (the same seed gives the same portfolio)")
    p.add_argument("--broken", type=int, default=0, metavar="K", help="rows to break on purpose (bad data)")
    p.set_defaults(func=_main)


def _main(args) -> int:
    table = sample_portfolio(args.n, seed=args.seed, broken=args.broken)
    path = write_table(table, args.out)
    print(f"synth portfolio-sample: {len(table)} applications ({args.broken} broken on purpose) -> {path}")
    return 0
