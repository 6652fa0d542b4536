#!/usr/bin/python3
"""The presets' verdicts, and the figures beside them, are the ones docs/reproduce.md shows.

fvd.toml runs the fvd paper's procedure on records whose truth is none of its models (evidence, section "## fvd:
Tables 3–14", rows `| <id> | **<verdict>**`); crfd.toml, mfm.toml and fdsp.toml run the papers' procedures on grids made from a compared model (their verdicts are
recovery checks); crfd_neutral.toml, mfm_neutral.toml and fdsp_neutral.toml on grids whose truth is none of the
compared models (evidence); mfm_utfsm.toml and fdsp_utfsm.toml run the mfm and fdsp papers' protocols on the real
UTFSM damper; lssvm and lssvm_utfsm run `dampbench lssvm --reproduce` by the lssvm paper's protocol (GA on its eq. 8,
tested at the conditions it trained on) on the synthetic LS-SVM set and on the real damper (LSSVM_RUNS, section
"## LS-SVM (lssvm paper)"). Each is run as a user runs it; the test fails when

  - the run fails, or its reproduction.json labels the records' truth or a verdict otherwise than the preset's kind
    (a recovery check on a compared model's grid, evidence elsewhere);
  - a claim's verdict, or the verdict of a parameter table ("Table 2"), equation ("eq. 4.4") or figure ("Fig. 9") of
    the paper that is judged, is missing from
    the table of docs/reproduce.md's section "## crfd, mfm, fdsp" as the row `| <preset> | <id> | **<verdict>**`;
  - a number in that row's text is none of the item's: its values, the paper's (also as printed in %), their
    relative differences in %, the means of each compared model's values, the numbers of the item's own detail and
    claim, or how many numbers the records determine. A figure of the docs that a run no longer gives fails here
    instead of going stale. Numbers that name a condition (followed by Hz, mm, m, A, °, V or kN, alone or as the
    last of a list) or an equation, table or figure are not results and are not checked.

The grid is generated into WORK_DIR (as a preset does on first use); the real-data preset is skipped with a
message when DATA_DIR ($DAMPBENCH_SHARED_DATA_DIR, else the argument, else REPO/../shared/data) is absent. ctest runs
one test per preset (paper_claims_<preset>), so the two cores share them with the rest of the suite: the mfm and
fdsp presets' Spencer law fits take a minute or more of one core's time each, and their COST starts them first.

usage: paper_claims_test.py DAMPBENCH REPO_ROOT WORK_DIR PRESET [DATA_DIR]
"""
import json
import os
import pathlib
import re
import shutil
import subprocess
import sys

RECOVERY_PRESETS = ["crfd", "mfm", "fdsp"]  # grids made from a compared model
EVIDENCE_PRESETS = ["fvd", "crfd_neutral", "mfm_neutral", "fdsp_neutral", "lssvm"]
REAL_DATA_PRESETS = ["mfm_utfsm", "fdsp_utfsm", "lssvm_utfsm"]  # read DATA_DIR/utfsm-mr-damper
LSSVM_RUNS = ["lssvm", "lssvm_utfsm"]  # the lssvm command, not a preset: its paper prints tables and no ranking
SECTION = "## crfd, mfm, fdsp"
OWN_SECTIONS = {"fvd": "## fvd: Tables 3–14"}  # a preset with a section of its own: its rows have no preset column
OTHER_SECTIONS = {run: "## LS-SVM (lssvm paper)" for run in LSSVM_RUNS}  # rows with the run's name, as in SECTION
UTFSM_SETTINGS = ["2mm5Hz", "5mm3Hz", "10mm1Hz", "25mm0x1Hz", "25mm0x25Hz", "25mm0x5Hz"]

NUMBER = re.compile(r"(?<![\w.])([+\-−]?\d+(?:\.\d+)?(?:e[+\-−]?\d+)?)")
CONDITION = re.compile(r"^((?:,\s*|\s+and\s+|\s+or\s+|\s*[–-]\s*)[\d.]+)*\s*(Hz|mm|m|A|°|V|kN)(?!\w)")
# a table, equation, figure or section's item id
PAPER_PART = re.compile(r"Table \d+|eqs?\. [\d.]+(?:-[\d.]+)?|Fig\. \d+|(?:§[\d.]+|Figs\. \d+-\d+),? [\w ,]+")
REFERENCE = re.compile(r"(eqs?\.|Tables?|Figs?\.)\s*(\d+\s*[–,-]\s*)*$")


