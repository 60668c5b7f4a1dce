"""deb.evaluate, deb.frequency_response and the studies over results:
deb.sweep, deb.compare, deb.write_report; the design studies over a budget
file: deb.uncertainty, deb.optimise, deb.sensitivity."""

import json
import os
import re
from collections.abc import Mapping

from . import _deb, _yaml
from ._errors import argument_error
from ._load import budget_of, is_text, overrides, source_text


def evaluate(budget, threads=None, *, set=None):
    """A deb.Result: budget (a deb.Budget, or what deb.load takes) evaluated as
    `deb run` evaluates it, on `threads` worker threads (None: every core;
    the numbers are the same for any count). The GIL is released meanwhile."""
    return _deb.evaluate(budget_of(budget, set), threads=threads)


def frequency_response(budget, path, f, *, threads=None):
    """H(j 2 pi f) of the budget's path named `path` at the frequencies f (Hz,
    1-D): a complex array of shape (len(f), outputs, inputs), in the path's
    output unit per input unit (the path's own channels, before any
    contributor's or output's unit conversion)."""
    return _deb.frequency_response(budget_of(budget), path, f, threads=threads)


def _sweep_section(parameters, mode):
    """The YAML text of a sweep: section; parameters is {key path: values} or
    a list of entries as in the file ({path, values | linear | log, label, unit})."""
    if isinstance(parameters, Mapping):
        entries = [{"path": str(k), "values": [v] if isinstance(v, str) else list(v)}
                   for k, v in parameters.items()]
    else:
        entries = list(parameters)
    return _yaml.dump({"sweep": {"mode": mode, "parameters": entries}})


def sweep(budget, set=None, *, parameters=None, mode="grid", threads=None):
    """Every variant of a sweep, evaluated (deb.SweepResult: .parameters,
    .values (variants x parameters), .results (deb.Result each), .csv()).

    budget      a file, a YAML text, a dict or a deb.Budget (its file or text)
    parameters  None: the budget's own `sweep:` section; else the section
                from Python: {key path or parameter name: [values]}, or a
                list of entries as in the file
    mode        "grid" (every combination) or "zip", with parameters
    set         overrides of the budget under every variant (not the sweep)
    threads     variants evaluated at a time (None: every core)
    """
    if isinstance(budget, _deb.Budget):
        budget = budget.file if budget.file is not None else budget.text
    pairs = overrides(set)
    if parameters is None:
        text = source_text(budget)
        if text is None:
            return _deb.sweep_file(os.fspath(budget), pairs, threads)
        return _deb.sweep_text(text[0], text[1], text[2], pairs, threads)
    if isinstance(budget, Mapping):
        if "sweep" in budget:
            raise argument_error("parameters", "the budget has a sweep section already")
        text, name, base_dir = _yaml.dump(budget), "<dict>", "."
    elif isinstance(budget, str) and is_text(budget):
        text, name, base_dir = budget, "<text>", "."
    elif isinstance(budget, (str, os.PathLike)):
        name = os.fspath(budget)
        try:
            with open(name, encoding="utf-8") as f:
                text = f.read()
        except OSError as e:
            raise argument_error("budget", f"cannot read {name}: {e.strerror}") from None
        base_dir = os.path.dirname(name) or "."
    else:
        raise argument_error("budget", f"expected a file name, a YAML text, a dict or a deb.Budget, "
                                       f"got {type(budget).__name__}")
    if re.search(r"^sweep\s*:", text, re.MULTILINE):
        raise argument_error("parameters", "the budget has a sweep section already")
    # Appended after the budget's last line: its own lines keep their numbers in messages.
    text = text.rstrip("\n") + "\n" + _sweep_section(parameters, mode)
    return _deb.sweep_text(text, name, base_dir, pairs, threads)


def _result_of(value, threads=None):
    return value if isinstance(value, _deb.Result) else evaluate(value, threads)


def compare(a, b, *, label_a=None, label_b=None, tolerance=None, threads=None):
    """A deb.Comparison of two results (deb.Result, or budgets evaluated here):
    per output, contributor and band the RMS of each, B - A and B / A
    (.figures, .largest_changes(), .moved(rel), .json(), .csv()), as deb
    compare; labels default to the budgets' names, tolerance is deb compare
    --tolerance's (recorded in .json(); .moved(tolerance) lists what moved)."""
    ra, rb = _result_of(a, threads), _result_of(b, threads)
    return _deb.compare(ra, rb, label_a or ra.name, label_b or rb.name, tolerance)


