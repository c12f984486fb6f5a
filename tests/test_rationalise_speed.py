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


def _chunk(n: int, seed: int):
    """The producer's inputs for the groups of a chunk of ``n`` generated applications: ``(apps, cg, rep)``."""
    import numpy as np
    from synth.data.generated_applications import generate
    from synth.design import evaluate
    from synth.design.applications import Applications
    from synth.design.space import core_rows
    from synth.platform import producer as P
    from synth.platform.options import catalogue
    inputs = generate(n, seed=seed)
    sp = catalogue().space
    apps = Applications.of(inputs)
    with np.errstate(all="ignore"):
        per_app = [core_rows(sp, d) for d in inputs]
        a = np.concatenate([np.full(len(c), i, dtype=np.int64) for i, c in enumerate(per_app)])
        crow = np.concatenate(per_app).astype(np.int64)
        cg = evaluate.core(apps, a, sp.rows("core", crow), evaluate.DEFAULT)
        pos = np.flatnonzero(cg.ok() & evaluate.inputs(apps, np.arange(n), evaluate.DEFAULT).ok()[a])
    extra = {"pad_code": sp.tables["core"]["pad_code"][crow]}
    rep = {s: P._group_ids(cg.values, pos, k, extra)[1] for s, k in P.group_keys(cg.values).items()}
    return apps, cg, rep, extra


def test_compiled_spring_rounds_equal_the_block_path():
    """The main-spring stages' compiled rounds (one pass: window, margins, stage minimum, record, and the exact skip
    of a pair whose cheap margins already fail below its group's best) give the block path's feasible options,
    margins, bindings and nearest springs, bit for bit, and judge the same pairs."""
    import numpy as np
    from synth.design import evaluate
    from synth.platform import producer as P
    from synth.platform.options import catalogue
    apps, cg, rep, _ = _chunk(24, seed=7)
    got = {}
    for compiled in (True, False):
        acc = P.Pairs(len(rep["spring"]))
        n = P._spring(apps, catalogue(), cg, rep["spring"], evaluate.DEFAULT, acc, compiled_rounds=compiled)
        got[compiled] = (n, acc.by_group(len(rep["spring"])), acc.best, acc.best_b, acc.evaluated)
    (n1, g1, b1, bb1, e1), (n0, g0, b0, bb0, e0) = got[True], got[False]
    assert n1 == n0 and n1[0] > 1000
    for x, y in zip(g1, g0):
        np.testing.assert_array_equal(x, y)
    np.testing.assert_array_equal(b1, b0)
    np.testing.assert_array_equal(bb1, bb0)
    np.testing.assert_array_equal(e1, e0)
    assert len(g1[1]) > 0 and (b1 < 0).any()   # feasible springs, and keys whose nearest spring fails


def test_wear_on_distinct_rows_equals_every_row(monkeypatch):
    """The compiled wear run once per distinct input row (:func:`synth.kernels.axial.distinct_rows`) gives every
    row's values bit for bit: the producer's axial group on a chunk with and without it."""
    import numpy as np
    from synth.design import evaluate
    from synth.kernels import axial
    from synth.platform.options import catalogue
    apps, cg, rep, extra = _chunk(12, seed=3)
    cat = catalogue()
    r = rep["axial"]
    pad = extra["pad_code"][r]
    g = np.repeat(np.arange(len(r)), np.where(pad < 0, 1, cat.n_axial_real))
    j = np.arange(len(g)) - np.searchsorted(g, g)
    o = np.where(pad[g] < 0, cat.axial_none, cat.axial_option(np.maximum(pad[g], 0), j))
    rows = cat.space.rows("axial", cat.option_row["axial"][o])
    seen = []
    distinct = axial.distinct_rows
    monkeypatch.setattr(axial, "distinct_rows", lambda cols: seen.append(distinct(cols)) or seen[-1])
    out = {}
    for share in (0.9, 0.0):   # 0.0: every row evaluated
        monkeypatch.setattr(axial, "DISTINCT_SHARE", share)
        out[share] = evaluate.axial(apps, cg, r[g], rows, evaluate.DEFAULT, engine="numba")
    keep, back = seen[0]
    assert keep is not None and len(keep) < 0.9 * len(back)   # rows do repeat: the wear ran on fewer
    assert seen[1] == (None, None)
    for k in evaluate.PLASTIC_WEAR_VALUES:
        np.testing.assert_array_equal(out[0.9].values[k], out[0.0].values[k], err_msg=k)
        assert np.isfinite(out[0.9].values[k]).sum() > 100, k
    for k, m in out[0.9].margins.items():
        np.testing.assert_array_equal(m, out[0.0].margins[k], err_msg=k)
