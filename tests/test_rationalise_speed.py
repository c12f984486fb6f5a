"""The rationalise command's speed paths (issue 36): what they leave out must not change what they write."""

from __future__ import annotations

import base64
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_arrays_path_imports_no_pyomo():
    """The default HiGHS path (the model built from arrays) solves without importing Pyomo, nor SciPy's statistics
    that Pyomo's dependency hooks import with it (about 1-2 s of a rationalise run)."""
    code = ("import sys\nfrom synth.platform.rationalise import rationalise\n"
            "from synth.platform.synthetic import synthetic_portfolio\n"
            "r = rationalise(synthetic_portfolio(8, seed=3), time_limit=30)\n"
            "print(r.status, 'pyomo' in sys.modules, 'scipy.stats' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, check=True,
                         env={"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin"}).stdout
    assert out.split() == ["optimal", "False", "False"], out


def test_tradeoff_png_drawn_once(tmp_path):
    """write_all draws the trade-off plot once: tradeoff.png is the PNG section.html embeds, byte for byte."""
    from synth.platform.outputs import write_all
    from synth.platform.rationalise import rationalise
    from synth.platform.synthetic import synthetic_portfolio
    pf = synthetic_portfolio(6, seed=1)
    r = rationalise(pf, time_limit=30)
    rows = [{"margin_floor": 0.0, "parts": 5, "cost_eur": 1.0, "worst_margin": 0.0, "served": 6, "status": "optimal"},
            {"margin_floor": 0.1, "parts": 7, "cost_eur": 2.0, "worst_margin": 0.1, "served": 6, "status": "optimal"}]
    r.tradeoff = rows
    write_all(pf, r, tmp_path, rows, "margin")
    html = (tmp_path / "section.html").read_text()
    embedded = [base64.b64decode(m) for m in re.findall(r"data:image/png;base64,([A-Za-z0-9+/=]+)", html)]
    assert (tmp_path / "tradeoff.png").read_bytes() in embedded
