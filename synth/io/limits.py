"""The resource limits of the input gate, and the bounds of every count option.

Every file synth reads is checked against these limits *before* anything
big is built from it, and every count given on the command line against
:data:`COUNTS`. They are software limits, not physics: each says why it is
what it is. The README promises that no input makes synth use more than
2 GB; the limits below are chosen so that the largest accepted input of
each kind stays well inside that (measured numbers in
``docs/sections/input_gate.md``).

>>> check_count("--points", 40)
40
>>> check_count("--points", -3)
Traceback (most recent call last):
...
synth.errors.InputError: --points: got -3; accepted: an integer in [2, 500] (margin thresholds probed: each is one catalog solve (500: about 20 s, 0.2 GB))
>>> short("x" * 500)[-25:]
'xxxxx... (500 characters)'
"""

from __future__ import annotations

import math
import reprlib
from dataclasses import dataclass

from synth.errors import InputError, Problem

__all__ = ["Limits", "LIMITS", "Count", "COUNTS", "check_count", "short", "KB", "MB"]

KB = 1024
MB = 1024 * 1024


@dataclass(frozen=True)
class Limits:
    """Limits on what one file may hold (bytes, nodes, depth, characters, rows).

    * ``text_input_bytes``: a design input, shrink-fit case or saved result is
      a few kB (the thesis input table has 60 fields; a ``synth flowchart --json``
      result about 30 kB); 8 MB leaves room for comments and long results.
    * ``workbook_bytes`` / ``workbook_unpacked_bytes`` / ``workbook_part_bytes``:
      the design-input template is about 25 kB (.xlsx) and unpacks to 70 kB
      (.xlsx) or 160 kB (.ods saved by LibreOffice), its largest part 106 kB
      (the .ods ``content.xml``); 2 MB unpacked and 512 kB per part leave room
      for notes and pasted rows. The XML readers are slow: openpyxl parses
      shared strings at about 2 s/MB and styles at 1.2 s/MB, odfpy a
      ``content.xml`` at 1.1 s/MB (measured, ``benchmarks/bench_readers.py``),
      so a part limit keeps every design workbook under about 2 s; the
      unpacked limit refuses a "zip bomb" before any XML is parsed.
    * ``sheet_rows`` / ``sheet_columns``: the template has about 70 rows and 8
      columns; a sheet whose used range claims more is not read cell by cell.
    * ``nodes``: mappings, lists and scalars in one YAML/TOML/JSON document
      *after* YAML aliases are expanded (a design input has about 70; a
      flowchart result about 1,000; a report's scene table a few thousand).
      A nine-level YAML "billion laughs" expands to 10^9 nodes and is refused
      after counting, in milliseconds, without being built.
    * ``depth``: nesting of mappings and lists (a shrink-fit case has 3 levels,
      a result 4).
    * ``string_chars``: one text value (a name, a part designation, a note).
    * ``integer_digits``: the largest integer any field needs has 7 digits
      (a durability duration in hours); a number of more than 30 digits is a
      typing error, and one of 400 digits would overflow a float.
    * ``portfolio_bytes`` / ``portfolio_rows``: a portfolio of 200,000
      applications (a whole product line's history; about 4-18 h of screening
      at the measured 3-15 applications/s) of 54 fields is a 94 MB CSV, read in
      3 s with a peak of 0.86 GB (measured); 128 MB keeps the peak about 1.2 GB.
      An .xlsx or .ods portfolio is read by calamine (Rust; openpyxl took 29 s
      and odfpy 24 s where calamine takes 3 s and 0.7 s), up to 48 MB unpacked:
      about 25,000 applications of the 54 fields in an .xlsx (38 MB for 20,000,
      read in 3.3 s), 7,500 in a pandas-written .ods; a bigger portfolio is a
      CSV or Parquet file.
    * ``catalog_bytes`` / ``catalog_rows``: a user catalog replaces a
      built-in one of at most a few hundred rows.
    """

    text_input_bytes: int = 8 * MB
    workbook_bytes: int = 16 * MB
    workbook_unpacked_bytes: int = 2 * MB
    workbook_part_bytes: int = 512 * KB
    sheet_rows: int = 2000
    sheet_columns: int = 64
    nodes: int = 200_000
    depth: int = 32
    string_chars: int = 10_000
    integer_digits: int = 30
    portfolio_bytes: int = 128 * MB
    portfolio_unpacked_bytes: int = 48 * MB
    portfolio_rows: int = 200_000
    portfolio_columns: int = 500
    catalog_bytes: int = 4 * MB
    catalog_rows: int = 100_000


LIMITS = Limits()


@dataclass(frozen=True)
class Count:
    """The accepted range of one count option of the command line, and why (the time and memory it runs in at
    its upper bound, measured: ``docs/sections/input_gate.md``, "Count options")."""

    option: str
    lo: int
    hi: int
    why: str


