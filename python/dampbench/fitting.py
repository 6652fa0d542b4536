"""fit: `dampbench fit` on Records or files, returning what `dampbench fit --format json` prints as a FitResult."""
import json
from dataclasses import dataclass, field

import numpy as np

from dampbench import _core
from dampbench.records import as_records, key_values, loader_args


@dataclass
class FitResult:
    """A fit: the best run's parameters and metrics, the verdict on the runs, identifiability, history and runs.

    params: {name: value in SI} of the best run; metrics: {metric: value} at them; converged and verdict: the
    convergence verdict on the runs (convergence holds its figures); identifiability: per parameter std_error,
    relative_error and flags (identifiable is True when no flag is raised), and the correlation matrix; history: per
    run an array of (evaluations, best so far) where it improved; runs: per run best_value, evaluations, stop and
    best_params. `json` is the whole of what `dampbench fit --format json` prints for the same fit.
    """
    model: str
    params: dict
    metrics: dict
    converged: bool
    verdict: str
    convergence: dict
    identifiability: dict
    correlation: np.ndarray
    history: list
    runs: list
    budget: dict
    json: dict = field(repr=False)

    @classmethod
    def from_json(cls, j):
        ident = j["identifiability"]
        correlation = np.array([[np.nan if c is None else c for c in row] for row in ident["correlation"]], dtype=float)
        history = [np.array(points, dtype=float).reshape(-1, 2) for points in j["history"]]
        return cls(model=j["model"], params=j["best_params"], metrics=j["metrics"],
                   converged=j["convergence"]["converged"], verdict=j["convergence"]["verdict"],
                   convergence=j["convergence"], identifiability=ident, correlation=correlation, history=history,
                   runs=j["run_results"], budget=j["budget"], json=j)


def _bounds_text(bounds):
    if bounds is None or isinstance(bounds, str):
        return bounds or ""
    return ",".join(f"{name}={float(lo)!r}:{float(hi)!r}" for name, (lo, hi) in bounds.items())


def _laws_text(laws):
    if laws is None or isinstance(laws, str):
        return laws or ""
    return ";".join(f"{name}={law}" for name, law in laws.items())


def fit(model, records, *, laws=None, bounds=None, metric="of_abs", optimizer=None, optimizer_settings=None,
        pop=None, iters=None, runs=None, budget=None, max_evals=None, max_seconds=None, seed=1, start=None,
        precision="mixed", predict=(), folds=None, reference=None, report=None, save_model=None, threads=None, isa=None,
        units=None, columns=None, transform=None, average_cycles=None, conditions=None, set=None):
    """Identifies `model` on one or more records, as `dampbench fit` with the same options and defaults.

    records: a Record, a file path, or a list of them (files read with the loader options units, columns,
    transform, average_cycles, conditions, set, as load_record). laws: {"c0": "poly(I,1)"} or the command line's
    text, or "auto"; bounds: {"c0": (lo, hi)} in SI or "c0=lo:hi"; optimizer, optimizer_settings ({"pc": 0.6}),
    pop, iters, runs, budget ("auto" or "fixed"), max_evals, max_seconds, seed, start ("per-file", or a model file
    of the same model and laws), precision ("mixed", the default: the population search in float32 lanes; or
    "double"), predict (files), folds, reference, report (HTML file), save_model (model file) as the command
    line's options. threads: worker threads (default every core); isa: "sse2", "avx2" or "avx512" for this call.

    The interpreter is released while the engine works; Ctrl-C stops it within a generation and raises
    KeyboardInterrupt. Errors raise UsageError, DataError, StoreError or InternalError with the command line's
    message.
    """
    loader = dict(units=units, columns=columns, transform=transform, average_cycles=average_cycles,
                  conditions=conditions, set=set)
    if isinstance(predict, str):
        predict = [predict]
    text = _core.fit(model, as_records(records, loader), laws=_laws_text(laws), bounds=_bounds_text(bounds),
                     metric=metric, optimizer=optimizer, optimizer_settings=key_values(optimizer_settings, "optimizer_settings"),
                     pop=pop, iters=iters, runs=runs, budget=budget or "", max_evals=max_evals,
                     max_seconds=max_seconds, seed=seed, start=start or "", precision=precision, predict=[str(p) for p in predict],
                     loader=loader_args(**loader), folds=folds or "", reference=reference or "",
                     report=str(report or ""), save_model=str(save_model or ""), threads=threads, isa=isa)
    return FitResult.from_json(json.loads(text))
