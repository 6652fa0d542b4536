#!/usr/bin/python3
"""Soak test of the results store (issue 17): a sweep killed with SIGKILL at N random moments in a row, resumed
each time, ends bit-identical to an uninterrupted run of the same sweep.

usage: store_soak_test.py DAMPBENCH WORK_DIR [KILLS (default 20)] [SEED (default 1)]
The kill moments are drawn from a seeded generator (the test is the same every time); a longer soak is the same
script with more kills, e.g. `tests/store_soak_test.py build/dampbench /tmp/soak 500 7`.

Compared: every stored number of every task group (runs: best value, metrics, parameters, evaluations, stop
reason, best-so-far trace, local-optimum flag; per-dataset metrics; identifiability; the group's status and
message), which must be equal byte for byte; the wall times and timestamps are allowed to differ. `dampbench
verify` must also accept the soaked store.
"""
import os
import random
import shutil
import signal
import sqlite3
import subprocess
import sys
import time

DAMPBENCH, WORK = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
KILLS = int(sys.argv[3]) if len(sys.argv) > 3 else 20
SEED = int(sys.argv[4]) if len(sys.argv) > 4 else 1
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# 4 models x 4 records x 2 optimizers = 32 task groups of a few tens of milliseconds each (about 1 s in all),
# so that kills land before, between and during group commits.
SWEEP = f"""
name = "soak"
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

RESULTS = {
    "groups": "SELECT grp, part, split, fitset, model, optimizer, metric, runs, task_key, status, message, evaluations "
              "FROM groups ORDER BY grp",
    "runs": "SELECT * FROM runs ORDER BY grp, run",
    "dataset_metrics": "SELECT * FROM dataset_metrics ORDER BY grp, run, dataset",
    "identifiability": "SELECT * FROM identifiability ORDER BY grp",
    "sensitivity": "SELECT * FROM sensitivity ORDER BY grp",
}


def contents(store):
    db = sqlite3.connect(store)
    out = {name: db.execute(query).fetchall() for name, query in RESULTS.items()}
    db.close()
    return out


def run_args(out):
    return [DAMPBENCH, "run", os.path.join(WORK, "soak.toml"), "-o", out, "--quiet", "--no-report", "--threads", "2"]


def main():
    shutil.rmtree(WORK, ignore_errors=True)
    os.makedirs(WORK)
    with open(os.path.join(WORK, "soak.toml"), "w") as f:
        f.write(SWEEP)
    start = time.monotonic()
    subprocess.run(run_args(os.path.join(WORK, "whole")), check=True, capture_output=True)
    whole_s = time.monotonic() - start

    rng = random.Random(SEED)
    soaked = os.path.join(WORK, "soaked")
    killed_with_progress = 0
    for k in range(KILLS):
        before = len(contents(os.path.join(soaked, "store.sqlite"))["groups"]) if os.path.exists(soaked) else 0
        p = subprocess.Popen(run_args(soaked), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        time.sleep(rng.uniform(0.05, 1.2 * whole_s))
        if p.poll() is None:
            os.kill(p.pid, signal.SIGKILL)
        p.wait()
        after = len(contents(os.path.join(soaked, "store.sqlite"))["groups"]) if os.path.exists(os.path.join(soaked, "store.sqlite")) else 0
        killed_with_progress += after > before
        if p.returncode == 0:  # finished before the kill: start over so that every kill interrupts something
            shutil.rmtree(soaked)
    final = subprocess.run(run_args(soaked), capture_output=True, text=True)
    if final.returncode != 0:
        sys.exit(f"the resumed run failed ({final.returncode}): {final.stderr}")

    a, b = contents(os.path.join(WORK, "whole", "store.sqlite")), contents(os.path.join(soaked, "store.sqlite"))
    failures = [f"{name}: {len(a[name])} rows uninterrupted, {len(b[name])} soaked, or different values"
                for name in RESULTS if a[name] != b[name]]
    verify = subprocess.run([DAMPBENCH, "verify", os.path.join(soaked, "store.sqlite"), "--sample", "4"],
                            capture_output=True, text=True)
    if verify.returncode != 0:
        failures.append("verify of the soaked store: " + verify.stdout + verify.stderr)
    print(f"{KILLS} SIGKILLs (seed {SEED}; {killed_with_progress} after some progress), then a resume: "
          f"{len(b['groups'])} task groups, {len(b['runs'])} runs "
          f"{'identical to' if not failures else 'DIFFERENT from'} the uninterrupted run ({whole_s:.1f} s)")
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
