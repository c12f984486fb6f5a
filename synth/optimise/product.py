"""The catalog product of one application through the one evaluator: feasibility, margins and scores as tables.

:func:`evaluate` runs the groups of :mod:`synth.design.evaluate` over the
decomposed design space of :mod:`synth.design.space` for one application:
the core group over every core the application may use, then each subsystem
over (core x option) rows, and keeps, per pair, what the solvers need: the
feasibility, the smallest margin counted in the margin objective, the
smallest margin of all (the nearest design), and the additive scores. No
formula lives here: margins are the registry's, values the evaluator's.

* ``prune=True`` evaluates the subsystems only for the cores that pass their
  own constraints (the others cannot be completed into a feasible design);
  ``prune=False`` evaluates all cores (infeasibility diagnosis).
* The main spring sees a core only through its key (torque, housing height
  and diameters): springs are evaluated once per distinct key, in blocks that
  bound the memory, and only within the mean-diameter range of the housings.

>>> from synth.data import case_path
>>> from synth.io.documents import load_input
>>> ev = evaluate(load_input(case_path("case1_as_run")))
>>> ev.core.values["hubload_nominal_n"][0].round(1), sorted(ev.subs)
(np.float64(652.5), ['axial', 'bolt', 'bushing', 'spring'])
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from synth.design.combine import best_row, join, nearest_choice
from synth.design.evaluate import DEFAULT, Group, Settings, axial_full, core, inputs
from synth.design.applications import Applications
from synth.design.space import SUBSYSTEMS, Space, core_rows, space, space_for
from synth.design.subsystems import SPRING_BLOCK_PAIRS, SubTable, evaluate_axial, family
from synth.design.verify import parts_of_design
from synth.cost.breakdown import attributes
from synth.optimise.objectives import additive_goals, additive_totals, goal

__all__ = ["SubTable", "Evaluation", "evaluate", "subsystem", "SPRING_BLOCK_PAIRS", "design_scores",
           "core_scores", "option_scores", "design_totals", "core_near", "nearest_of", "judge_undecided"]

@dataclass
class Evaluation:
    """The evaluated design space of one application (``apps`` holds it as application 0)."""

    inputs: object
    apps: Applications
    space: Space
    settings: Settings
    cores: np.ndarray           # core table rows the application may use
    input: Group              # the input-only group (one row): a failure there makes every design infeasible
    core: Group               # the core group over ``cores``
    rows: np.ndarray            # positions in ``cores`` whose subsystems were evaluated
    subs: dict                  # subsystem -> SubTable over (rows, options)
    score_core: dict            # additive goal -> (len(cores),)
    score: dict                 # subsystem -> additive goal -> (n_options,)
    notes: list = field(default_factory=list)
    evaluations: int = 0

    def core_feasible(self) -> np.ndarray:
        """``(len(cores),)``: the core's own constraints and the input-only ones pass."""
        return self.core.ok() & bool(self.input.ok()[0])

    def any_feasible(self) -> bool:
        """Whether some design of the evaluated space meets every constraint: a feasible core (evaluated) with a
        feasible option in every subsystem."""
        ok = self.core_feasible()[self.rows]
        for s in SUBSYSTEMS:
            ok = ok & self.subs[s].feasible.any(axis=1)
        return bool(ok.any())

    def core_margin(self) -> np.ndarray:
        """Smallest margin of the core counted in the margin objective (input-only constraints never are)."""
        return self.core.min_margin()

    def core_min_margin(self) -> np.ndarray:
        """Smallest margin of every constraint of the core and of the inputs (the nearest design)."""
        return np.minimum(self.core.min_margin(objective_only=False), float(self.input.min_margin(False)[0]))

    def core_near(self) -> tuple:
        """``(len(cores),)`` near figures of every core with the input-only checks
        (:func:`synth.design.combine.join` of the core's and the inputs')."""
        return core_near(self.core, self.input, np.zeros(len(self.cores), dtype=np.int64))

    def near(self, pos: int, options: dict) -> tuple:
        """The near figures of the design of core position ``pos`` and option rows ``options`` (the one key's:
        :func:`synth.design.combine.near_key`)."""
        r = int(np.flatnonzero(self.rows == pos)[0])
        core = tuple(x[pos] for x in self.core_near())
        return join(core, *((t.min_margin[r, o], t.second[r, o], t.fails[r, o])
                            for t, o in ((self.subs[s], options[s]) for s in SUBSYSTEMS)))

    def nearest(self) -> tuple:
        """``(core position, options, smallest margin)`` of the nearest design over the evaluated cores: the best
        under the one key of near designs (:func:`synth.design.combine.near_key`: the largest smallest margin of
        every counted check, then the largest second smallest, then the fewest failing checks, then the catalog
        order), exact over the product without enumerating it (:func:`synth.design.combine.nearest_choice` per
        core, :func:`~synth.design.combine.best_row` over them)."""
        return nearest_of(tuple(x[self.rows] for x in self.core_near()), self.subs, self.rows)

    def parts(self, pos: int, options: dict) -> dict:
        """The part keys of core position ``pos`` (in ``cores``) and option rows ``options``."""
        return parts_of_design(self.space, self.cores[pos], options, self.core.values, pos)

    def objective_values(self, pos: int, options: dict, margin: float) -> dict:
        """``{standard, cost, ..., margin}`` of a design given by positions (every additive goal, and the margin)."""
        return {**design_totals({k: v[pos] for k, v in self.score_core.items()},
                                [{k: v[options[s]] for k, v in self.score[s].items()} for s in SUBSYSTEMS]),
                "margin": margin}


