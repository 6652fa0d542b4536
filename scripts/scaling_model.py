#!/usr/bin/env python3
"""Predicts the wall time of a sweep on K MPI ranks from a store of a one-process run (docs/performance.md).

dampbench's MPI scheme (engine/distributed/mpi_runner.hpp): rank 0 hands task groups, largest first, to the
K - 1 worker ranks as they ask, and handles every result serially (decode, commit to SQLite). This script
replays that with the measured numbers:
  - each group's cost on one worker, from the store: its wall_time_s, scaled so that the groups' costs add up
    to the run's wall time (in one process several groups share the cores at once, so their wall times overlap);
    a worker is --worker-speedup times as fast as the machine the store was written on (1: the same machine;
    a 32-core node against 2 cores is at most 16, less since a group's batch does not scale perfectly);
  - the order: decreasing cost (dampbench orders by an estimate of it, sweep/schedule.hpp);
  - rank 0's time per group (--per-group-ms, measured by `mpirun ... dampbench run`, which prints it) and a
    network latency per group (--latency-us, for the request and the assignment);
  - --repeat R: the sweep R times over (R copies of every group), e.g. the presets with 100x the runs.
Rank 0 is a single server: a result waits while rank 0 handles earlier ones, so once K - 1 workers finish
groups faster than 1 / per-group time, adding ranks stops helping; the table shows where.

usage: scaling_model.py STORE --wall-s W --per-group-ms C [--latency-us L] [--repeat R] [--worker-speedup S]
                        [--ranks 1,2,...]
"""
import argparse
import heapq
import sqlite3


def group_costs(store, wall_s):
    db = sqlite3.connect(f"file:{store}?mode=ro", uri=True)
    times = [t for (t,) in db.execute("SELECT wall_time_s FROM groups ORDER BY grp")]
    db.close()
    scale = wall_s / sum(times)
    return [t * scale for t in times]


def simulate(costs, workers, per_group_s, latency_s):
    """Wall time and rank 0's busy share with `workers` worker ranks (0: rank 0 runs everything itself)."""
    order = sorted(costs, reverse=True)
    if workers == 0:
        return sum(order), 0.0
    free = [(0.0, w) for w in range(workers)]  # (time the worker asks for its next group, worker)
    heapq.heapify(free)
    done = []
    for cost in order:
        t, w = heapq.heappop(free)
        finish = t + latency_s + cost
        done.append(finish)
        heapq.heappush(free, (finish, w))
    rank0 = 0.0  # rank 0 handles results in the order they arrive, one at a time
    for finish in sorted(done):
        rank0 = max(rank0, finish) + per_group_s
    return rank0, len(order) * per_group_s / rank0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("store")
    ap.add_argument("--wall-s", type=float, required=True, help="wall time of the one-process run of the store")
    ap.add_argument("--per-group-ms", type=float, required=True, help="rank 0's handling time per group")
    ap.add_argument("--latency-us", type=float, default=50.0, help="network latency per group (request + assignment)")
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--worker-speedup", type=float, default=1.0, help="a worker's speed over the measured machine")
    ap.add_argument("--ranks", default="1,2,4,8,16,32,64,128,256,512,1024")
    a = ap.parse_args()
    costs = [c / a.worker_speedup for c in group_costs(a.store, a.wall_s)] * a.repeat
    one, _ = simulate(costs, 0, 0, 0)
    print(f"{len(costs)} task groups, {one:.0f} s in one process (worker speed-up {a.worker_speedup}); rank 0 "
          f"{a.per_group_ms} ms per group, latency {a.latency_us} us; largest group {max(costs):.1f} s")
    print("| ranks | workers | predicted wall | speed-up | efficiency per worker | rank 0 busy |")
    print("|---:|---:|---:|---:|---:|---:|")
    for k in (int(x) for x in a.ranks.split(",")):
        wall, busy = simulate(costs, k - 1, a.per_group_ms / 1e3, a.latency_us / 1e6)
        workers = max(k - 1, 1)
        print(f"| {k} | {k - 1} | {wall:.1f} s | {one / wall:.1f} | {one / wall / workers:.2f} | {100 * busy:.0f} % |")


if __name__ == "__main__":
    main()
