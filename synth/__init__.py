"""synth: design synthesiser for automotive timing-belt tensioners.

The Python API (``docs/sections/api.md``); every function imports what it needs when called, so
``import synth`` stays light (no numpy, pandas or solver is loaded by it):

* :func:`load` - a validated design input from any supported file (YAML, TOML, JSON, the Excel
  template, a thesis case file, or a saved result of any scene);
* :func:`synthesise` - the synthesis (``synth design``): the best catalog design for an objective;
* :func:`run_flowchart` - the thesis procedure (``synth flowchart``), or a given design checked;
* :func:`verify` - one given design (its part keys) checked through every step;
* :func:`screen` - a whole portfolio, one row per application (``synth bulk``), as a DataFrame;
* :func:`write_report` - the HTML report, its PDF and the results workbook (``synth report``);
* :func:`capability` - a design's production capability and the verdicts resting on assumptions (``synth robust``);
* :func:`derive` - each check's derivation: the margin with its numbers, the value and the limit traced through the
  physics functions, the source of every input, constant and catalog row (``synth design --explain CHECK``).

Each returns a :class:`~synth.design.result.Result` (``.verdict``, ``.parts``, ``.values``,
``.checks``, ``.to_frame()``; a notebook shows its digest) except :func:`screen` (a DataFrame) and
:func:`write_report` (the paths written). The configuration is per call: model settings are keywords
(``fidelity="screening"``, ``friction_circle=False``, ``bushing_running_in=True``, ``bolt_method="vdi2230"``,
``spring_limit_basis="en13906"``, ``catalogs=[folder]``, ``engine="numpy"``, ...: the fields of
:class:`~synth.design.settings.Settings`), design rules the ``rules=`` keyword (else the input file's ``rules:``
section); each call resolves them into one :class:`~synth.design.settings.Settings` and passes it down, so calls
in several threads (a web server, a notebook) never see each other's rules or catalogs.

The physics lives in :mod:`synth.model`, standard parts in the ``catalogs/`` CSV files, the input
schema in :mod:`synth.schema`, the registry, evaluator and result in :mod:`synth.design`, the
command-line scenes in :mod:`synth.scenes`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:  # pragma: no cover - types only
    from pathlib import Path

    import pandas as pd

    from synth.design.evaluate import Settings
    from synth.design.result import Result
    from synth.schema import DesignInput

from synth import display as _display
from synth.version import __version__

__all__ = ["load", "synthesise", "run_flowchart", "verify", "screen", "write_report", "capability", "derive", "settings",
           "Result", "DesignInput", "Settings", "InputError", "__version__"]

_LAZY = {"Result": ("synth.design.result", "Result"), "DesignInput": ("synth.schema", "DesignInput"),
         "Settings": ("synth.design.settings", "Settings"), "InputError": ("synth.errors", "InputError")}


def __getattr__(name: str) -> Any:
    """The API's types, imported on first use (``synth.Result``, ``synth.DesignInput``, ...)."""
    if name in _LAZY:
        import importlib
        module, attr = _LAZY[name]
        return getattr(importlib.import_module(module), attr)
    raise AttributeError(f"module 'synth' has no attribute {name!r}")


def _threads(fn):
    """An API function run under the command line's thread settings (:func:`synth.threads.call`: BLAS at one
    thread; a multi-threaded BLAS beside other work made small dense algebra many times slower, issue 36)."""
    import functools

    @functools.wraps(fn)
    def run(*args, **kw):
        from synth import threads
        with threads.call():
            return fn(*args, **kw)
    return run


def _result_digest(result) -> str:
    """A result's view in a notebook: the report's digest (:mod:`synth.display`)."""
    from synth.report.html import digest_html
    return digest_html(result)


_display.HTML_VIEWS["Result"] = _result_digest


def settings(**kw) -> "Settings":
    """The configuration (:class:`~synth.design.settings.Settings`) of keywords: the model settings, ``rules``,
    ``spring_limit_basis``, ``catalogs``, ``engine``; an unknown one names the accepted ones."""
    from synth import plugins
    from synth.design.settings import Settings
    from synth.errors import InputError, Problem
    plugins.load()  # the installed plug-ins' declarations (every API call resolves its configuration here)
    known = [*Settings.__dataclass_fields__, "spring_limit_basis"]
    bad = [Problem(f"setting {k}", v, "one of " + ", ".join(known)) for k, v in kw.items() if k not in known]
    if bad:
        raise InputError(bad)
    return Settings(**kw)


