"""Assemble docs/model.md from docs/sections/*.md and the constants CSVs.

Run ``python docs/build_model_md.py`` after editing a section or a constant;
``tests/test_docs.py`` checks the file is current.
"""

from __future__ import annotations

import csv
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
ORDER = ["00_overview", "architecture", "data_sources", "step00_03", "plain_bushing", "friction_wear", "stackup",
         "packaging", "disc_spring", "torsion_spring", "bolted_joint", "cad",
         "optimisation", "fidelity", "bulk_engine", "kernels", "bulk", "reports", "shrink_fit", "validation"]


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


def build() -> str:
    sections = {p.stem: p for p in (ROOT / "docs" / "sections").glob("*.md")}
    names = [n for n in ORDER if n in sections] + sorted(n for n in sections if n not in ORDER)
    parts = [sections[n].read_text(encoding="utf-8").strip() + "\n" for n in names]
    return "\n".join(parts) + "\n" + constants_table()


if __name__ == "__main__":
    (ROOT / "docs" / "model.md").write_text(build(), encoding="utf-8")
    print("docs/model.md written")
