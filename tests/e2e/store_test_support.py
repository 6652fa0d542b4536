"""Shared by the Python tests: a small sweep of the repository's fvd records and the stored numbers two stores are
compared on (store_soak_test.py, store_faults_test.py, mpi_test.py); records of an MR damper at three currents
made by `dampbench simulate` and a sweep of algebraic, ODE and law models over them (report_browser_test.py,
mpi_test.py)."""
import os
import sqlite3
import subprocess

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

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
    "groups": "SELECT grp, part, split, fitset, model, optimizer, metric, runs, task_key, status, message, evaluations, "
              "laws "
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


def write_current_records(dampbench, work):
    """rec_I0.csv, rec_I0.5.csv, rec_I1.csv in `work`: Bingham forces (f_c = 200 + 800 I N, c0 = 2000 N s/m,
    f0 = 10 N) under a 10 mm, 1 Hz sine, 2 % noise, with the current as operating variable."""
    for current in ("0", "0.5", "1"):
        f_c = 200 + 800 * float(current)
        tmp = os.path.join(work, "tmp.csv")
        subprocess.run([dampbench, "simulate", "--model", "mrd.bingham", "--params", f"f_c={f_c},c0=2000,f0=10",
                        "--sine", "amp=0.01,freq=1,cycles=2,fs=200", "--noise-rel", "0.02", "--seed", "7", "-o", tmp],
                       check=True, capture_output=True)
        with open(tmp) as f:
            body = f.read()
        with open(os.path.join(work, f"rec_I{current}.csv"), "w") as f:
            f.write(f"# operating: I={current}\n" + body)


def current_sweep(name, runs, each_split_extra="", extra=""):
    """A sweep of the current records: Bingham per current with PSO and DE, Bouc-Wen (ODE) per current, a
    current-dependent Bingham law fitted at 0 and 1 A predicting 0.5 A, a regression of f_c on I."""
    return f"""
name = "{name}"
seed = 3
runs = {runs}

[[models]]
model = "mrd.bingham"
optimizers = ["pso", "de"]

[[models]]
model = "mrd.bouc_wen"
optimizers = ["pso"]

[[models]]
name = "bingham(I)"
model = "mrd.bingham"
laws = "f_c=poly(I,1)"
optimizers = ["pso"]

[[optimizers]]
name = "pso"
population = 16
iterations = 12

[[optimizers]]
name = "de"
population = 16
iterations = 12

[[datasets]]
name = "r"
files = ["rec_I0.csv", "rec_I0.5.csv", "rec_I1.csv"]

[[splits]]
name = "each"
models = ["mrd.bingham", "mrd.bouc_wen"]
{each_split_extra}

[[splits]]
name = "laws"
models = ["bingham(I)"]
by = "all"
fit = {{ I = [0, 1] }}
predict = {{ I = 0.5 }}

[[regressions]]
name = "fc"
model = "mrd.bingham"
split = "each"
laws = "f_c=poly(I,1)"
{extra}"""
