#!/usr/bin/python3
"""Builds the peer comparison tables from the JSON lines that run_peers.sh collected.

Input: a JSON-lines file; each line is one measurement:
  {"peer": "scipy"|"pagmo2", "problem", "algorithm", "candidate_samples_per_s", "rates", "cpu_rates",
   "best", "median", "worst", "runs", "evaluations", "load_before", "load_after", "busy_before", ...}
  {"peer": "dampbench", "problem", "algorithm", "rates", "cpu_rates", "rate_1thread", "best", "median",
   "worst", "busy_load_before", "timed_runs" (fit's "runs": count, best, mean, ...), "evaluations", ...}
  {"peer": "load", "load1", ...}  load averages sampled around the measurements
Writes the Markdown tables to --out and prints them.
"""
import argparse
import json
import math
import random
import statistics
import sys

# dampbench optimizer matching each peer algorithm, and the throughput target dampbench is held to
MATCH = {("scipy", "de"): ("de", 50.0), ("pagmo2", "de"): ("de", 10.0), ("pagmo2", "sga"): ("ga", 10.0),
         ("pagmo2", "pso_gen"): ("pso", 10.0), ("pagmo2", "cmaes"): ("cmaes", 10.0)}
# Metric ties: on fvd every algorithm reaches the same floor (0.0175908...) and differs in the 8th digit.
REL_TOL = 1e-6
BOOTSTRAP_RESAMPLES = 4000


def median_ratio_interval(ours, peer, resamples=BOOTSTRAP_RESAMPLES, seed=1):
    """95 % percentile-bootstrap interval of median(ours) / median(peer), each side resampled with replacement
    (a fixed seed: the same files give the same table). None when either side has fewer than 2 values.
    A median of some 50 stochastic runs moves by a percent or more from one set of seeds to the next, so a
    difference whose interval contains 1 is no difference the runs can show."""
    if len(ours) < 2 or len(peer) < 2 or not all(map(math.isfinite, ours + peer)):
        return None
    rng = random.Random(seed)
    ratios = sorted(statistics.median(rng.choices(ours, k=len(ours))) /
                    statistics.median(rng.choices(peer, k=len(peer))) for _ in range(resamples))
    return ratios[int(0.025 * resamples)], ratios[int(0.975 * resamples) - 1]


def interval_text(ours_median, peer_median, interval):
    ratio = ours_median / peer_median if peer_median not in (0, math.inf) else math.nan
    return f"{ratio:.4f}" + ("" if interval is None else f" [{interval[0]:.4f}, {interval[1]:.4f}]")


def median_verdict(ours_median, peer_median, interval):
    """"better or equal" (ours ≤ peer), "equal within the runs' spread" (the interval contains 1), or "no"."""
    if peer_median == math.inf or ours_median <= peer_median * (1 + REL_TOL):
        return "yes", True
    if interval is not None and interval[0] <= 1 <= interval[1]:
        return "equal within the runs' spread", True
    return "no", False


def rate(r):
    return f"{r:.3g}" if r == r else "—"


def metric(v):
    return "inf" if v is None or v == math.inf else f"{v:.6g}"


def per_run(evaluations, runs):
    """Evaluations per run, or None where the measurement does not tell (older JSON lines)."""
    return evaluations / runs if evaluations and runs else None


