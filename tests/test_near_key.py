"""The one ranking of near designs (synth.design.combine: near_figures, join, near_key, nearest_choice): the
per-core choice from the options' near figures is the brute-force best over every combination, on random figures
full of ties and on case 1's own options (a restricted catalog), and every search ranks by it."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from synth.data import case_path
from synth.design.combine import best_row, join, near_figures, near_key, nearest_choice
from synth.design.evaluate import Settings
from synth.design.space import SUBSYSTEMS
from synth.io.documents import load_input
from synth.optimise.product import evaluate


def _brute(core, options):
    """Per row, the best (key, picks) over every combination of available options (``None``: a subsystem has none)."""
    out = []
    for r in range(len(core[0])):
        choices = [np.flatnonzero(o[3][r]) for o in options]
        best = None
        for combo in itertools.product(*choices):
            fig = join(tuple(float(x[r]) for x in core),
                       *((float(o[0][r, k]), float(o[1][r, k]), int(o[2][r, k])) for o, k in zip(options, combo)))
            key = near_key(fig, combo)
            if best is None or key < best[0]:
                best = (key, fig, combo)
        out.append(best)
    return out


def _random_figures(rng, n_rows, sizes):
    levels = np.array([-0.4, -0.3, -0.2, -0.1, 0.0, 0.1, 0.3])  # few values: ties everywhere

    def part(shape):
        a = rng.choice(levels, shape)
        b = np.maximum(a, rng.choice(levels, shape))
        f = (a < 0).astype(int) + (b < 0) + rng.integers(0, 2, shape) * (b < 0)
        return a, b, f
    core = part((n_rows,))
    options = []
    for k in sizes:
        a, b, f = part((n_rows, k))
        options.append((a, b, f, rng.random((n_rows, k)) < 0.85))
    return core, options


@pytest.mark.parametrize("seed", range(12))
def test_nearest_choice_is_the_brute_force_best_of_every_combination(seed):
    rng = np.random.default_rng(seed)
    core, options = _random_figures(rng, 8, (3, 4, 2, 5))
    (m1, m2, fails), picks = nearest_choice(core, options)
    for r, want in enumerate(_brute(core, options)):
        if want is None:  # a subsystem without an available option: no design
            assert m1[r] == -np.inf
            continue
        _, fig, combo = want
        assert (m1[r], m2[r], fails[r]) == fig
        assert tuple(int(p[r]) for p in picks) == combo


def test_best_row_takes_the_key_then_the_first_row():
    figures = (np.array([-0.3, -0.2, -0.2, -0.2]), np.array([0.0, -0.1, -0.05, -0.05]), np.array([1, 2, 4, 3]))
    assert best_row(figures) == 3
    assert best_row((np.array([-0.2, -0.2]), np.array([-0.1, -0.1]), np.array([2, 2]))) == 0


def test_near_figures_of_a_design_are_the_join_of_its_parts():
    rng = np.random.default_rng(1)
    m = rng.choice([-0.3, -0.1, 0.0, 0.2, np.inf], (50, 9))
    whole = near_figures(m)
    parts = [near_figures(m[:, c]) for c in (slice(0, 2), slice(2, 3), slice(3, 7), slice(7, 9))]
    assert all((x == y).all() for x, y in zip(whole, join(*parts)))


@pytest.fixture(scope="module")
def case1_restricted():
    """Case 1's evaluation on 4 cores (among them the nearest design's), each subsystem cut to a few options (the
    nearest design's, ties on the binding check and random others): small enough to enumerate every design."""
    d = load_input(case_path("case1"))
    ev = evaluate(d, Settings(), prune=False, only=[3, 11, 27, 40])
    rng = np.random.default_rng(0)
    keep = {}
    for s in SUBSYSTEMS:
        t = ev.subs[s]
        best = np.argmax(np.where(t.available, t.min_margin, -np.inf), axis=1)
        avail = np.flatnonzero(t.available.any(axis=0))
        keep[s] = np.unique(np.r_[best, rng.choice(avail, min(6, len(avail)), replace=False)])
        cut = np.zeros(t.available.shape[1], dtype=bool)
        cut[keep[s]] = True
        t.available = t.available & cut
    return ev


def test_case1_nearest_design_on_a_restricted_catalog_is_the_brute_force_best(case1_restricted):
    ev = case1_restricted
    pos, options, value = ev.nearest()
    core = ev.core_near()
    found = []
    for r, p in enumerate(ev.rows):  # every design of the restricted product, its figures joined on a grid
        choices = [np.flatnonzero(ev.subs[s].available[r]) for s in SUBSYSTEMS]
        grid = [np.reshape(c, [-1 if j == i else 1 for j in range(4)]) for i, c in enumerate(choices)]
        parts = [tuple(x[r][g] for x in ev.subs[s].near()[:3]) for s, g in zip(SUBSYSTEMS, grid)]
        a, b, f = (np.broadcast_to(x, tuple(len(c) for c in choices)).ravel()
                   for x in join(tuple(x[p] for x in core), *parts))
        combos = np.stack([np.broadcast_to(g, tuple(len(c) for c in choices)).ravel()
                           for g in grid], axis=1)
        i = np.lexsort((*combos.T[::-1], f, -b, -a))[0]
        found.append((near_key((a[i], b[i], f[i]), (r, *combos[i])), int(p), dict(zip(SUBSYSTEMS, map(int, combos[i]))),
                      (float(a[i]), float(b[i]), int(f[i]))))
    best = min(found, key=lambda x: x[0])
    assert (pos, options) == (best[1], best[2])
    assert ev.near(pos, options) == best[3] and value == best[3][0]
    assert best[3][0] == pytest.approx(-0.35216, abs=5e-5) and best[3][1] > best[3][0]  # ties broken by the 2nd
    ties = sum(x[3][0] == best[3][0] for x in found)
    assert ties > 1  # several cores tie on the smallest margin: the second and the count decide