def core_near(cg: Group, ig: Group, a) -> tuple:
    """The near figures of core group ``cg``'s rows with their applications' input-only checks (``ig``: the input
    group, one row per application; ``a``: each core row's application in it): :func:`~synth.design.combine.join`
    of the two groups' assessments."""
    return join(cg.assessment().near, tuple(x[a] for x in ig.assessment().near))


def nearest_of(core: tuple, subs: dict, rows) -> tuple:
    """``(row, options, smallest margin)`` of the nearest design over cores ``rows`` (any labels, one per core):
    ``core`` their near figures with the input-only checks (:func:`synth.design.combine.join`), ``subs`` their
    subsystems' :class:`SubTable` (one row per core): :func:`~synth.design.combine.nearest_choice` per core,
    :func:`~synth.design.combine.best_row` over them (:meth:`Evaluation.nearest`; the bulk's from its own
    groups, :func:`synth.optimise.batch_nearest.nearest`)."""
    figures, picks = nearest_choice(core, [subs[s].near() for s in SUBSYSTEMS])
    r = best_row(figures)
    return int(rows[r]), {s: int(p[r]) for s, p in zip(SUBSYSTEMS, picks)}, float(figures[0][r])


#: the note of an application without its durability test (the checks that need it are not verified)
DURABILITY_NOTE = "durability test not given: bushing, plastic wear and spring fatigue checks are not verified"


def core_scores(sp: Space, cores, core_values: dict) -> dict:
    """Every additive goal's scores (:func:`synth.optimise.objectives.additive_goals`) of core rows ``cores``
    (``core_values``: the core group's values at those rows, at least :func:`~synth.optimise.objectives.core_reads`)."""
    return {g.name: g.core(sp, cores, core_values) for g in additive_goals()}


def option_scores(sp: Space, table: str, stiffness_nm_per_deg=None, options=None) -> dict:
    """Every additive goal's scores of the options of a subsystem (``options`` None: every row; the spring's cost
    needs the stiffness)."""
    return {g.name: g.option(sp, table, options, stiffness_nm_per_deg) for g in additive_goals()}


def design_totals(core: dict, options) -> dict:
    """A design's additive goals as results show them: its core's scores plus its options' (in
    :data:`~synth.design.space.SUBSYSTEMS` order), each rounded as its goal says."""
    return {name: goal(name).total(v) for name, v in additive_totals(core, options).items()}


def judge_undecided(apps, sp, cg, pos, core_ok, settings, subs: dict) -> None:
    """At fidelity ``screening`` (the axial table screened, then judged: :func:`synth.design.evaluate.axial_judged`),
    "no design" must be the full model's verdict too: when no core is complete (a feasible option in every
    subsystem) but some lack only an axial option, the axial table takes the full model's verdicts
    (:func:`synth.design.evaluate.axial_full`: the screening model may reject options the full model passes), as
    :meth:`synth.optimise.batch.Batch.optimum` searches such an application again. In place."""
    if settings.judge is settings or not len(pos):
        return
    has = {s: t.feasible.any(axis=1) for s, t in subs.items()}
    if np.logical_and.reduce([core_ok, *has.values()]).any():
        return
    if np.logical_and.reduce([core_ok, *(v for s, v in has.items() if s != "axial")]).any():
        subs["axial"] = evaluate_axial(axial_full)(apps, sp, cg, pos, settings, family("axial"))[0]


