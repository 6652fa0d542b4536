#!/usr/bin/python3
"""The tables of docs/performance.md from the files scripts/bench.sh writes.

Reads results/bench/bench_<variant>.json (`dampbench bench --format json`) and models_<variant>.json
(Google Benchmark, for the vector-function probes) for the variants portable, native and native-sleef,
and prints in Markdown:
  1. candidate-samples per second of every model: portable and native, 1 and 2 threads, ratios;
  2. the vector-function probe rates (ns per element) for libmvec and SLEEF;
  3. each model's share of its own ceiling: the rate it would reach if it did nothing but its vector calls
     (calls per candidate-sample below × the probe's ns per call), next to the measured rate;
  4. libmvec against SLEEF: `dampbench bench` 1-thread rates of the native builds, side by side.
No dependency beyond the standard library.

Usage: bench/bench_tables.py [results/bench]
"""
import json
import os
import sys

# Vector calls per candidate-sample on the `dampbench bench` record (1 Hz, 1024 samples per cycle,
# X = 0.02): the laws in models/*.cpp; for the ODE models, calls per RK4 stage × 4 stages × sub-steps per
# sample (ceil(dt·max|v|·kSubstepsPerStroke / stroke): 2 for Bouc–Wen, Spencer and Maxwell, 1 for fdsp),
# plus the force's own calls (Maxwell: one |x_k|^β per sample).
CALLS = {
    "fvd.linear_viscous": {},
    "fvd.generalized_viscous": {"exp": 1},
    "fvd.gv_linear_elastic": {"exp": 1},
    "fvd.gv_quadratic_elastic": {"exp": 1},
    "crfd.gvnem": {"exp": 2, "tanh": 1},
    "crfd.gvnem_modified": {"tanh": 1},
    "crfd.kwok": {"tanh": 1},
    "crfd.maxwell": {"log": 9, "exp": 9},
    "mrd.magic_formula": {"atan": 2, "sin": 1},
    "mrd.bingham": {},
    # one exact |z|^n per sub-step (first RK4 stage), the three later stages from the
    # binomial series (engine/kernels/ode_kernel.hpp); the 2-4 % of stages that fall back are not counted
    "mrd.bouc_wen": {"log": 2, "exp": 2},
    "mrd.spencer": {"log": 2, "exp": 2},
    "mrd.spencer_voltage": {"log": 1, "exp": 1},
    "mrd.spencer_freq": {"log": 1, "exp": 1},
}


def load(path):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, json.JSONDecodeError) as e:
        sys.exit(f"{path}: cannot read ({e}); run scripts/bench.sh first")


def probes(path):
    """{function: ns per element} from the vector/<f> benchmarks of a Google Benchmark JSON file."""
    out = {}
    for b in load(path).get("benchmarks", []):
        name = b.get("name", "")
        if name.startswith("vector/") and b.get("run_type", "iteration") == "iteration":
            out[name.split("/")[1]] = 1e9 / b["items_per_second"]
    return out


def g(x):
    return f"{x:.3g}"


def main():
    folder = sys.argv[1] if len(sys.argv) > 1 else "results/bench"
    bench = {v: load(os.path.join(folder, f"bench_{v}.json")) for v in ("portable", "native", "native-sleef")}
    probe = {v: probes(os.path.join(folder, f"models_{v}.json")) for v in ("portable", "native", "native-sleef")}
    models = list(bench["native"]["models"])

    print("| model | portable 1t | portable 2t | native 1t | native 2t | 2t/1t portable | 2t/1t native "
          "| lanes/scalar portable | lanes/scalar native | limit ratio native |")
    print("|---|" + "---:|" * 9)
    for m in models:
        p, n = bench["portable"]["models"][m], bench["native"]["models"][m]
        print(f"| {m} | {g(p['cand_samples_per_s_1t'])} | {g(p['cand_samples_per_s_2t'])} "
              f"| {g(n['cand_samples_per_s_1t'])} | {g(n['cand_samples_per_s_2t'])} "
              f"| {p['cand_samples_per_s_2t'] / p['cand_samples_per_s_1t']:.2f} "
              f"| {n['cand_samples_per_s_2t'] / n['cand_samples_per_s_1t']:.2f} "
              f"| {p['scalar_ratio']:.2f} | {n['scalar_ratio']:.2f} | {n['limit_ratio']:.3f} |")
    for v in ("portable", "native"):
        mach = bench[v]["machine"]
        print(f"\n{v}: vector-exp probe {g(mach['exp_per_s_1t'])} exp/s on 1 thread ({mach['vector_isa']}, "
              f"{mach['build']})", end="")
    print("\n")

    funcs = ["exp", "log", "tanh", "atan", "sin", "abs_pow_chain"]
    print("| ns per element, 1 thread | " + " | ".join(funcs) + " |")
    print("|---|" + "---:|" * len(funcs))
    for v in ("portable", "native", "native-sleef"):
        print(f"| {v} | " + " | ".join(f"{probe[v][f]:.2f}" if f in probe[v] else "" for f in funcs) + " |")
    print()

    print("| model (native, 1 thread) | vector calls per candidate-sample | ceiling (candidate-samples/s) "
          "| measured | share of ceiling |")
    print("|---|---|---:|---:|---:|")
    for m in models:
        calls = CALLS.get(m)
        if not calls:
            continue
        ns = sum(k * probe["native"][f] for f, k in calls.items())
        measured = bench["native"]["models"][m]["cand_samples_per_s_1t"]
        desc = " + ".join(f"{k} {f}" for f, k in calls.items())
        print(f"| {m} | {desc} | {g(1e9 / ns)} | {g(measured)} | {measured * ns / 1e9:.2f} |")
    print()

    print("| model | native libmvec 1t | native SLEEF 1t | SLEEF / libmvec |")
    print("|---|---:|---:|---:|")
    for m in models:
        a = bench["native"]["models"][m]["cand_samples_per_s_1t"]
        b = bench["native-sleef"]["models"][m]["cand_samples_per_s_1t"]
        print(f"| {m} | {g(a)} | {g(b)} | {b / a:.2f} |")


if __name__ == "__main__":
    main()