def as_float(token):
    return float(token.replace("−", "-"))


def numbers_in(text):
    return [as_float(m.group(1)) for m in NUMBER.finditer(text)]


def item_numbers(item):
    """Every number a docs row may quote for this item (see the module's docstring)."""
    values, paper = item["values"], item["paper_values"]
    found = set(values.values()) | set(paper.values())
    found |= {100 * v for v in paper.values()} | {v / 100 for v in paper.values()}  # a paper's % kept as fractions
    found |= {100 * (v - paper[k]) / abs(paper[k]) for k, v in values.items() if paper.get(k)}
    models = {}
    for label, v in values.items():  # "row: model" (claims) or "row column" (tables)
        models.setdefault(label.split(": ", 1)[-1] if ": " in label else label.split(" ", 1)[-1], []).append(v)
    found |= {sum(vs) / len(vs) for vs in models.values()}
    found |= set(numbers_in(item["detail"])) | set(numbers_in(item["claim"]))
    found.add(len(values) - len(item.get("not_determined", [])))
    return {abs(x) for x in found}


def unmatched_in(text, known, names=None):
    """The numbers of `text` that are none of `known` at their printed precision; a number after a match of `names`
    (a regex ending at the number) names something and is not checked."""
    missing = []
    for m in NUMBER.finditer(text):
        before = text[:m.start()]
        if CONDITION.match(text[m.end():]) or REFERENCE.search(before) or (names and names.search(before)):
            continue
        token = m.group(1).replace("−", "-")
        mantissa, _, exponent = token.partition("e")
        decimals = len(mantissa.split(".")[1]) if "." in mantissa else 0
        tolerance = 0.5 * 10 ** (int(exponent or 0) - decimals) * (1 + 1e-9)
        if not any(abs(abs(float(token)) - k) <= tolerance for k in known):
            missing.append(m.group(1))
    return missing


def unmatched_numbers(text, item):
    """The numbers of `text` that are none of the item's at their printed precision."""
    return unmatched_in(text, item_numbers(item))


def docs_section(root, section):
    text = (root / "docs" / "reproduce.md").read_text()
    begin = text.find("\n" + section + "\n")
    if begin < 0:
        sys.exit(f"docs/reproduce.md has no section '{section}'")
    end = text.find("\n## ", begin + len(section) + 1)
    return text[begin:end if end >= 0 else len(text)]


def is_claim(item):
    """A claim of the paper ("table8-laws", "energy-linear-elastic"), not one of its tables (whose id is the table's)."""
    return item["id"] != item["table"]


def checked_items(report):
    """The claims and the paper's parameter tables ("Table 2"), equations ("eq. 4.4", "eqs. 4-9") and figures ("Fig. 9")
    that were judged."""
    for item in report["items"]:
        if is_claim(item) or (PAPER_PART.fullmatch(item["id"]) and item["verdict"] != "not-comparable"):
            yield item


def lssvm_command(exe, root, out, preset, env):
    """The lssvm paper's protocol as docs/reproduce.md gives it: GA on eq. 8 over the training records, tested at the
    conditions trained on (the synthetic set's later windows at 0.4 and 0.8 A; the real damper's 0, 0.5 and 1 A files)."""
    command = [exe, "lssvm", "--fitness", "paper", "-o", str(out), "--reproduce", str(root / "datasets/papers/lssvm.toml")]
    if preset == "lssvm":
        lssvm = root / "datasets" / "lssvm"
        command += ["--truth", "mrd.bouc_wen with current-dependent c0 and alpha, 1 N noise (datasets/lssvm)"]
        command += [arg for f in sorted(lssvm.glob("train_*.csv")) for arg in ("--train", str(f))]
        return command + [arg for f in ("2Hz_0p4A", "2Hz_0p8A", "4Hz_0p4A", "4Hz_0p8A")
                          for arg in ("--test", str(lssvm / f"test_{f}.csv"))]
    data = pathlib.Path(env["DAMPBENCH_SHARED_DATA_DIR"]) / "utfsm-mr-damper"
    files = [str(data / f"{s}{i}.txt") for s in UTFSM_SETTINGS for i in ("0A", "0x5A", "1A")]
    return command + ["--columns", "t,x,v,F", "--units", "x=mm,v=mm/s", "--conditions", "utfsm", "--max-train", "1260"] + \
        [arg for f in files for arg in ("--train", f)] + [arg for f in files for arg in ("--test", f)]