def load(path: "str | Path") -> "DesignInput":
    """The validated design input of ``path``: YAML, TOML, JSON, the Excel template (.xlsx), a thesis case
    file (its ``inputs:`` block) or a saved result (``--json`` of any scene: the inputs it carries).

    Bad input raises :class:`~synth.errors.InputError` naming the field (and cell, for a workbook).
    """
    from pathlib import Path

    from synth import schema
    from synth.io import documents
    data = documents.read_mapping(Path(path))
    return schema.validate({k: v for k, v in data.items() if v is not None})


def _input(d) -> "DesignInput":
    from synth.schema import DesignInput
    if isinstance(d, DesignInput):
        return d
    if isinstance(d, dict):
        from synth import schema
        return schema.validate(d)
    return load(d)


def _configure(d, rules, settings_kw: dict, samples: int | None = None) -> "Settings":
    """The configuration of an API call, resolved once: its settings keywords and design rules (``rules``: a
    mapping, a :class:`~synth.design.rules.Rules` or a rules file; else the input file ``d``'s ``rules:`` section;
    else none). ``spring_limit_basis`` given as a keyword sets the rules' basis."""
    from pathlib import Path

    from synth.design.rules import NONE, Rules, read_rules
    if rules is not None:
        found = read_rules(rules) if isinstance(rules, (str, Path)) else Rules.from_mapping(rules)
    elif isinstance(d, (str, Path)) and str(d).lower().endswith((".yaml", ".yml", ".toml", ".json")):
        found = read_rules(d, "input file", section_only=True)
    else:
        found = NONE
    return _with_targets(settings(rules=found, **settings_kw), samples)


def _with_targets(s: "Settings", samples: int | None) -> "Settings":
    """Configuration ``s`` with the design rules' capability targets (``ppk_min``, ``ppm_max``) as its capability
    target (:attr:`~synth.design.settings.Settings.capability`) when none is given, as the command line reads them
    (``--capability``/``--ppm`` first, else the rules'): a target the user set is never dropped. ``samples``: the
    Monte Carlo samples per design of such a target (None: the estimator's default)."""
    if s.capability is not None or not s.rules.capability:
        return s
    from synth.robust.settings import RobustSettings
    ppk, ppm = s.rules.targets()
    kw = {} if samples is None else {"samples": samples}
    return s.replace(capability=RobustSettings(capability=ppk, ppm=ppm, **kw))


@_threads
def run_flowchart(d: "DesignInput | str | Path | dict", parts: dict | None = None, *, rules=None,
                  **settings_kw) -> "Result":
    """The thesis procedure (steps 0-10, its selection loops) on input ``d``; with ``parts``, that design checked.

    ``d``: a :class:`~synth.schema.DesignInput`, a mapping of fields or a file (as :func:`load`).
    The result keeps 60 points of the wear histories for the report's graphs. ``rules``: design rules (a mapping,
    :class:`~synth.design.rules.Rules` or a rules file; default: the input file's ``rules:`` section).
    """
    from synth import catalog, flowchart
    s = _configure(d, rules, settings_kw)
    with catalog.using(s.catalogs):
        return flowchart.run(_input(d), s, parts=parts, time_points=60)


@_threads
def synthesise(d: "DesignInput | str | Path | dict", objective: str = "standard", solver: str = "enumerate", *,
               pin_inputs: bool = False, fix=(), free=(), top: int = 1, distinct=None,
               time_limit_s: float | None = None,
               n_trials: int = 200, rules=None, **settings_kw) -> "Result":
    """The best catalog design of input ``d`` (what ``synth design`` prints).

    ``objective``: ``standard`` (the most standardised design, cost then the margin as tie-breaks: the default
    of every scene), ``cost`` (standardisation then the margin as tie-breaks), ``margin``, a lexicographic
    ``"a,b"`` (kept as given) or weights ``"cost=1,margin=5"``; ``solver``:
    ``enumerate`` (exhaustive, exact: the default), ``minlp``, ``milp-highs``, ``milp-cvxpy``,
    ``blackbox`` (``n_trials`` per subsystem study) or ``flowchart``. An infeasible input gets the nearest design and a
    ``diagnosis`` (what binds, the smallest input relaxation).

    The parts the input names (pivot class, bushing thickness, main spring, bolt) are kept unless no design with
    them passes; ``fix`` (field names) keeps them whatever the verdict, ``pin_inputs=True`` keeps every one,
    ``free`` lets synth choose them. ``Result.changes`` says which the design does not keep, and why.
    ``top`` K > 1: ``Result.alternatives``, the K best designs in objective order that differ in a catalog part
    (rank, parts, objectives, smallest margin and what binds it, what differs from the optimum; ``distinct``: the
    part keys that count, :data:`synth.optimise.alternatives.DISTINCT_KEYS`), or for an infeasible input its K
    nearest designs by the smallest margin (each with every check it fails). ``rules``: design rules (required safety
    factors and limits, minimum margins; a mapping, :class:`~synth.design.rules.Rules` or a rules file; default:
    the input file's ``rules:`` section), echoed in ``Result.rules``; the other keywords are the configuration's
    (:class:`~synth.design.settings.Settings`: ``fidelity``, ``spring_limit_basis``, ``catalogs``, ...).
    """
    from synth import catalog
    from synth.optimise.honour import solve_honouring
    s = _configure(d, rules, settings_kw)
    kw: dict = {"settings": s, "pin_inputs": pin_inputs, "fix": fix, "free": free, "top": top,
                "distinct": distinct}
    if s.capability is not None:  # a capability target (capability=, or the rules'): the robust synthesis
        from synth.robust.synthesis import robust_for
        kw["robust"] = robust_for(s.capability)
    if solver == "blackbox":
        kw["n_trials"] = n_trials
    if time_limit_s is not None:
        kw["time_limit_s"] = time_limit_s
    with catalog.using(s.catalogs):
        return solve_honouring(_input(d), objective, solver, **kw)


