#!/usr/bin/python3
"""The presets whose verdicts are evidence give the verdicts docs/reproduce.md shows.

crfd_neutral.toml, mfm_neutral.toml and fdsp_neutral.toml run their paper's preset on a grid whose truth is none of the compared
models (datasets/README.md); mfm_utfsm.toml runs the mfm paper's protocol on the real UTFSM damper. Each is run as a
user runs it; the test fails when

  - the run fails, or its reproduction.json labels the records' truth a compared model or a verdict a recovery
    check (on these records a verdict is evidence about the paper's claim);
  - a claim's verdict is missing from the table of docs/reproduce.md's section "## crfd, mfm, fdsp" as the row
    `| <preset> | <claim id> | **<verdict>**`, so a changed result cannot leave the docs behind.

The grid is generated into WORK_DIR (as a preset does on first use); the real-data preset is skipped with a
message when DATA_DIR ($DAMPBENCH_SHARED_DATA_DIR, else the argument, else REPO/../shared/data) is absent. ctest runs
one test per preset (paper_claims_<preset>), so the two cores share them with the rest of the suite: the mfm
and fdsp presets' Spencer law fits take minutes of one core's time each, and their COST starts them first.

usage: paper_claims_test.py DAMPBENCH REPO_ROOT WORK_DIR PRESET [DATA_DIR]
"""
import json
import os
import pathlib
import shutil
import subprocess
import sys

PRESETS = ["crfd_neutral", "mfm_neutral", "fdsp_neutral"]
REAL_DATA_PRESETS = ["mfm_utfsm"]  # read DATA_DIR/utfsm-mr-damper
SECTION = "## crfd, mfm, fdsp"


def docs_section(root):
    text = (root / "docs" / "reproduce.md").read_text()
    begin = text.find("\n" + SECTION + "\n")
    if begin < 0:
        sys.exit(f"docs/reproduce.md has no section '{SECTION}'")
    end = text.find("\n## ", begin + len(SECTION) + 1)
    return text[begin:end if end >= 0 else len(text)]


def main():
    if len(sys.argv) < 5 or sys.argv[4] not in PRESETS + REAL_DATA_PRESETS:
        sys.exit(f"usage: paper_claims_test.py DAMPBENCH REPO_ROOT WORK_DIR PRESET [DATA_DIR], PRESET one of "
                 f"{', '.join(PRESETS + REAL_DATA_PRESETS)}")
    exe, root, work, preset = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3]), sys.argv[4]
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    docs = docs_section(root)
    env = dict(os.environ, DAMPBENCH_GENERATED_DIR=str(work / "generated"))
    if preset in REAL_DATA_PRESETS:
        data = pathlib.Path(os.environ.get("DAMPBENCH_SHARED_DATA_DIR") or
                            (sys.argv[5] if len(sys.argv) > 5 and sys.argv[5] else root.parent / "shared" / "data"))
        if not (data / "utfsm-mr-damper").is_dir():
            print(f"skipped {preset}: no real data at {data / 'utfsm-mr-damper'}")
            sys.exit(77)  # ctest's SKIP_RETURN_CODE
        env["DAMPBENCH_SHARED_DATA_DIR"] = str(data)
    out = work / preset
    run = subprocess.run([exe, "run", str(root / "datasets" / "presets" / f"{preset}.toml"), "-o", str(out),
                          "--quiet", "--no-report", "--threads", "1"], env=env, capture_output=True, text=True)
    if run.returncode != 0:
        sys.exit(f"{preset}: exit {run.returncode}\n{run.stdout}{run.stderr}")
    report = json.loads((out / "reproduction.json").read_text())
    failures = []
    if report["data"]["truth_is_compared_model"] is not False:
        failures.append(f"{preset}: its truth is labelled a compared model")
    claims = 0
    for item in report["items"]:
        if item["recovery_check"] is not False:
            failures.append(f"{preset} {item['id']}: labelled a recovery check")
        if not item["id"].startswith("table") or "-" not in item["id"]:
            continue  # a table, not a claim ("table8-laws")
        claims += 1
        row = f"| {preset} | {item['id']} | **{item['verdict']}**"
        if row not in docs:
            failures.append(f"docs/reproduce.md lacks the row '{row}' ({item['detail']})")
    if claims == 0:
        failures.append(f"{preset}: no claim in reproduction.json")
    print(f"{preset}: {claims} claims checked")
    if failures:
        sys.exit("\n".join(failures))


if __name__ == "__main__":
    main()