#: key -> the bounds of a count option (the key is the option, or ``"scene option"`` where one option of two
#: scenes sizes different work); the upper bound keeps every array that count sizes small and every run finite
COUNTS: dict[str, Count] = {k: c for k, c in (
    ("--reassemblies", Count("--reassemblies", 0, 100,
     "re-assemblies (pull-off + press-on) of the crank pulley; the paper's case has 1 (i = 2 displacements) "
     "and a pulley comes off at each timing-belt change, a handful of times in an engine's life")),
    ("--points", Count("--points", 2, 500, "margin thresholds probed: each is one catalog solve (500: about 20 s, "
                                           "0.2 GB)")),
    ("rationalise --points", Count("--points", 2, 50, "points of the trade-off curve: each is one platform MILP of "
                                                      "up to --node-limit nodes and --time-limit seconds")),
    ("rationalise --node-limit", Count("--node-limit", 1, 2**31 - 1,
     "branch-and-bound nodes per platform MILP: the reproducible limit (1: the root node only; the largest is "
     "the largest number HiGHS's mip_max_nodes takes)")),
    ("N", Count("N", 1, LIMITS.portfolio_rows, "applications in the portfolio (the largest portfolio synth bulk "
                                               "reads)")),
    ("--broken", Count("--broken", 0, LIMITS.portfolio_rows, "rows broken on purpose, at most N")),
    ("--seed", Count("--seed", 0, 2**32 - 1, "a seed of numpy's random generator")),
    ("--chunk-size", Count("--chunk-size", 1, 5_000,
     "applications per chunk; the engine keeps a chunk's design spaces and probes in memory (about 0.33 MB "
     "per application, catalogs/constants_bulk.csv), so 5,000 stay within about 2 GB")),
    ("--workers", Count("--workers", 1, 64, "worker processes (a local cluster: at most the usable cores)")),
    ("--trials", Count("--trials", 1, 100_000, "black-box trials per subsystem study")),
    ("--top", Count("--top", 1, 50, "ranked alternative designs (50: about 8 s, 0.2 GB)")),
    ("--samples", Count("--samples", 64, 262_144,
     "Monte Carlo samples of one design (2^18: about 1.1 GB; a power of two keeps the Sobol balance)")),
    ("bulk --samples", Count("--samples", 64, 2_048,
     "Monte Carlo samples per application, 64 applications at once (2^11: about 1.1 GB)")),
)}


def check_count(option: str, value, lo: int | None = None, hi: int | None = None) -> int:
    """``value`` as an int if it is a whole number within the bounds of ``option`` (a key of :data:`COUNTS`).

    ``lo``/``hi`` narrow the bounds (``--broken`` at most N). Raises
    :class:`~synth.errors.InputError` naming the option, the value and the
    accepted range.
    """
    c = COUNTS[option]
    option = c.option  # the name the user typed (a key "bulk --samples" is option --samples)
    lo = c.lo if lo is None else max(c.lo, lo)
    hi = c.hi if hi is None else min(c.hi, hi)
    accepted = f"an integer in [{lo}, {hi}] ({c.why})"
    if isinstance(value, bool):
        raise InputError(Problem(option, value, accepted))
    try:
        number = int(value)
        if isinstance(value, float) and (not math.isfinite(value) or value != number):
            raise ValueError
        if isinstance(value, str) and str(number) != value.strip().lstrip("+"):
            raise ValueError
    except (TypeError, ValueError, OverflowError):
        raise InputError(Problem(option, short(value), accepted)) from None
    if not lo <= number <= hi:
        raise InputError(Problem(option, short(value), accepted))
    return number


def short(value, limit: int = 80):
    """``value`` itself when its text is short, else an abbreviation of it (for messages).

    A message never prints a huge value (a 400-digit number, an expanded YAML
    alias, a megabyte of text): long text keeps its first characters and its
    length, containers are abbreviated by :mod:`reprlib`.
    """
    if isinstance(value, (bool, float, type(None))):
        return value
    if isinstance(value, int):
        digits = len(str(abs(value))) if value.bit_length() < 14000 else int(value.bit_length() * 0.30103) + 1
        return value if digits <= 30 else f"an integer of {digits} digits"
    if isinstance(value, str):
        return value if len(value) <= limit else f"{value[:limit]}... ({len(value)} characters)"
    text = _REPR.repr(value)
    return value if "..." not in text and len(text) <= limit else text


_REPR = reprlib.Repr()
_REPR.maxlevel, _REPR.maxlist, _REPR.maxdict, _REPR.maxtuple = 2, 6, 6, 6
_REPR.maxstring, _REPR.maxother, _REPR.maxlong = 40, 40, 30
