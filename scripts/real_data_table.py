#!/usr/bin/python3
"""Identifies the MR-damper models on every UTFSM test file (../shared/data/utfsm-mr-damper) and one
current-dependent Bouc-Wen law over all files, and prints the nrmse table for the README.

Usage: scripts/real_data_table.py [--data DIR] [--dampbench PATH] [--runs R] [--pop N] [--iters L]

Each fit is `dampbench fit --model M --data FILE --columns t,x,v,F --units x=mm,v=mm/s --conditions utfsm
--metric nrmse ...`; the law fit adds `--laws` and every file at once. Data: M. Quiroz (UTFSM, 2022), MIT
licence, DanielMaurelE/vRTHS_AMBC_MRdamper.
"""
import argparse
import glob
import json
import os
import subprocess
import sys
import time

MODELS = ["mrd.bingham", "mrd.magic_formula", "mrd.bouc_wen", "mrd.spencer"]
LAW = ("mrd.bouc_wen", "c0=poly(I,1);k0=poly(I,1);alpha=poly(I,1)")
LOADER = ["--columns", "t,x,v,F", "--units", "x=mm,v=mm/s", "--conditions", "utfsm", "--metric", "nrmse"]


def fit(exe, model, files, args, laws=None):
    cmd = [exe, "fit", "--model", model, *LOADER, "--runs", str(args.runs), "--pop", str(args.pop),
           "--iters", str(args.iters), "--seed", "1", "--format", "json"]
    for f in files:
        cmd += ["--data", f]
    if laws:
        cmd += ["--laws", laws]
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def per_file_nrmse(exe, model, coefficients, path):
    """nrmse of given law coefficients on one file (`dampbench evaluate`)."""
    params = ",".join(f"{k}={v!r}" for k, v in coefficients.items())
    loader = [a for a in LOADER if a not in ("--metric", "nrmse")]
    cmd = [exe, "evaluate", "--model", model[0], "--laws", model[1], *loader, "--data", path, "--params", params,
           "--format", "json"]
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    return json.loads(out)[path]["nrmse"]


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    p = argparse.ArgumentParser()
    p.add_argument("--data", default=os.path.join(here, "..", "..", "shared", "data", "utfsm-mr-damper"))
    p.add_argument("--dampbench", default=os.path.join(here, "..", "build", "dampbench"))
    p.add_argument("--runs", type=int, default=3)
    p.add_argument("--pop", type=int, default=40)
    p.add_argument("--iters", type=int, default=100)
    args = p.parse_args()
    files = sorted(glob.glob(os.path.join(args.data, "*A.txt")))
    if not files:
        sys.exit(f"no UTFSM files in {args.data}: the data lives in ../shared/data beside the repository")
    start = time.time()
    rows = []
    for f in files:
        name = os.path.basename(f)[:-4]
        row = [name] + [fit(args.dampbench, m, [f], args)["metrics"]["nrmse"] for m in MODELS]
        rows.append(row)
        print("  " + name, file=sys.stderr)
    law = fit(args.dampbench, LAW[0], files, args, LAW[1])
    for row, f in zip(rows, files):
        row.append(per_file_nrmse(args.dampbench, LAW, law["best_params"], f))
    header = ["file"] + MODELS + ["bouc_wen, laws in I (all files)"]
    print("| " + " | ".join(header) + " |")
    print("|---|" + "---:|" * (len(header) - 1))
    for row in rows:
        print("| " + " | ".join([row[0]] + [f"{v:.4f}" for v in row[1:]]) + " |")
    means = [sum(r[i] for r in rows) / len(rows) for i in range(1, len(header))]
    print("| **mean** | " + " | ".join(f"**{m:.4f}**" for m in means) + " |")
    print(f"\n{len(files)} files, runs={args.runs}, pop={args.pop}, iters={args.iters}; "
          f"law fit: {LAW[1]}; wall {time.time() - start:.0f} s", file=sys.stderr)


if __name__ == "__main__":
    main()
