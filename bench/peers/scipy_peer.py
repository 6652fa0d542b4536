#!/usr/bin/python3
"""scipy peer of dampbench: scipy.optimize.differential_evolution with a vectorized numpy objective.

Problems (same equations, metric and RK4 sub-step rule as dampbench; see README.md):
  fvd  fvd.gv_linear_elastic  F = m*a + C*sgn(v)*|v|^alpha + K1*x      (algebraic)
  bw   mrd.bouc_wen           dz/dt = -gamma|v| sgn(z)|z|^n - beta v |z|^n + A v,
                              F = c0 v + k0 (x - x0) + alpha z          (RK4, sub-steps per sample)
Metric: of_abs = trapezoid integral of |F_m - F| dt / (sigma(F_m) * T)  (engine/model/metrics.hpp).

Input: a CSV t,x,v,a,F in SI (the signals dampbench itself uses; bench/peers/run_peers.sh writes it).
Output: one JSON object on stdout (evaluations, wall time, candidate-samples/s, per-run final metrics).
"""
import argparse
import json
import math
import sys
import time

import numpy as np
from scipy.optimize import differential_evolution


def load_signals(path):
    data = np.genfromtxt(path, delimiter=",", names=True, dtype=float, comments="#")
    t, x, v, a, F = (np.ascontiguousarray(data[c]) for c in ("t", "x", "v", "a", "F"))
    n = t.size
    w = np.zeros(n)  # trapezoid weights, as engine/record/signals.cpp
    half = 0.5 * np.diff(t)
    w[:-1] += half
    w[1:] += half
    duration = t[-1] - t[0]
    sigma = math.sqrt(float(np.sum((F - F.mean()) ** 2)) / n)  # population standard deviation
    return dict(t=t, x=x, v=v, a=a, F=F, w=w, duration=duration, sigma=sigma,
                ptp=float(x.max() - x.min()), vmax=float(np.abs(v).max()), n=n)


def log_abs_clamped(v):
    """engine/common/vector_math.hpp: log|v| clamped so |v|^alpha = exp(alpha*log|v|) is finite at 0."""
    return np.log(np.abs(v) + 1e-300)


def make_fvd_objective(s):
    """fvd.gv_linear_elastic, vectorized over the population: params (4, S) -> (S,)."""
    a, x, Fm, w = s["a"], s["x"], s["F"], s["w"]
    sgn_v = np.sign(s["v"])
    log_abs_v = log_abs_clamped(s["v"])
    scale = 1.0 / (s["sigma"] * s["duration"])

    def objective(p):
        m, C, alpha, K1 = (p[j][:, None] for j in range(4))
        F = m * a + C * sgn_v * np.exp(alpha * log_abs_v) + K1 * x  # (S, N)
        value = np.abs(Fm - F) @ w * scale
        value[~np.isfinite(value)] = np.inf
        return value

    return objective


def ode_substeps(s, k, per_stroke):
    """engine/kernels/ode_kernel.hpp ode_substeps for a stroke-driven law (Bouc-Wen):
    ceil(dt*V*per_stroke/ptp), at least 1, V the larger |v| at the interval's two ends."""
    dt = s["t"][k] - s["t"][k - 1]
    if s["ptp"] <= 0:
        return 1
    vk = max(abs(s["v"][k - 1]), abs(s["v"][k]))
    n = math.ceil(dt * vk * per_stroke / s["ptp"])
    return max(1, int(min(n, 1e6)))


