"""Assemble docs/model.md from docs/sections/*.md and the constants CSVs.

Run ``python docs/build_model_md.py`` after editing a section or a constant;
``tests/test_docs.py`` checks the file is current.
"""

from __future__ import annotations

import csv
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
ORDER = ["00_overview", "architecture", "data_sources", "flowchart_rules", "step00_03", "plain_bushing",
         "friction_wear", "stackup", "packaging", "disc_spring", "torsion_spring", "bolted_joint", "cad",
         "optimisation", "fidelity", "robust", "control", "bulk_engine", "kernels", "kernels_axial", "performance", "bulk", "reports", "ui",
         "shrink_fit", "drive", "validation"]


def constants_table() -> str:
    lines = ["## Appendix: every named constant", "",
             "Generated from `catalogs/constants*.csv` (name, value, unit, source).", "",
             "| file | name | value | unit | source | note |", "|---|---|---|---|---|---|"]
    for path in sorted((ROOT / "catalogs").glob("constants*.csv")):
        with path.open(newline="", encoding="utf-8") as fh:
            for row in csv.DictReader(fh):
                cells = [path.name, row["name"], row["value"], row.get("unit", ""), row.get("source", ""),
                         row.get("note", "") or ""]
                lines.append("| " + " | ".join(str(c).replace("|", "/").replace("\n", " ") for c in cells) + " |")
    return "\n".join(lines) + "\n"


def _csv_table(name: str, title: str, intro: str, columns: list) -> str:
    """A generated appendix: the rows of ``catalogs/<name>.csv`` (the given columns, every row with its source)."""
    lines = [f"## {title}", "", intro, "", "| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]
    with (ROOT / "catalogs" / f"{name}.csv").open(newline="", encoding="utf-8") as fh:
        for row in csv.DictReader(fh):
            lines.append("| " + " | ".join(str(row.get(c, "") or "").replace("|", "/").replace("\n", " ")
                                           for c in columns) + " |")
    return "\n".join(lines) + "\n"


def build() -> str:
    sections = {p.stem: p for p in (ROOT / "docs" / "sections").glob("*.md")}
    names = [n for n in ORDER if n in sections] + sorted(n for n in sections if n not in ORDER)
    parts = [sections[n].read_text(encoding="utf-8").strip() + "\n" for n in names]
    tolerances = _csv_table("tolerances", "Appendix: the tolerance model",
                            "Generated from `catalogs/tolerances.csv` (section \"Production scatter\"): band in "
                            "`unit` (half-width), or `band_from` the named catalog column, constant or input.",
                            ["quantity", "kind", "band", "unit", "band_from", "source", "note"])
    ranges = _csv_table("assumption_ranges", "Appendix: plausible ranges of the illustrative limits",
                        "Generated from `catalogs/assumption_ranges.csv`: `low` and `high` are values or factors "
                        "of the catalog's value (`scale`).",
                        ["assumption", "catalog", "key", "column", "low", "high", "scale", "applies", "source",
                         "reason"])
    return "\n".join(parts) + "\n" + constants_table() + "\n" + tolerances + "\n" + ranges


if __name__ == "__main__":
    (ROOT / "docs" / "model.md").write_text(build(), encoding="utf-8")
    print("docs/model.md written")
