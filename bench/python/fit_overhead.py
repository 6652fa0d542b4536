#!/usr/bin/env python3
"""The Python module's overhead over the command line on the same fit (docs/performance.md, "Python").

Runs one fit of at least 2 s alternately as `dampbench fit --format json` (a process; its wall time from outside)
and as `dampbench.fit(...)` in this interpreter (the call's wall time), N times each, checks that both give the
same parameters, and prints the medians and the overhead (Python − CLI) / CLI. The interpreter's start and
`import dampbench` are timed apart: a notebook pays them once, not per fit.

    PYTHONPATH=build/python /usr/bin/python3 bench/python/fit_overhead.py build/dampbench [N] [DATA_DIR]
"""
import json
import statistics
import subprocess
import sys
import time
from pathlib import Path

import dampbench

exe = sys.argv[1]
repeats = int(sys.argv[2]) if len(sys.argv) > 2 else 5
data_dir = Path(sys.argv[3] if len(sys.argv) > 3 else Path(__file__).resolve().parents[3] / "shared" / "data")
record = data_dir / "utfsm-mr-damper" / "10mm1Hz1A.txt"
loader = dict(columns="t,x,v,F", units="x=mm,v=mm/s", conditions="utfsm")
# mrd.bouc_wen (an ODE model) by ga-lm with a fixed budget: 2-4 s on 2 cores.
budget = dict(pop=48, iters=40, runs=4, seed=1)
cli = [exe, "fit", "--model", "mrd.bouc_wen", "--data", str(record), "--columns", loader["columns"], "--units",
       loader["units"], "--conditions", "utfsm", "--pop", "48", "--iters", "40", "--runs", "4", "--seed", "1",
       "--format", "json"]

cli_s, py_s = [], []
for _ in range(repeats):
    start = time.perf_counter()
    out = subprocess.run(cli, check=True, capture_output=True, text=True).stdout
    cli_s.append(time.perf_counter() - start)
    start = time.perf_counter()
    result = dampbench.fit("mrd.bouc_wen", record, **budget, **loader)
    py_s.append(time.perf_counter() - start)
    assert result.params == json.loads(out)["best_params"], "the Python fit differs from the command line's"

start = time.perf_counter()
subprocess.run([sys.executable, "-c", "import dampbench"], check=True)
import_s = time.perf_counter() - start
cli_median, py_median = statistics.median(cli_s), statistics.median(py_s)
print(f"fit of mrd.bouc_wen on {record.name}, ga-lm 4 x 48 x 40, median of {repeats}:")
print(f"  command line  {cli_median:.3f} s  (runs: {', '.join(f'{s:.3f}' for s in cli_s)})")
print(f"  Python call   {py_median:.3f} s  (runs: {', '.join(f'{s:.3f}' for s in py_s)})")
print(f"  overhead      {100 * (py_median - cli_median) / cli_median:+.2f} % of the command line's wall time")
print(f"  interpreter start + import dampbench (once per session): {import_s:.3f} s")