def make_bouc_wen_objective(s, per_stroke):
    """mrd.bouc_wen, vectorized over the population, time loop in Python with the same RK4 sub-steps."""
    t, x, v, Fm, w = s["t"], s["x"], s["v"], s["F"], s["w"]
    n = s["n"]
    substeps = [0] + [ode_substeps(s, k, per_stroke) for k in range(1, n)]
    scale = 1.0 / (s["sigma"] * s["duration"])

    def objective(p):
        c0, k0, x0, alpha, beta, gamma, A, nexp = (np.ascontiguousarray(p[j]) for j in range(8))
        S = c0.size
        z = np.zeros(S)
        failed = np.zeros(S, dtype=bool)
        acc = np.zeros(S)

        def rate(zz, u):
            zn = np.exp(nexp * log_abs_clamped(zz))
            return (-gamma * abs(u)) * np.sign(zz) * zn - (beta * u) * zn + A * u

        for k in range(n):
            if k > 0:
                ns = substeps[k]
                h = (t[k] - t[k - 1]) / ns
                v0, dv = v[k - 1], v[k] - v[k - 1]
                for i in range(ns):  # inputs interpolated linearly between samples (x is unused by the rate)
                    va, vm, vb = v0 + (i / ns) * dv, v0 + ((i + 0.5) / ns) * dv, v0 + ((i + 1) / ns) * dv
                    k1 = rate(z, va)
                    k2 = rate(z + 0.5 * h * k1, vm)
                    k3 = rate(z + 0.5 * h * k2, vm)
                    k4 = rate(z + h * k3, vb)
                    z = z + (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
                bad = ~(np.abs(z) < 1e30)  # masking as the kernel: flag the lane, reset its state
                if bad.any():
                    failed |= bad
                    z[bad] = 0.0
            F = c0 * v[k] + k0 * (x[k] - x0) + alpha * z
            acc += w[k] * np.abs(Fm[k] - F)
        value = acc * scale
        value[failed | ~np.isfinite(value)] = np.inf
        return value

    return objective, sum(substeps)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--problem", choices=["fvd", "bw"], required=True)
    ap.add_argument("--data", required=True, help="CSV t,x,v,a,F in SI")
    ap.add_argument("--lower", required=True, help="comma-separated lower bounds (dampbench's defaults)")
    ap.add_argument("--upper", required=True, help="comma-separated upper bounds")
    ap.add_argument("--pop", type=int, default=50)
    ap.add_argument("--gens", type=int, default=100, help="evaluated generations including the initial one")
    ap.add_argument("--F", type=float, default=0.5)
    ap.add_argument("--CR", type=float, default=0.9)
    ap.add_argument("--runs", type=int, default=50)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--substeps-per-stroke", type=float, default=600.0)
    args = ap.parse_args()

    s = load_signals(args.data)
    lower = [float(v) for v in args.lower.split(",")]
    upper = [float(v) for v in args.upper.split(",")]
    bounds = list(zip(lower, upper))
    if args.problem == "fvd":
        objective, rk4_steps = make_fvd_objective(s), 0
    else:
        objective, rk4_steps = make_bouc_wen_objective(s, args.substeps_per_stroke)
    d = len(bounds)
    counter = [0]  # candidates evaluated: scipy 1.10's nfev counts vectorized calls, not candidates

    def counted(p):
        counter[0] += p.shape[1]
        return objective(p)

    values, nfev_total, wall, cpu = [], 0, 0.0, 0.0
    for run in range(args.runs):
        rng = np.random.default_rng([args.seed, run])
        # The population size is set through `init` (popsize is a multiplier of d in scipy, and 50/d is
        # not whole): N members uniform in the box, as dampbench's initial population.
        init = np.array(lower) + rng.random((args.pop, d)) * (np.array(upper) - np.array(lower))
        t0, cpu0 = time.perf_counter(), time.process_time()
        before = counter[0]
        res = differential_evolution(
            counted, bounds, strategy="rand1bin", maxiter=args.gens - 1, popsize=1, init=init,
            mutation=args.F, recombination=args.CR, tol=0.0, atol=0.0, polish=False, seed=rng,
            updating="deferred", vectorized=True)
        wall += time.perf_counter() - t0
        cpu += time.process_time() - cpu0
        values.append(float(res.fun))
        nfev_total += counter[0] - before
        print(f"scipy {args.problem} run {run + 1}/{args.runs}: {res.fun:.6g} ({counter[0] - before} evaluations)",
              file=sys.stderr, flush=True)

    v = np.sort(np.array(values))
    out = {
        "peer": "scipy", "scipy": __import__("scipy").__version__, "numpy": np.__version__,
        "problem": args.problem, "algorithm": "de", "runs": args.runs, "samples": int(s["n"]),
        "rk4_steps_per_candidate": rk4_steps, "evaluations": nfev_total, "wall_time_s": wall,
        "candidate_samples_per_s": nfev_total * s["n"] / wall, "cpu_time_s": cpu,
        "candidate_samples_per_cpu_s": nfev_total * s["n"] / cpu,
        "best": float(v[0]), "median": float(np.median(v)), "worst": float(v[-1]), "values": values,
    }
    print(json.dumps(out))


if __name__ == "__main__":
    main()
