"""dampbench.Store and dampbench.report against the command line and against SQLite itself: a small sweep is run by
`dampbench run`, then its runs are compared with the store's own rows (decoded here with struct, independently of
the engine), its tables with `dampbench table --format json`, its report with `dampbench report`."""
import json
import math
import os
import sqlite3
import struct
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
import pytest

import dampbench
from conftest import SOURCE_DIR, cli_json, run_cli

FVD = SOURCE_DIR / "datasets" / "fvd"

# 2 models with different parameters x 2 records x 1 optimizer, 3 runs each: 4 task groups, 12 runs, well under
# a second.
SWEEP = f"""
name = "pystore"
seed = 3
runs = 3
tables = ["runs", "params"]
models = ["fvd.linear_viscous", "fvd.gv_linear_elastic"]

[optimizer]
name = "pso"
population = 12
iterations = 25

[[datasets]]
name = "fvd"
files = ["{FVD}/test1_20mm_92mms.csv", "{FVD}/test3_20mm_460mms.csv"]
"""


@pytest.fixture(scope="module")
def store():
    """(dampbench executable, store path) of the small sweep, run once for the module."""
    exe = os.environ.get("DAMPBENCH_EXE")
    if not exe:
        pytest.skip("DAMPBENCH_EXE is not set (run through ctest)")
    work = Path(os.environ.get("DAMPBENCH_TEST_TMP", "/tmp/dampbench_test_store"))
    work.mkdir(parents=True, exist_ok=True)
    spec = work / "pystore.toml"
    spec.write_text(SWEEP)
    out = work / "out"
    path = out / "store.sqlite"
    for stale in (path, Path(f"{path}-wal"), Path(f"{path}-shm")):
        stale.unlink(missing_ok=True)
    code, _, err = run_cli(exe, "run", spec, "-o", out, "--store", path)
    assert code == 0, f"dampbench run exited {code}: {err}"
    return exe, path


def sql_rows(path, query):
    db = sqlite3.connect(f"file:{path}?mode=ro", uri=True)
    try:
        return db.execute(query).fetchall()
    finally:
        db.close()


def doubles(blob):
    return struct.unpack(f"<{len(blob) // 8}d", blob)


def same_bits(a, b):
    return struct.pack("<d", a) == struct.pack("<d", b)


def test_runs_are_the_stored_rows_bit_for_bit(store):
    _, path = store
    runs = dampbench.Store(path).runs()
    stored = sql_rows(path, "SELECT r.grp, r.run, r.best_value, r.metrics, r.params, r.evaluations, r.stop_reason, "
                            "m.name, m.params FROM runs r JOIN groups g ON g.grp = r.grp "
                            "JOIN models m ON m.part = g.part AND m.model = g.model ORDER BY r.grp, r.run")
    assert len(stored) == 12
    assert len(runs) == len(stored)
    metric_names = sql_rows(path, "SELECT value FROM meta WHERE key='metrics'")[0][0].split(",")
    assert set(metric_names) <= set(runs.columns)
    for d, (grp, run, best, metrics, params, evals, stop, model, names) in zip(runs.to_dict("records"), stored):
        assert (d["group"], d["run"], d["model"], d["evaluations"], d["stop_reason"]) == (grp, run, model, evals, stop)
        assert same_bits(d["best_value"], best)
        for name, value in zip(metric_names, doubles(metrics)):
            assert same_bits(d[name], value), (grp, run, name)
        names = json.loads(names)
        values = doubles(params)
        assert len(names) == len(values) > 0
        for name, value in zip(names, values):
            assert same_bits(d[name], value), (grp, run, name)
    # A parameter of one model only is NaN on the other model's rows.
    own = sql_rows(path, "SELECT name, params FROM models")
    params = {name: set(json.loads(p)) for name, p in own}
    only_elastic = params["fvd.gv_linear_elastic"] - params["fvd.linear_viscous"]
    assert only_elastic
    viscous = runs[runs.model == "fvd.linear_viscous"]
    for name in only_elastic:
        assert viscous[name].isna().all()
        assert runs[runs.model == "fvd.gv_linear_elastic"][name].notna().all()


def test_runs_agree_with_the_runs_table(store):
    """Per model and condition, the runs table's Min, Max and Runs are the min, max and count of runs().best_value."""
    exe, path = store
    s = dampbench.Store(path)
    runs = s.runs()
    for model in ("fvd.linear_viscous", "fvd.gv_linear_elastic"):
        cli = cli_json(exe, "table", path, "--kind", "runs", "--model", model)["tables"]
        assert len(cli) == 1
        columns = cli[0]["columns"]
        mine = runs[runs.model == model].groupby("fitset").best_value
        assert len(cli[0]["rows"]) == mine.ngroups == 2
        for row in cli[0]["rows"]:
            cells = dict(zip(columns, row))
            best = mine.get_group(cells["Condition"])
            assert cells["Min"] == best.min() and cells["Max"] == best.max() and cells["Runs"] == len(best)


