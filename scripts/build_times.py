#!/usr/bin/python3
"""Where a build's time went: its heaviest compile steps (ninja's log) and its slowest tests (ctest's timings).

usage: scripts/build_times.py BUILD_DIR [--top N]

Reads BUILD_DIR/.ninja_log (the newest entry of each output; wall seconds of the step, which on a loaded machine
include waiting for a core) and BUILD_DIR/Testing/Temporary/CTestCostData.txt (ctest's average time per test over
its runs in this build folder). Prints the N heaviest steps, each target's share of the summed step time, and the
N slowest tests. scripts/test.sh prints it for each of its builds after its stage table.
"""
import argparse
import collections
import os
import re
import sys


def ninja_steps(build):
    """{output: seconds} from .ninja_log, newest entry per output. A command with several outputs (a link and the
    test list gtest_discover_tests writes after it) has one line per output with the same times and command hash:
    it counts once, under its first output."""
    path = os.path.join(build, ".ninja_log")
    newest = {}
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                continue
            fields = line.rstrip("\n").split("\t")
            if len(fields) < 5:
                continue
            newest[fields[3]] = (int(fields[0]), int(fields[1]), fields[4])
    steps, seen = {}, set()
    for output, (start, end, command_hash) in newest.items():
        if (start, end, command_hash) not in seen:
            seen.add((start, end, command_hash))
            steps[output] = (end - start) / 1000.0
    return steps


def target_of(output):
    """The target a step belongs to: the X of .../CMakeFiles/X.dir/..., or the output itself (links)."""
    m = re.search(r"CMakeFiles/([^/]+)\.dir/", output)
    return m.group(1) if m else "links and other steps"


def test_times(build):
    """{test: seconds} from ctest's cost data (absent before a first ctest run)."""
    path = os.path.join(build, "Testing", "Temporary", "CTestCostData.txt")
    times = {}
    if not os.path.exists(path):
        return times
    with open(path) as f:
        for line in f:
            if line.startswith("---"):
                break
            parts = line.rsplit(" ", 2)
            if len(parts) == 3:
                try:
                    times[parts[0].split("  # GetParam")[0]] = float(parts[2])
                except ValueError:
                    pass
    return times


def table(title, rows):
    print(f"\n{title}")
    for name, value in rows:
        print(f"  {value:>10}  {name}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("build")
    parser.add_argument("--top", type=int, default=8)
    args = parser.parse_args()
    if not os.path.exists(os.path.join(args.build, ".ninja_log")):
        sys.exit(f"build_times: {args.build}/.ninja_log not found (a Ninja build folder is expected)")
    steps = ninja_steps(args.build)
    total = sum(steps.values())
    print(f"{args.build}: {len(steps)} build steps, {total:.0f} s summed")
    heaviest = sorted(steps.items(), key=lambda kv: -kv[1])[: args.top]
    table("heaviest steps (s)", [(o, f"{s:.1f}") for o, s in heaviest])
    by_target = collections.Counter()
    for output, seconds in steps.items():
        by_target[target_of(output)] += seconds
    table("steps summed per target (s)", [(t, f"{s:.0f}") for t, s in by_target.most_common(args.top)])
    tests = test_times(args.build)
    if tests:
        slowest = sorted(tests.items(), key=lambda kv: -kv[1])[: args.top]
        table(f"slowest tests (s; {len(tests)} tests, {sum(tests.values()):.0f} s summed)",
              [(t, f"{s:.1f}") for t, s in slowest])


if __name__ == "__main__":
    main()