def subsystem(apps, sp: Space, cg: Group, pos, name: str, settings: Settings, span=None) -> tuple[SubTable, int]:
    """Subsystem ``name`` of the core rows ``pos`` of core group ``cg`` against every option of ``sp``'s table
    ``name`` (the design space's, or any table of option columns: a black-box search's proposals), by its declaration
    (:mod:`synth.design.subsystems`).

    Returns the :class:`SubTable` over ``(len(pos), options)`` and the number of (row, option) pairs the
    evaluator computed (main springs: per distinct key, within the housings' mean-diameter window).
    """
    return family(name).run(apps, sp, cg, pos, settings, span=span)


def evaluate(d, settings: Settings = Settings(fidelity="full"), *, pin_inputs: bool = False,
             prune: bool = True, subsystems: bool = True, only=None, tables: dict | None = None) -> Evaluation:
    """Evaluate the design space of input ``d`` (see the module docstring).

    ``only``: the positions (in the application's cores) whose subsystems are evaluated (the bulk's nearest design:
    the cores that may tie on the smallest margin), each against the options it would meet without ``only`` (the
    main springs searched span the housings of the cores ``prune`` keeps). ``tables``: subsystem -> its
    :class:`SubTable` over ``pos`` computed elsewhere (the bulk's from its own kept values and compiled kernels).

    ``subsystems=False`` evaluates the inputs and the cores only (a black-box search evaluates its own
    proposals with :func:`subsystem`).
    """
    apps = Applications.of([d])
    sp = space_for(d, pin_inputs)
    cores = core_rows(sp, d)
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
        ig = inputs(apps, np.zeros(1, dtype=np.int64), settings)
        cg = core(apps, np.zeros(len(cores), dtype=np.int64), sp.rows("core", cores), settings)
        ok = cg.ok() & bool(ig.ok()[0])
        all_pos = np.flatnonzero(ok) if prune else np.arange(len(cores))
        pos = all_pos if only is None else np.asarray(only, dtype=np.int64)
        counter = [len(cores)]
        subs = {}
        if subsystems:
            for s in SUBSYSTEMS:
                if tables and s in tables:
                    subs[s], n = tables[s], 0
                else:
                    subs[s], n = subsystem(apps, sp, cg, pos, s, settings, span=None if only is None else all_pos)
                counter[0] += n
            judge_undecided(apps, sp, cg, pos, ok[pos], settings, subs)
    score_core = core_scores(sp, cores, cg.values)
    score = {s: option_scores(sp, s, float(apps.spring_stiffness_nm_per_deg[0])) for s in SUBSYSTEMS}
    notes = []
    if not apps.met("durability")[0]:
        notes.append(DURABILITY_NOTE)
    return Evaluation(d, apps, sp, settings, cores, ig, cg, pos, subs, score_core, score, notes, counter[0])


def design_scores(d, parts: dict, settings: Settings = DEFAULT) -> dict:
    """The additive goals (``{standard, cost, ...}``) of the design ``parts`` of input ``d``, priced at its annual
    volume: the core's score, then the bushing's, the axial group's, the bolt's and the main spring's added in turn."""
    attrs = attributes(d, parts)[1]  # priced at the input's annual volume
    apps = Applications.of([d])
    cg = core(apps, np.zeros(1, dtype=np.int64), attrs["core"], settings)
    sp = Space(attrs, space().parts)
    one = np.zeros(1, dtype=np.int64)
    k = float(apps.spring_stiffness_nm_per_deg[0])
    out = {}
    for g in additive_goals():
        v = float(g.core(sp, one, {n: cg.values[n] for n in g.reads})[0])
        for s in ("bushing", "axial", "bolt", "spring"):
            v += float(g.option(sp, s, one, k)[0])
        out[g.name] = g.total(v)
    return out