def json_cells(df):
    """A DataFrame's rows as `table --format json` writes them (non-finite numbers as text)."""
    def cell(v):
        if isinstance(v, float) and not math.isfinite(v):
            return "nan" if math.isnan(v) else ("inf" if v > 0 else "-inf")
        return v
    return [[cell(v) for v in row] for row in df.itertuples(index=False, name=None)]


@pytest.mark.parametrize("kind", [None, "runs", "params", "param-stats", "overview"])
def test_tables_equal_the_command_lines(store, kind):
    exe, path = store
    mine = dampbench.Store(path).tables(kind)
    cli = cli_json(exe, "table", path, "--kind", kind or "sweep")["tables"]
    assert list(mine) == [t["id"] for t in cli]
    for t in cli:
        df = mine[t["id"]]
        assert df.attrs["title"] == t["title"] and df.attrs["note"] == t["note"] and df.attrs["paper"] == t["paper"]
        assert list(df.columns) == t["columns"]
        assert json_cells(df) == t["rows"]


def test_tables_with_options_and_numbers_as_floats(store):
    exe, path = store
    mine = dampbench.Store(path).tables("runs", model="fvd.linear_viscous")
    cli = cli_json(exe, "table", path, "--kind", "runs", "--model", "fvd.linear_viscous")["tables"]
    assert list(mine) == [t["id"] for t in cli]
    df = next(iter(mine.values()))
    assert df["Mean"].dtype == np.float64 and df["Condition"].dtype == object
    assert dampbench.Store(path).tables("runs", model="no.such_model") == {}


def test_groups_one_row_per_group_with_the_tables_verdict(store):
    exe, path = store
    groups = dampbench.Store(path).groups()
    stored = sql_rows(path, "SELECT grp, status, evaluations, wall_time_s FROM groups ORDER BY grp")
    assert list(groups.group) == [g for g, *_ in stored]
    assert list(groups.status) == [s for _, s, *_ in stored]
    assert list(groups.evaluations) == [e for _, _, e, _ in stored]
    assert all(same_bits(a, b) for a, b in zip(groups.wall_time_s, [w for *_, w in stored]))
    runs = dampbench.Store(path).runs()
    assert list(groups.best_value) == list(runs.groupby("group").best_value.min())
    assert groups.identifiability.notna().all()
    for t in cli_json(exe, "table", path, "--kind", "runs")["tables"]:
        model = t["title"].rsplit("— ", 1)[1]
        for row in t["rows"]:
            cells = dict(zip(t["columns"], row))
            g = groups[(groups.model == model) & (groups.fitset == cells["Condition"])]
            assert len(g) == 1
            converged = cells["Converged"] == "yes"
            assert bool(g.converged.iloc[0]) == converged
            if not converged:
                assert cells["Converged"].endswith(g.verdict.iloc[0])


def test_report_writes_the_command_lines_bytes(store, tmp_path):
    exe, path = store
    cli_html = tmp_path / "cli.html"
    code, _, err = run_cli(exe, "report", path, "-o", cli_html, "--max-points", 300)
    assert code == 0, err
    mine = dampbench.report(path, tmp_path / "py.html", max_points=300)
    assert mine == str(tmp_path / "py.html")
    assert Path(mine).read_bytes() == cli_html.read_bytes()


def test_two_threads_read_one_store(store):
    _, path = store
    s = dampbench.Store(path)
    expected = (s.runs(), dampbench.Store(path).groups())
    with ThreadPoolExecutor(4) as pool:
        got = list(pool.map(lambda i: s.runs() if i % 2 == 0 else s.groups(), range(8)))
    for i, df in enumerate(got):
        assert df.equals(expected[i % 2])


def test_a_shards_tables_warn_that_they_are_partial(store, tmp_path):
    exe, _ = store
    spec = tmp_path / "pystore.toml"
    spec.write_text(SWEEP)
    shard = tmp_path / "shard.sqlite"
    code, _, err = run_cli(exe, "run", spec, "-o", tmp_path / "out", "--shard", "1/2", "--store", shard)
    assert code == 0, err
    code, out, err = run_cli(exe, "table", shard, "--kind", "runs", "--format", "json")
    assert code == 0 and "holds shard 1/2 of the sweep only" in err
    with pytest.warns(UserWarning, match="holds shard 1/2 of the sweep only"):
        tables = dampbench.Store(shard).tables("runs")
    assert {i: json_cells(df) for i, df in tables.items()} == {t["id"]: t["rows"] for t in json.loads(out)["tables"]}
    assert len(dampbench.Store(shard).runs()) == 6


def cli_error(exe, *args):
    code, _, err = run_cli(exe, *args)
    assert err.startswith("dampbench: error: ")
    return code, err[len("dampbench: error: "):].rstrip("\n")