def count(v):
    return "?" if v is None else f"{v:g}"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("results")
    ap.add_argument("--out", required=True)
    ap.add_argument("--header", default="", help="Markdown text put above the tables")
    ap.add_argument("--repeat", type=int, default=2, help="REPEAT of run_peers.sh")
    ap.add_argument("--repeat-short", type=int, default=5, help="REPEAT_SHORT of run_peers.sh")
    ap.add_argument("--short-s", type=float, default=30, help="SHORT_S of run_peers.sh")
    args = ap.parse_args()

    rows = [json.loads(line) for line in open(args.results) if line.strip()]
    peers = [r for r in rows if r.get("peer") in ("scipy", "pagmo2")]
    ours = {(r["problem"], r["algorithm"]): r for r in rows if r.get("peer") == "dampbench"}
    loads = [r for r in rows if r.get("peer") == "load"]

    speed = ["### Throughput (candidate-samples/s, wall clock; the issue's targets)", "",
             "| problem | peer algorithm / dampbench | peer | dampbench, 2 threads | **ratio** | target "
             "| dampbench, 1 thread | per CPU-second: peer | per CPU-second: dampbench | ratio per CPU-s "
             "| others' CPU share / load1 before: peer | … before dampbench's timed fits |",
             "|---|---|---:|---:|---:|---|---:|---:|---:|---:|---|---|"]
    quality = ["### Final of_abs over the runs (same budget)", "",
               "| problem | peer algorithm / dampbench | peer runs | peer best | peer median | peer worst "
               "| dampbench runs | dampbench best | dampbench median | dampbench worst "
               "| median ratio dampbench / peer, 95 % bootstrap interval | dampbench median equal or better "
               "| evaluations per run: peer / dampbench |",
               "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---|---|---|"]
    verdicts = []
    for p in peers:
        ours_alg, target = MATCH[(p["peer"], p["algorithm"])]
        d = ours.get((p["problem"], ours_alg))
        if d is None:
            continue
        r_ours, r_peer = max(d["rates"]), p["candidate_samples_per_s"]
        c_ours = max(d.get("cpu_rates") or [math.nan])
        c_peer = max(p.get("cpu_rates") or [math.nan])
        ratio = r_ours / r_peer
        met = ratio >= target
        interval = median_ratio_interval(d["values"], p.get("values") or [])
        med_text, med_ok = median_verdict(d["median"], p["median"], interval)
        # The medians compare at equal budgets only; a count missing from the JSON is shown as "?".
        e_peer = per_run(p.get("evaluations"), p.get("runs"))
        e_ours = per_run(d.get("evaluations"), d["timed_runs"].get("count"))
        evals_ok = e_peer is None or e_ours is None or e_peer == e_ours
        verdicts.append(met and med_ok and evals_ok)
        name = f"{p['peer']} {p['algorithm']} / {ours_alg}"
        busy_ours = ", ".join(f"{b:.0%} / {l:.1f}" for b, l in d.get("busy_load_before", []))
        speed.append(
            f"| {p['problem']} | {name} | {rate(r_peer)} | {rate(r_ours)} | **{ratio:.1f}×** "
            f"| ≥ {target:g}× {'met' if met else 'NOT met'} | {rate(d.get('rate_1thread', math.nan))} "
            f"| {rate(c_peer)} | {rate(c_ours)} | {c_ours / c_peer:.1f}× "
            f"| {p.get('busy_before', math.nan):.0%} / {p.get('load_before', math.nan):.1f} | {busy_ours} |")
        quality.append(
            f"| {p['problem']} | {name} | {p['runs']} | {metric(p['best'])} | {metric(p['median'])} "
            f"| {metric(p['worst'])} | {len(d['values'])} | {metric(d['best'])} | {metric(d['median'])} "
            f"| {metric(d['worst'])} | {interval_text(d['median'], p['median'], interval)} | {med_text} "
            f"| {count(e_peer)} / {count(e_ours)}{'' if evals_ok else ' NOT equal'} |")

    notes = [
        f"Rates: best of the repetitions of each measurement (a measurement shorter than {args.short_s:g} s is "
        f"made {args.repeat_short} times in all; longer dampbench fits {args.repeat} time(s), longer peer runs once). "
        "Per CPU-second = candidate-samples / (user + "
        "system CPU time of the process), which load from other processes changes little. All wall-clock rates: "
        + "; ".join([f"{p['peer']} {p['problem']}/{p['algorithm']} "
                     + ", ".join(rate(x) for x in p.get("rates", [p["candidate_samples_per_s"]])) for p in peers]
                    + [f"dampbench {k[0]}/{k[1]} " + ", ".join(rate(x) for x in v["rates"])
                       for k, v in sorted(ours.items())]) + ".",
        "",
        "dampbench's best/median/worst come from single-run fits over seeds 1..R (`fit --format json` gives no "
        "median); the timed R-run fit's own best / mean: " + "; ".join(
            f"{k[0]}/{k[1]} {metric(v['timed_runs']['best'])} / {metric(v['timed_runs']['mean'])}"
            for k, v in sorted(ours.items())) + ".",
    ]
    if loads:
        l1 = [r["load1"] for r in loads]
        notes += ["", f"Load average (1 min) sampled {len(l1)} times during the measurements: min {min(l1):.2f}, "
                      f"median {statistics.median(l1):.2f}, max {max(l1):.2f} (2 cores)."]
    text = "\n".join([args.header, ""] + speed + [""] + quality + [""] + notes) + "\n"
    with open(args.out, "w") as f:
        f.write(text)
    print(text)
    print("targets met in every row" if verdicts and all(verdicts) else
          "targets NOT met in every row", file=sys.stderr)


if __name__ == "__main__":
    main()
