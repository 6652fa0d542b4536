#!/usr/bin/python3
"""Issue 13's budget check of the utfsm preset: is every (model, file) best of the preset within 2 % of the best
found with a 10x budget?

Writes a copy of datasets/presets/utfsm.toml with every optimizer's iterations x10 (the per-file split only), runs
both with `dampbench run`, and compares the best run of each (model, file) group. Takes ~45 min on 2 cores
(preset 9 min, 10x 33 min). Usage:

    scripts/utfsm_budget_check.py [--dampbench build/dampbench] [--out /tmp/utfsm_check] [--factor 10]
"""
import argparse
import pathlib
import re
import sqlite3
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent


def scaled_spec(text: str, factor: int) -> str:
    """The preset with iterations x factor, without the current-dependent model, split and table."""
    text = re.sub(r'^name = "utfsm"', 'name = "utfsm_budget"', text, count=1, flags=re.M)
    text = re.sub(r"^iterations = (\d+)", lambda m: f"iterations = {int(m.group(1)) * factor}", text, flags=re.M)
    blocks = re.split(r"(?m)^(?=\[\[|# )", text)
    keep = [b for b in blocks if "(I)" not in b and 'name = "current"' not in b and 'split = "current"' not in b]
    return "".join(keep)


def best_per_group(store: pathlib.Path) -> dict:
    db = sqlite3.connect(f"file:{store}?mode=ro", uri=True)
    q = """select m.name, d.name, min(r.best_value) from groups g join runs r on r.grp = g.grp
           join models m on m.part = g.part and m.model = g.model
           join fitsets f on f.part = g.part and f.split = g.split and f.fitset = g.fitset
           join datasets d on d.part = g.part and d.dataset = json_extract(f.fit, '$[0]')
           where json_array_length(f.fit) = 1 group by g.grp"""
    return {(m, d): v for m, d, v in db.execute(q)}


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--dampbench", default=str(ROOT / "build" / "dampbench"))
    ap.add_argument("--out", default="/tmp/utfsm_check")
    ap.add_argument("--factor", type=int, default=10)
    ap.add_argument("--tolerance", type=float, default=0.02)
    a = ap.parse_args()
    out = pathlib.Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    preset = ROOT / "datasets" / "presets" / "utfsm.toml"
    big = out / "utfsm_budget.toml"
    big.write_text(scaled_spec(preset.read_text(), a.factor))
    for spec, folder in ((preset, out / "preset"), (big, out / "big")):
        subprocess.run([a.dampbench, "run", str(spec), "-o", str(folder), "--quiet"], check=True)
    small, large = best_per_group(out / "preset" / "store.sqlite"), best_per_group(out / "big" / "store.sqlite")
    rows = sorted(((small[k] - v) / v, k, small[k], v) for k, v in large.items() if k in small)
    for rel, (model, data), s, b in rows[::-1][:10]:
        print(f"{rel:+.4%}  {model:22s} {data:18s} preset {s:.6g}  {a.factor}x {b:.6g}")
    over = [r for r in rows if r[0] > a.tolerance]
    print(f"{len(rows)} (model, file) pairs; {len(over)} more than {a.tolerance:.0%} above the {a.factor}x budget's best")
    return 1 if over or not rows else 0


if __name__ == "__main__":
    sys.exit(main())
