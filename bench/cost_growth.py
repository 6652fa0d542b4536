#!/usr/bin/python3
"""Cost growth tables and plot from the Google Benchmark suite (bench/bench_models.cpp).

Reads the JSON of `bench_models --benchmark_format=json` (benchmarks named
evaluate/<model>/candidates:C/samples:S/threads:T/real_time) and prints, per model:
  - ns per candidate-sample on 2 threads for every candidates × samples cell: a constant table means the
    cost grows linearly in candidates and in samples;
  - the 1 → 2 thread speed-up for every cell.
With --svg FILE it also draws the time of one batch evaluation against candidates × samples (log-log, one
line per model and thread count, a slope-1 guide): points on a line of slope 1 are linear scaling.
No dependency beyond the standard library (the SVG is written by hand).

Usage: bench/cost_growth.py results/bench/growth_native.json [--svg docs/cost_growth.svg]
"""
import argparse
import json
import math
import re
import sys
from collections import defaultdict

NAME = re.compile(r"^evaluate/(?P<model>[^/]+)/candidates:(?P<c>\d+)/samples:(?P<s>\d+)/threads:(?P<t>\d+)")


def load(path):
    """{(model, candidates, samples, threads): (seconds per batch, candidate-samples per second)}"""
    try:
        with open(path) as f:
            doc = json.load(f)
    except (OSError, json.JSONDecodeError) as e:
        sys.exit(f"{path}: cannot read a Google Benchmark JSON file ({e})")
    out = {}
    scale = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}
    for b in doc.get("benchmarks", []):
        m = NAME.match(b.get("name", ""))
        if not m or b.get("run_type", "iteration") != "iteration":
            continue
        key = (m["model"], int(m["c"]), int(m["s"]), int(m["t"]))
        out[key] = (b["real_time"] * scale[b.get("time_unit", "ns")], b["items_per_second"])
    if not out:
        sys.exit(f"{path}: no evaluate/<model>/candidates:/samples:/threads: benchmarks in it")
    return out


def tables(data):
    models = sorted({k[0] for k in data})
    lines = []
    for model in models:
        cells = {k[1:]: v for k, v in data.items() if k[0] == model}
        cands = sorted({c for c, _, _ in cells})
        samples = sorted({s for _, s, _ in cells})
        threads = sorted({t for _, _, t in cells})
        top = max(threads)
        lines.append(f"**{model}**: ns per candidate-sample on {top} thread(s) (constant ⇒ linear growth)\n")
        lines.append("| candidates \\ samples | " + " | ".join(str(s) for s in samples) + " |")
        lines.append("|---:|" + "---:|" * len(samples))
        for c in cands:
            row = [f"{1e9 / cells[(c, s, top)][1]:.3g}" if (c, s, top) in cells else "" for s in samples]
            lines.append(f"| {c} | " + " | ".join(row) + " |")
        if len(threads) > 1:
            lo = min(threads)
            lines.append(f"\n{model}: speed-up {lo} → {top} threads\n")
            lines.append("| candidates \\ samples | " + " | ".join(str(s) for s in samples) + " |")
            lines.append("|---:|" + "---:|" * len(samples))
            for c in cands:
                row = []
                for s in samples:
                    a, b = cells.get((c, s, lo)), cells.get((c, s, top))
                    row.append(f"{b[1] / a[1]:.2f}" if a and b else "")
                lines.append(f"| {c} | " + " | ".join(row) + " |")
        lines.append("")
    return "\n".join(lines)


def svg(data, path):
    W, H, L, R, T, B = 720, 480, 70, 190, 20, 50
    xs = [c * s for (_, c, s, _) in data]
    ys = [v[0] for v in data.values()]
    x0, x1 = math.floor(math.log10(min(xs))), math.ceil(math.log10(max(xs)))
    y0, y1 = math.floor(math.log10(min(ys))), math.ceil(math.log10(max(ys)))
    px = lambda x: L + (math.log10(x) - x0) / (x1 - x0) * (W - L - R)
    py = lambda y: H - B - (math.log10(y) - y0) / (y1 - y0) * (H - T - B)
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" font-family="sans-serif" font-size="11">',
           f'<rect width="{W}" height="{H}" fill="white"/>']
    for e in range(x0, x1 + 1):
        out.append(f'<line x1="{px(10**e):.1f}" y1="{T}" x2="{px(10**e):.1f}" y2="{H-B}" stroke="#ddd"/>')
        out.append(f'<text x="{px(10**e):.1f}" y="{H-B+15}" text-anchor="middle">1e{e}</text>')
    for e in range(y0, y1 + 1):
        out.append(f'<line x1="{L}" y1="{py(10**e):.1f}" x2="{W-R}" y2="{py(10**e):.1f}" stroke="#ddd"/>')
        out.append(f'<text x="{L-5}" y="{py(10**e)+4:.1f}" text-anchor="end">1e{e} s</text>')
    out.append(f'<text x="{(L+W-R)/2}" y="{H-10}" text-anchor="middle">candidates × samples per batch</text>')
    colors = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2", "#17becf"]
    series = defaultdict(list)
    for (model, c, s, t), (sec, _) in data.items():
        series[(model, t)].append((c * s, sec))
    for i, ((model, t), pts) in enumerate(sorted(series.items())):
        pts.sort()
        color = colors[i % len(colors)]
        path_d = " ".join(f"{'M' if j == 0 else 'L'}{px(x):.1f},{py(y):.1f}" for j, (x, y) in enumerate(pts))
        dash = '' if t > 1 else ' stroke-dasharray="4,3"'
        out.append(f'<path d="{path_d}" fill="none" stroke="{color}"{dash}/>')
        for x, y in pts:
            out.append(f'<circle cx="{px(x):.1f}" cy="{py(y):.1f}" r="2.5" fill="{color}"/>')
        out.append(f'<text x="{W-R+8}" y="{T+14*(i+1)}" fill="{color}">{model}, {t} thread(s)</text>')
    # slope-1 guide through the smallest point of the first series
    gx, gy = min(series[sorted(series)[0]])
    ex = 10 ** x1
    out.append(f'<line x1="{px(gx):.1f}" y1="{py(gy):.1f}" x2="{px(ex):.1f}" y2="{py(gy*ex/gx):.1f}" '
               f'stroke="black" stroke-dasharray="1,3"/>')
    out.append(f'<text x="{W-R+8}" y="{T+14*(len(series)+2)}">dotted black: slope 1 (linear)</text>')
    out.append("</svg>")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("json", help="bench_models --benchmark_format=json output")
    ap.add_argument("--svg", help="write the log-log plot here")
    a = ap.parse_args()
    data = load(a.json)
    print(tables(data))
    if a.svg:
        svg(data, a.svg)


if __name__ == "__main__":
    main()
