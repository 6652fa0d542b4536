"""Shared by the store tests (store_soak_test.py, store_faults_test.py): a small sweep of the repository's fvd
records and the stored numbers two stores are compared on."""
import os
import sqlite3

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# 4 models x 4 records x 2 optimizers = 32 task groups of a few tens of milliseconds each (about 1 s in all on
# 2 cores), so that faults land before, between and during group commits.
SWEEP = f"""
name = "small"
seed = 5
runs = 3
models = ["fvd.linear_viscous", "fvd.generalized_viscous", "fvd.gv_linear_elastic", "fvd.gv_quadratic_elastic"]

[[optimizers]]
name = "pso"
population = 30
iterations = 150

[[optimizers]]
name = "de"
population = 30
iterations = 150

[[datasets]]
name = "fvd"
files = ["{ROOT}/datasets/fvd/test1_20mm_92mms.csv", "{ROOT}/datasets/fvd/test2_20mm_230mms.csv",
         "{ROOT}/datasets/fvd/test3_20mm_460mms.csv", "{ROOT}/datasets/fvd/test4_17mm_460mms.csv"]
"""
GROUPS = 32

# Every stored number of every task group; wall times and timestamps may differ between runs.
RESULTS = {
    "groups": "SELECT grp, part, split, fitset, model, optimizer, metric, runs, task_key, status, message, evaluations "
              "FROM groups ORDER BY grp",
    "runs": "SELECT * FROM runs ORDER BY grp, run",
    "dataset_metrics": "SELECT * FROM dataset_metrics ORDER BY grp, run, dataset",
    "identifiability": "SELECT * FROM identifiability ORDER BY grp",
    "sensitivity": "SELECT * FROM sensitivity ORDER BY grp",
}


def write_sweep(work):
    path = os.path.join(work, "small.toml")
    with open(path, "w") as f:
        f.write(SWEEP)
    return path


def contents(store):
    """{table: rows} of the numbers compared, read with SQLite itself (not with dampbench)."""
    db = sqlite3.connect(f"file:{store}?mode=ro", uri=True)
    out = {name: db.execute(query).fetchall() for name, query in RESULTS.items()}
    db.close()
    return out


def stored_groups(store):
    """Task groups in a store, 0 while it is being created."""
    if not os.path.exists(store):
        return 0
    try:
        db = sqlite3.connect(f"file:{store}?mode=ro", uri=True)
        n = db.execute("SELECT COUNT(*) FROM groups").fetchone()[0]
        db.close()
        return n
    except sqlite3.Error:
        return 0


def differences(a, b):
    """Tables whose rows differ between two stores' contents (empty when bit-identical)."""
    return [f"{name}: {len(a[name])} rows vs {len(b[name])}, or different values" for name in RESULTS if a[name] != b[name]]