def main():
    presets = RECOVERY_PRESETS + EVIDENCE_PRESETS + REAL_DATA_PRESETS
    if len(sys.argv) < 5 or sys.argv[4] not in presets:
        sys.exit(f"usage: paper_claims_test.py DAMPBENCH REPO_ROOT WORK_DIR PRESET [DATA_DIR], PRESET one of "
                 f"{', '.join(presets)}")
    exe, root, work, preset = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3]), sys.argv[4]
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    docs = docs_section(root, OWN_SECTIONS.get(preset, OTHER_SECTIONS.get(preset, SECTION)))
    env = dict(os.environ, DAMPBENCH_GENERATED_DIR=str(work / "generated"))
    if preset in REAL_DATA_PRESETS:
        data = pathlib.Path(os.environ.get("DAMPBENCH_SHARED_DATA_DIR") or
                            (sys.argv[5] if len(sys.argv) > 5 and sys.argv[5] else root.parent / "shared" / "data"))
        if not (data / "utfsm-mr-damper").is_dir():
            print(f"skipped {preset}: no real data at {data / 'utfsm-mr-damper'}")
            sys.exit(77)  # ctest's SKIP_RETURN_CODE
        env["DAMPBENCH_SHARED_DATA_DIR"] = str(data)
    out = work / preset
    command = lssvm_command(exe, root, out, preset, env) if preset in LSSVM_RUNS else \
        [exe, "run", str(root / "datasets" / "presets" / f"{preset}.toml"), "-o", str(out), "--quiet", "--no-report"]
    run = subprocess.run(command + ["--threads", "1"], env=env, capture_output=True, text=True)
    if run.returncode != 0:
        sys.exit(f"{preset}: exit {run.returncode}\n{run.stdout}{run.stderr}")
    report = json.loads((out / "reproduction.json").read_text())
    recovery = preset in RECOVERY_PRESETS
    failures = []
    if report["data"]["truth_is_compared_model"] is not recovery:
        failures.append(f"{preset}: its truth is {'not ' if recovery else ''}labelled a compared model")
    claims = 0
    for item in report["items"]:
        if item["recovery_check"] is not recovery:
            failures.append(f"{preset} {item['id']}: {'not ' if recovery else ''}labelled a recovery check")
    for item in checked_items(report):
        claims += is_claim(item)
        own = preset in OWN_SECTIONS
        prefix = f"| {item['id']} | **{item['verdict']}**" if own else f"| {preset} | {item['id']} | **{item['verdict']}**"
        row = next((line for line in docs.split("\n") if line.startswith(prefix)), None)
        if row is None:
            failures.append(f"docs/reproduce.md lacks the row '{prefix}' ({item['detail']})")
            continue
        columns = 2 if own else 3  # the row's text after its preset, id and verdict
        what = row.split(" | ", columns)[columns] if row.count(" | ") >= columns else ""
        missing = unmatched_numbers(what, item)
        if missing:
            failures.append(f"docs/reproduce.md, row '{prefix}': {', '.join(missing)} is none of the run's numbers for "
                            f"this item ({item['detail']})")
    if claims == 0 and preset not in LSSVM_RUNS:
        failures.append(f"{preset}: no claim in reproduction.json")
    if preset in LSSVM_RUNS and not any(item["verdict"] != "not-comparable" for item in report["items"]):
        failures.append(f"{preset}: no item of reproduction.json is judged")
    print(f"{preset}: {claims} claims and the parameter tables checked")
    if failures:
        sys.exit("\n".join(failures))


if __name__ == "__main__":
    main()