@_threads
def capability(source: "Result | DesignInput | str | Path | dict", *, target: float | None = 1.33,
               ppm: float | None = None, samples: int | None = None, seed: int | None = None,
               assumptions: bool = True, rules=None, **settings_kw) -> "Result":
    """The production capability of a design (``synth robust``): ``source`` a :class:`Result` (its design), or an
    input (the design :func:`synthesise` returns for it). Returns the result with ``.robust`` set: the tolerance
    model, per check the probability of violation with its 95 % interval, Ppk, worst case, RSS and contributors,
    whether every counted check meets ``target`` (Ppk) and ``ppm``, and with ``assumptions`` the verdicts that
    flip inside the illustrative limits' ranges (``synth.robust``). A :class:`Result` is judged under its own
    configuration (its settings and rules); an input under ``rules`` and the settings keywords."""
    from synth import catalog
    from synth.design.result import Result
    from synth.robust.settings import RobustSettings
    from synth.robust.capability import add_capability
    kw = {k: v for k, v in (("samples", samples), ("seed", seed)) if v is not None}
    rs = RobustSettings(capability=target, ppm=ppm, **kw)
    r = source if isinstance(source, Result) else synthesise(source, rules=rules, **settings_kw)
    if r.parts:
        with catalog.using(settings_kw.get("catalogs")):
            add_capability(r, rs)
        if not assumptions:
            r.robust.pop("assumptions", None)
    return r


@_threads
def verify(d: "DesignInput | str | Path | dict", parts: dict, *, rules=None, **settings_kw) -> "Result":
    """Design ``parts`` (every part key: ``synth.design.space.PART_KEYS``, as any result's ``.parts``) checked
    for input ``d`` through every step, with the wear histories for the graphs (60 points)."""
    from synth import catalog
    from synth.design.space import PART_DEFAULTS, PART_KEYS
    from synth.design.verify import verify as _verify
    from synth.errors import InputError, Problem
    s = _configure(d, rules, settings_kw)
    missing = [k for k in PART_KEYS if k not in (parts or {}) and k not in PART_DEFAULTS]
    if missing:
        raise InputError(Problem("parts", ", ".join(missing) + " missing", "a dict with every part key: "
                                 + ", ".join(PART_KEYS)))
    with catalog.using(s.catalogs):
        return _verify(_input(d), dict(parts), s, time_points=60)


@_threads
def derive(source: "Result | DesignInput | str | Path | dict", check: "str | list | None" = None, *,
           parts: dict | None = None, rules=None, **settings_kw):
    """The derivation of ``check`` (a registry id; a list of ids: a list; None: every evaluated check, a list) of a
    design: a :class:`~synth.design.result.Result` (its design, inputs and configuration), or input ``source`` with
    the design ``parts`` (every part key, as :func:`verify`) under ``rules`` and the settings keywords.

    Each :class:`~synth.design.derivation.Derivation` holds the margin with its numbers, the value and the limit
    traced through the physics functions (each call's equation, arguments and result) and the source of every
    input, constant and catalog row; ``.text()`` is the terminal's, ``.as_dict()`` plain data. A bad id raises
    :class:`~synth.errors.InputError` listing the accepted ones.
    """
    from synth import catalog
    from synth.design.derivation import check_names, derivations, derive_result
    from synth.design.result import Result
    from synth.errors import InputError, Problem
    ids = None if check is None else check_names(check)
    if isinstance(source, Result):
        out = derive_result(source, ids)
    else:
        if parts is None:
            raise InputError(Problem("parts", None, "the design's parts (a result's .parts) with an input; or pass "
                                     "a Result"))
        s = _configure(source, rules, settings_kw)
        with catalog.using(s.catalogs):
            out = derivations(_input(source), dict(parts), ids, s)
    return out[0] if isinstance(check, str) else out