def test_missing_store_raises_the_command_lines_error_and_is_not_created(exe, tmp_path):
    missing = tmp_path / "nothing" / "store.sqlite"
    code, message = cli_error(exe, "table", missing, "--kind", "runs")
    with pytest.raises(dampbench.StoreError) as e:
        dampbench.Store(missing)
    assert str(e.value) == message and e.value.exit_code == code == 4
    assert not missing.exists() and not missing.parent.exists()
    beside = tmp_path / "absent.sqlite"
    with pytest.raises(dampbench.StoreError, match="no store at"):
        dampbench.Store(beside)
    assert list(tmp_path.iterdir()) == []
    with pytest.raises(dampbench.StoreError, match="no store at"):
        dampbench.report(missing, tmp_path / "r.html")


def test_a_file_that_is_not_a_store_raises_store_error(exe, tmp_path):
    text = tmp_path / "notes.txt"
    text.write_text("not a database\n" * 100)
    other = tmp_path / "other.sqlite"
    db = sqlite3.connect(other)
    db.execute("CREATE TABLE t(x)")
    db.commit()
    db.close()
    for path in (text, other):
        code, message = cli_error(exe, "table", path, "--kind", "runs")
        with pytest.raises(dampbench.StoreError) as e:
            dampbench.Store(path)
        assert str(e.value) == message and code == 4


def test_unknown_kind_raises_usage_error_with_the_command_lines_message(store):
    exe, path = store
    code, message = cli_error(exe, "table", path, "--kind", "nope")
    with pytest.raises(dampbench.UsageError) as e:
        dampbench.Store(path).tables("nope")
    assert str(e.value) == message and code == 2


def test_fvd_preset_one_row_per_run_and_its_paper_tables(store, tmp_path):
    """The fvd preset (16 task groups of 50 runs, about a second): 800 rows, the stored best values, Tables 3-14 and
    the energy table (the records read again, as the command line does)."""
    exe, _ = store
    out = tmp_path / "fvd"
    code, _, err = run_cli(exe, "run", SOURCE_DIR / "datasets" / "presets" / "fvd.toml", "-o", out)
    assert code == 0, err
    path = out / "store.sqlite"
    runs = dampbench.Store(path).runs()
    stored = sql_rows(path, "SELECT best_value FROM runs ORDER BY grp, run")
    assert len(runs) == len(stored) == 800
    assert (runs.groupby(["model", "fitset"]).size() == 50).all()
    assert all(same_bits(a, b) for a, b in zip(runs.best_value, [v for (v,) in stored]))
    mine = dampbench.Store(path).tables()
    cli = cli_json(exe, "table", path, "--kind", "sweep")["tables"]
    assert list(mine) == [t["id"] for t in cli] and len(cli) == 14
    for t in cli:
        assert json_cells(mine[t["id"]]) == t["rows"]


# One joint fit of two records predicting a third: per-dataset metrics, fitted and predicted.
JOINT = f"""
name = "pyjoint"
seed = 2
runs = 2
tables = ["errors"]
models = ["fvd.linear_viscous"]

[optimizer]
name = "pso"
population = 10
iterations = 20

[[datasets]]
name = "train"
files = ["{FVD}/test1_20mm_92mms.csv", "{FVD}/test2_20mm_230mms.csv"]

[[datasets]]
name = "check"
file = "{FVD}/test3_20mm_460mms.csv"

[[splits]]
name = "joint"
datasets = ["train", "check"]
fit = {{ freq = [0.732112738, 1.83028185] }}
predict = {{}}
by = "all"
"""


def test_dataset_metrics_of_a_joint_fit_and_its_prediction(store, tmp_path):
    exe, _ = store
    spec = tmp_path / "joint.toml"
    spec.write_text(JOINT)
    code, _, err = run_cli(exe, "run", spec, "-o", tmp_path / "out")
    assert code == 0, err
    path = tmp_path / "out" / "store.sqlite"
    s = dampbench.Store(path)
    runs = s.runs()
    assert list(runs.datasets) == ["test1_20mm_92mms + test2_20mm_230mms"] * 2 and list(runs.predict) == ["check"] * 2
    per = s.dataset_metrics()
    stored = sql_rows(path, "SELECT m.run, d.name, m.role, m.metrics FROM dataset_metrics m JOIN datasets d "
                            "ON d.dataset = m.dataset ORDER BY m.grp, m.run, m.dataset")
    assert len(per) == len(stored) == 6
    metric_names = sql_rows(path, "SELECT value FROM meta WHERE key='metrics'")[0][0].split(",")
    for d, (run, name, role, metrics) in zip(per.to_dict("records"), stored):
        assert (d["run"], d["dataset"], d["role"]) == (run, name, role)
        assert all(same_bits(d[m], v) for m, v in zip(metric_names, doubles(metrics)))
    # The errors table prints the best run's metric on each dataset.
    best = int(s.groups().best_run.iloc[0])
    for role in ("fit", "predict"):
        cli = cli_json(exe, "table", path, "--kind", "errors", "--role", role)["tables"]
        mine = s.tables("errors", role=role)
        assert list(mine) == [t["id"] for t in cli]
        for t in cli:
            assert json_cells(mine[t["id"]]) == t["rows"]
            for name, value in t["rows"][:-1]:  # the last row is the mean
                row = per[(per.run == best) & (per.dataset == name)]
                assert list(row.role) == [role] and row.of_abs.iloc[0] == value
