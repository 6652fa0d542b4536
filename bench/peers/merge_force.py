#!/usr/bin/python3
"""Writes the peers' input t,x,v,a,F (SI) for a test record.

t, x, v, a come from `dampbench simulate --input RECORD` (the signals exactly as dampbench prepares them:
units converted, v and a by engine/record/differentiate.cpp's 3rd-order scheme, printed with 17 digits); F is the
record's measured force converted to newtons (header unit N, kN or MN).

usage: merge_force.py SIMULATE_OUTPUT.csv RECORD.csv OUT.csv
"""
import csv
import re
import sys

UNITS = {"": 1.0, "N": 1.0, "kN": 1e3, "MN": 1e6}


def main():
    sim_path, record_path, out_path = sys.argv[1:4]
    sim = list(csv.DictReader(open(sim_path)))
    lines = [line for line in open(record_path) if line.strip() and not line.startswith("#")]
    header = [h.strip() for h in lines[0].split(",")]
    col, scale = None, None
    for i, h in enumerate(header):
        m = re.fullmatch(r"F\s*(?:\[(\w*)\])?", h)
        if m:
            col, scale = i, UNITS[m.group(1) or ""]
    if col is None:
        sys.exit(f"{record_path}: no F column in {header}")
    force = [float(line.split(",")[col]) * scale for line in lines[1:]]
    if len(force) != len(sim):
        sys.exit(f"{record_path}: {len(force)} samples, simulate wrote {len(sim)}")
    with open(out_path, "w") as out:
        out.write("t,x,v,a,F\n")
        for row, f in zip(sim, force):
            out.write(f"{row['t']},{row['x']},{row['v']},{row['a']},{f!r}\n")


if __name__ == "__main__":
    main()