@_threads
def screen(applications, *, objective: str = "standard", fidelity: str = "screening", diagnose: bool = True,
           chunk_size: int | None = None, progress: bool = True, rules=None, **settings_kw) -> "pd.DataFrame":
    """Every application of a portfolio, one row each (``synth bulk`` in memory, nothing written).

    ``applications``: a portfolio file (CSV, Excel, .ods, Parquet), a DataFrame whose columns are input
    fields, or a list of design inputs (:class:`~synth.schema.DesignInput`, mappings or files). Returns the
    input columns followed by the result columns of :func:`synth.bulk.engine.columns` and ``error`` (a
    row that does not validate gets its problems there; the others run). A progress bar follows the
    chunks (a ``tqdm`` bar in Jupyter). ``rules`` (design rules: a mapping, :class:`~synth.design.rules.Rules` or a
    rules file) and the settings keywords configure every row, as :func:`synthesise`'s.
    """
    import pandas as pd

    from synth import catalog

    from synth.bulk.portfolio import read_portfolio, records
    from synth.bulk.run import compute_chunk, default_chunk_size, result_columns
    from synth.errors import InputError, Problem
    from synth.progress import Progress
    from synth.robust.settings import BULK_SAMPLES
    s = _configure(None, rules, {**settings_kw, "fidelity": fidelity}, samples=BULK_SAMPLES)  # synth bulk's
    size = default_chunk_size() if chunk_size is None else chunk_size
    if not isinstance(size, int) or isinstance(size, bool) or size < 1:
        raise InputError(Problem("chunk_size", chunk_size, "an integer >= 1"))
    if isinstance(applications, pd.DataFrame):
        table = applications.reset_index(drop=True)
        recs = records(table)
    elif isinstance(applications, (list, tuple)):
        import dataclasses
        recs = [{k: v for k, v in dataclasses.asdict(_input(a)).items() if v is not None} for a in applications]
        table = pd.DataFrame(recs)
    else:
        table = read_portfolio(applications)
        recs = records(table)
    chunks = []
    bar = Progress(total=len(recs), desc="synth screen") if progress else None
    try:
        for a in range(0, len(recs), size):
            with catalog.using(s.catalogs):
                chunks.append(compute_chunk(recs[a:a + size], objective=objective, diagnose=diagnose, settings=s))
            if bar is not None:
                bar.update(len(chunks[-1]))
    finally:
        if bar is not None:
            bar.close()
    res = pd.concat(chunks, ignore_index=True) if chunks else pd.DataFrame(columns=result_columns())
    keep = [c for c in table.columns if c not in res.columns]
    return pd.concat([table[keep].reset_index(drop=True), res], axis=1)


@_threads
def write_report(source: "Result | DesignInput | str | Path", out_dir: "str | Path", *, pdf: bool = True,
                 cad_pictures: bool = True, author: str = "", revision: str = "", page: str = "landscape",
                 platform=None, scenes: dict | None = None) -> dict:
    """The design report of ``source`` into ``out_dir``: ``report.html``, ``report.pdf``, ``results.xlsx``
    (and the 3D model's pictures in ``out_dir/cad``), as ``synth report`` writes them.

    ``source``: a :class:`~synth.design.result.Result` (reported as it is), a design input (synthesised
    first, as ``synth report INPUT`` does) or a file (an input or a saved result). Returns
    ``{"html", "pdf", "pdf_note", "xlsx", "result", "graphs", "skipped"}``.
    """
    from synth.design.result import Result
    from synth.report.document import reverified, write_files
    from synth.report.source import read_source
    from synth.schema import DesignInput
    if isinstance(source, DesignInput):
        source = synthesise(source)
    elif not isinstance(source, Result):
        from pathlib import Path
        source = Path(source)
    result, cells, name = read_source(source, _priced)
    return write_files(reverified(result, None, name), out_dir, cells=cells, name=name, scenes=scenes, cad=None,
                       show_progress=True, cad_pictures=cad_pictures, pdf=pdf, author=author, revision=revision,
                       page=page, platform=platform, application=None, robust=None, graphs=None)


def _priced(d: "DesignInput") -> "Result":
    """The synthesis of an input file :func:`write_report` reports, as ``synth report INPUT`` makes it: the default
    synthesis (:func:`synthesise`) with the design's price lines (:func:`synth.cost.decision.cost_report`)."""
    from synth.cost.decision import cost_report
    r = synthesise(d)
    r.cost = cost_report(d, r, sensitivity=False, settings=settings())
    return r