def write_report(budget_or_result, directory, *, set=None, plots=True, formats=("png", "pdf"), asd=False,
                 reverse_cps=False, digits=4, force=False, exports=(), threads=None):
    """The report directory of `deb run` (summary.json, result.h5, index.html,
    report.md, report.pdf, plots/) for a deb.Result, or for a budget (a
    deb.Budget, a file, a text or a dict) evaluated first. Options as deb
    run's: plots=False is --no-plots (gnuplot is not needed), formats
    --format, exports --export ("csv", "mat", "xlsx"), force --force.
    Replaces `directory` atomically, only if deb wrote it (unless force).
    Returns {"files": [...], "plots": [...], "pdf_pages": n}."""
    result = budget_or_result if isinstance(budget_or_result, _deb.Result) else evaluate(budget_or_result, threads,
                                                                                          set=set)
    return _deb.write_report(result, os.fspath(directory), plots, list(formats), asd, reverse_cps, digits, force,
                             list(exports), threads)


def to_dict(result):
    """summary.json of the result as a dict: the text deb run writes
    (deb::SummaryJson), parsed."""
    return json.loads(result.summary_json())


def _budget_file(budget):
    """The file of a budget given as a path or a deb.Budget loaded from one."""
    if isinstance(budget, _deb.Budget):
        if budget.file is None:
            raise argument_error("budget", "uncertainty, optimise and sensitivity read a budget file; this one "
                                           "was loaded from a text or a dict")
        return budget.file
    if isinstance(budget, (str, os.PathLike)) and not (isinstance(budget, str) and is_text(budget)):
        return os.fspath(budget)
    raise argument_error("budget", f"expected a budget file name or a deb.Budget loaded from one, "
                                   f"got {type(budget).__name__}")


def uncertainty(budget, *, samples=1000, method="mc", seed=1, threads=None, set=None):
    """The uncertainty study of `deb uncertainty` (docs/uncertainty.md): the
    budget's parameters with a distribution sampled (method "mc", "lhs" or
    "sobol"), every sample's budget evaluated (the GIL released).

    Returns the summary.json dict deb uncertainty writes (parameters,
    metrics with mean, sd, percentiles, P(meet) and its 95 % Wilson
    interval, drivers, worst corners), plus "sample_parameters" (samples x
    parameters, in their units), "sample_metric_names" and "sample_metrics"
    (samples x metrics, each an RMS): numpy arrays of every sample.
    The same seed gives the same numbers for any thread count."""
    summary, parameters, names, metrics = _deb.uncertainty_file(_budget_file(budget), overrides(set), int(samples),
                                                                str(method), int(seed), threads)
    out = json.loads(summary)
    out["sample_parameters"] = parameters
    out["sample_metric_names"] = names
    out["sample_metrics"] = metrics
    return out


def optimise(budget, vary, *, objective=None, method="auto", starts=1, max_evaluations=200, tolerance=1e-8,
             seed=1, robust=None, robust_samples=64, threads=None, set=None):
    """The design optimisation of `deb optimise` (docs/optimise.md): the
    parameters `vary` (names, each with min and max in the budget) chosen to
    minimise `objective` (an output's name, a weighted sum such as
    "z + 0.5*x", or "max-ratio"; None: the only
    output, else max-ratio) with every requirement met. robust=95 minimises
    the 95th percentile under the other parameters' tolerances.

    Returns the summary.json dict deb optimise writes ("optimum": values,
    objective, requirements with "active"; "starts_run"; ...), plus "history"
    (history.csv's text: every evaluation)."""
    if isinstance(vary, str):
        vary = [v.strip() for v in vary.split(",")]
    summary, history = _deb.optimise_file(_budget_file(budget), [str(v) for v in vary], overrides(set),
                                          None if objective is None else str(objective), str(method), int(starts),
                                          int(max_evaluations), float(tolerance), int(seed),
                                          None if robust is None else float(robust), int(robust_samples), threads)
    out = json.loads(summary)
    out["history"] = history
    return out


def sensitivity(budget, parameters, *, step=1e-3, central_differences=False, threads=None, set=None):
    """The derivatives of `deb sensitivity` (docs/cli.md): d var / d ln p of
    every output's total and contributors for each parameter (a name from
    `parameters:` or a key path), on the nominal grid: exact where the
    parameter acts only through rational paths' realisations, else by
    central differences of relative step `step` (central_differences=True:
    for every parameter).

    Returns {"sensitivities": [{parameter, output, unit, contributor,
    variance, d_variance_d_log_p, elasticity, method}, ...] in the order of
    sensitivity.csv, "methods": {parameter: {"exact": bool, "note": str}}}."""
    if isinstance(parameters, str):
        parameters = [parameters]
    rows, methods = _deb.sensitivity_file(_budget_file(budget), [str(p) for p in parameters], overrides(set),
                                          float(step), bool(central_differences), threads)
    return {"sensitivities": list(rows),
            "methods": {m["parameter"]: {"exact": m["exact"], "note": m["note"]} for m in methods}}
