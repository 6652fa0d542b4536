"""A sweep's store (`dampbench run`'s SQLite file) as pandas tables: its runs, its task groups and the comparison
tables of `dampbench table`, and its HTML report as `dampbench report` writes it."""
import os
import warnings

import pandas as pd

from dampbench import _core

_SWEEP_KIND = "sweep"  # the kind that means "the tables the sweep file asks for"


def _names(value):
    if value is None:
        return []
    if isinstance(value, str):
        return [value]
    return list(value)


class Store:
    """A sweep's store opened to read with dampbench's own reader: the stored doubles come back bit for bit.

    Store(path) raises StoreError with the command line's message for a missing file ("no store at '...'"), a file
    that is not a dampbench store, or a store of another format; a missing store is not created.

        store = dampbench.Store("results/fvd/store.sqlite")
        runs = store.runs()                 # one row per run
        runs.groupby(["model", "fitset"]).best_value.min()
        tables = store.tables("runs")        # {table id: DataFrame}
    """

    def __init__(self, path):
        self.path = os.fspath(path)
        self._reader = _core.StoreReader(self.path)

    def __repr__(self):
        return f"<dampbench.Store '{self.path}': sweep '{self.meta('name')}'>"

    def meta(self, key):
        """A value of the store's meta table ("name", "spec_hash", "dampbench_version", "build_flags", "shard",
        ...); "" when the store does not hold it."""
        return self._reader.meta(key)

    def runs(self):
        """Every stored run, one row per run (runs of failed groups: none), in group then run order.

        Columns: part, group (the task group's number), split, fitset (the condition's label), datasets (the fit
        datasets' names joined by " + "), predict (the predicted datasets' names, "" when none), model (its name
        in the sweep file), model_id, laws (those a laws = "auto" group chose, else empty), optimizer (its label),
        metric (the optimized metric), run (index in its group), best_value, evaluations, stop_reason, local_optimum (the run's local stage ended at its own
        optimum); then one column per metric, named as the metric (of_abs, of_sq, rmse, nrmse, ...), each the
        metric at the run's best parameters; then one column per parameter name, in the order the models first
        name them, with the value in SI units (the stored double; the tables print paper units) and NaN for a
        run whose model has no such parameter. A parameter whose name another column holds is named
        "param_<name>".
        """
        return pd.DataFrame(self._reader.runs())

    def dataset_metrics(self):
        """The metrics of each run on each dataset of a joint fit (role "fit") and on each predicted dataset (role
        "predict"), one row per (group, run, dataset); single-dataset fits without predictions have none (their
        metrics are runs()'s). Columns: those of runs() up to metric, then run, dataset (its name), role, and one
        column per metric as in runs(). Empty when no group has any."""
        return pd.DataFrame(self._reader.dataset_metrics())

    def groups(self):
        """Every stored task group, one row each (failed ones included), in group order.

        Columns: part, group, split, fitset, datasets, predict, model, model_id, laws, optimizer, metric (as runs()),
        runs (the runs asked for), status ("done" or "failed"), message (why it failed), evaluations (all runs),
        wall_time_s, candidate_samples (model samples computed), finished_at (UTC, ISO 8601), best_run and
        best_value (the lowest best value; None/NaN without runs), converged and verdict (the convergence
        verdict on the runs, as the tables' † marks; None without runs), identifiable (no parameter flagged at
        the best run) and identifiability ("ok", or each flagged parameter's flags; None when not stored).
        """
        return pd.DataFrame(self._reader.groups())

    def tables(self, kind=None, *, split=None, model=None, optimizer=None, metric=None, role=None, target_rel=0.01):
        """The tables `dampbench table STORE --kind KIND` prints, as {table id: DataFrame}, in the command's order.

        kind: a table kind (runs, param-stats, variability, ranking, fvd, params, errors, regression,
        sensitivity, ranksum, bootstrap, runtime, failures, overview), or None for the tables the sweep file
        asks for (--kind sweep). split, model (a name or a list), optimizer (a label or a list), metric, role
        ("fit" or "predict") and target_rel are the command's options. A cell that holds a number is a float (its
        full-precision value, NaN and inf included), any other a str ("-", "yes", "† runs disagree", ...). Each
        DataFrame's attrs hold "title", "paper" (the paper's table it reproduces, "" if none) and "note". An empty
        dict when no stored group matches (where the command exits 1). UsageError for an unknown kind, role or
        metric. A shard's store gives partial tables, with a warning as the command's note.
        """
        if self.meta("shard"):
            warnings.warn(f"{self.path} holds shard {self.meta('shard')} of the sweep only: its tables are partial "
                          "(dampbench merge joins the shards' stores)", stacklevel=2)
        raw = self._reader.tables(kind or _SWEEP_KIND, split or "", _names(model), _names(optimizer),
                                  metric or "", role or "", float(target_rel))
        out = {}
        for t in raw:
            df = pd.DataFrame(t["rows"], columns=t["columns"], dtype=object)
            for i in range(df.shape[1]):  # by position: a table may repeat a column head
                if all(isinstance(v, float) for v in df.iloc[:, i]):
                    df.isetitem(i, df.iloc[:, i].astype("float64"))
            df.attrs.update(title=t["title"], paper=t["paper"], note=t["note"])
            out[t["id"]] = df
        return out


def report(store_path, output_html=None, *, max_points=2500):
    """Writes the HTML report of a store as `dampbench report STORE -o OUTPUT --max-points N` does (the same
    function: the same bytes) and returns its path. output_html: default report.html beside the store. Records
    are re-read from the paths the stored sweep file names. Raises StoreError for a missing store or an output that
    cannot be written, UsageError for a store without a finished group or max_points < 2."""
    return _core.report(os.fspath(store_path), os.fspath(output_html) if output_html is not None else "", int(max_points))
