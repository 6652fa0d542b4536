#!/usr/bin/python3
"""Soak test of the results store: a sweep killed with SIGKILL at N random moments in a row, resumed
each time, ends bit-identical to an uninterrupted run of the same sweep.

usage: store_soak_test.py DAMPBENCH WORK_DIR [KILLS (default 20)] [SEED (default 1)]
The kill moments are drawn from a seeded generator (the test is the same every time); a longer soak is the same
script with more kills, e.g. `tests/e2e/store_soak_test.py build/dampbench /tmp/soak 500 7`.

Compared: every stored number of every task group (runs: best value, metrics, parameters, evaluations, stop
reason, best-so-far trace, local-optimum flag; per-dataset metrics; identifiability; the group's status and
message), which must be equal byte for byte; the wall times and timestamps are allowed to differ. `dampbench
verify` must also accept the soaked store.
"""
import os
import random
import shutil
import signal
import subprocess
import sys
import time

from store_test_support import contents, differences, stored_groups, write_sweep

DAMPBENCH, WORK = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
KILLS = int(sys.argv[3]) if len(sys.argv) > 3 else 20
SEED = int(sys.argv[4]) if len(sys.argv) > 4 else 1


def run_args(out):
    return [DAMPBENCH, "run", os.path.join(WORK, "small.toml"), "-o", out, "--quiet", "--no-report", "--threads", "2"]


def main():
    shutil.rmtree(WORK, ignore_errors=True)
    os.makedirs(WORK)
    write_sweep(WORK)
    start = time.monotonic()
    subprocess.run(run_args(os.path.join(WORK, "whole")), check=True, capture_output=True)
    whole_s = time.monotonic() - start

    rng = random.Random(SEED)
    soaked = os.path.join(WORK, "soaked")
    killed_with_progress = 0
    for k in range(KILLS):
        before = stored_groups(os.path.join(soaked, "store.sqlite"))
        p = subprocess.Popen(run_args(soaked), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        time.sleep(rng.uniform(0.05, 1.2 * whole_s))
        if p.poll() is None:
            os.kill(p.pid, signal.SIGKILL)
        p.wait()
        after = stored_groups(os.path.join(soaked, "store.sqlite"))
        killed_with_progress += after > before
        if p.returncode == 0:  # finished before the kill: start over so that every kill interrupts something
            shutil.rmtree(soaked)
    final = subprocess.run(run_args(soaked), capture_output=True, text=True)
    if final.returncode != 0:
        sys.exit(f"the resumed run failed ({final.returncode}): {final.stderr}")

    a, b = contents(os.path.join(WORK, "whole", "store.sqlite")), contents(os.path.join(soaked, "store.sqlite"))
    failures = differences(a, b)
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
