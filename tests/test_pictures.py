"""The README's pictures show what today's code decides: docs/img/pictures.json (written with the pictures by
docs/build_pictures.py) against the same facts recomputed by the cheap paths: case 1's stored synthesis re-verified
(synthesising it again takes 18 s: ``python docs/build_pictures.py --check`` does), the default application
synthesised, the flowchart run; no Chromium, no CadQuery."""

from __future__ import annotations

import importlib.util
import json
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
README = (ROOT / "README.md").read_text(encoding="utf-8")
RUN = "run python docs/build_pictures.py"


def _build():
    spec = importlib.util.spec_from_file_location("build_pictures", ROOT / "docs" / "build_pictures.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


BP = _build()
MANIFEST = json.loads(BP.MANIFEST.read_text(encoding="utf-8"))


def test_every_readme_picture_has_its_command_and_facts():
    used = set(re.findall(r"docs/img/([\w-]+)\.png", README))
    assert used == set(BP.COMMANDS), "README pictures and docs/build_pictures.py's COMMANDS differ"
    for name in used:
        assert (BP.IMG / f"{name}.png").is_file(), f"docs/img/{name}.png missing: {RUN}"
        assert MANIFEST.get(name, {}).get("command") == BP.COMMANDS[name], f"{name}: its command changed: {RUN}"
        assert MANIFEST[name]["facts"], name


@pytest.mark.parametrize("name", sorted(BP.FACTS))
def test_a_picture_shows_what_the_code_decides_today(name):
    stored = MANIFEST[name]["facts"]
    today = json.loads(json.dumps(BP.FACTS[name](stored["parts"])))  # the stored design, re-verified
    assert today == stored, f"docs/img/{name}.png shows what the code no longer decides: {RUN}\n" \
                            f"stored {stored}\ntoday  {today}"


def test_the_ui_picture_shows_the_edit_the_readme_describes():
    f = MANIFEST["ui_design"]["facts"]
    assert f["edit"] == {"spring_stiffness_nm_per_deg": 0.02}
    assert "stiffness edited from 0.0164 to 0.02 Nm/deg" in README
    turned = f["turned_red"]
    said = re.search(r"stiffness edited from 0.0164 to 0.02 Nm/deg: ([^.]*)\.", README).group(1)
    assert said == _ui_sentence(turned), f"README's web example says '{said}'; the picture shows {turned}"


def _ui_sentence(turned: list) -> str:
    from synth.design.constraints import REGISTRY
    if not turned:
        return "no check changes verdict"
    names = ", ".join(REGISTRY[c].label for c in turned)
    return f"{len(turned)} check{'s' if len(turned) > 1 else ''} turn{'' if len(turned) > 1 else 's'} red ({names})"


def test_the_platform_picture_is_the_readme_examples():
    """The trade-off picture is of the README's rationalise example, whose printed line tests/test_readme.py checks
    against today's code (a rationalisation is too slow to repeat here): the manifest holds that line and the
    README's sentence about the curve reads the manifest's numbers."""
    f = MANIFEST["platform_tradeoff"]["facts"]
    assert f["summary_line"] in README, f"the trade-off picture is of another rationalisation: {RUN}"
    rows = f["rows"]
    m = re.search(r"grows from (\d+) to (\d+) parts to give the (\d+) applications that can have one a margin "
                  r"of (\d+) %", README)
    assert m, "README's sentence about the trade-off curve"
    first, last, served, pct = map(int, m.groups())
    at = [r for r in rows if round(100 * r["margin_floor"]) == pct]
    assert (rows[0]["parts"], at[0]["parts"], at[0]["served"]) == (first, last, served), \
        f"README's trade-off sentence differs from the picture's rows {rows}"
