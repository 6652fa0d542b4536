#!/usr/bin/python3
"""docs/reproduce.md's UTFSM table and the README's "Real MR-damper data" bullet say what the `utfsm` preset writes.

The whole preset takes 84 s on two cores, so the test runs its per-file split (the four base models, the preset's
optimizers, seed and runs) on six of the 30 files, one per amplitude-frequency setting at a spread of currents: a
per-file fit depends only on its own record and task key, so each cell must equal the table's at its printed
precision (%.6g, with the † that marks a group whose runs disagree). Then, over the whole table: each column's mean is the **mean** row (4 digits); the README bullet's
means are the mean row's, rounded to 3 digits; and "Spencer <= Bouc-Wen <= Bingham on each" holds on every row. A
change that moves the fits then fails here instead of leaving the figures stale (docs/reproduce.md says how to
regenerate the table).

usage: utfsm_table_test.py DAMPBENCH REPO_ROOT WORK_DIR DATA_DIR
Exit 77 (ctest: skipped) without DATA_DIR/utfsm-mr-damper.
"""
import csv
import os
import pathlib
import re
import shutil
import subprocess
import sys

SAMPLE = ["10mm1Hz0A", "25mm0x1Hz0x25A", "25mm0x25Hz0x5A", "25mm0x5Hz0x75A", "2mm5Hz1A", "5mm3Hz0x5A"]
MODELS = ["mrd.bingham", "mrd.magic_formula", "mrd.bouc_wen", "mrd.spencer"]  # the table's column order
README_NAMES = {"mrd.spencer": "Spencer", "mrd.bouc_wen": "Bouc–Wen", "mrd.magic_formula": "magic formula",
                "mrd.bingham": "Bingham"}


def docs_table(reproduce):
    """{file: [nrmse per MODELS]} and the mean row, from the table under '## Real MR-damper data (UTFSM)'."""
    text = reproduce.read_text()
    section = text[text.index("## Real MR-damper data (UTFSM)"):]
    header = f"| file | {' | '.join(MODELS)} |"
    if header not in section:
        sys.exit(f"docs/reproduce.md: the UTFSM table's header is not '{header}'")
    rows, mean = {}, None
    for line in section[section.index(header):].splitlines()[2:]:
        if not line.startswith("|"):
            break
        cells = [c.strip().strip("*") for c in line.strip("|").split("|")]  # a † stays: errors.csv writes it too
        if cells[0] == "mean":
            mean = cells[1:]
        else:
            rows[cells[0]] = cells[1:]
    return rows, mean


def sampled_run(exe, root, work, data):
    """The preset's per-file split on SAMPLE: {file: [nrmse text per MODELS]} as errors.csv writes it."""
    records = work / "records"
    records.mkdir(parents=True)
    for name in SAMPLE:
        (records / f"{name}.txt").symlink_to(data / "utfsm-mr-damper" / f"{name}.txt")
    preset = (root / "datasets" / "presets" / "utfsm.toml").read_text()
    blocks = re.split(r"\n(?=\[\[)", preset.replace("@shared/utfsm-mr-damper/", f"{records}/"))
    dropped = lambda b: (b.startswith("[[models]]") and "laws" in b) or \
        (b.startswith(("[[splits]]", "[[tables]]")) and "\"current\"" in b)
    (work / "utfsm_sample.toml").write_text("\n".join(b for b in blocks if not dropped(b)))
    # At the avx2 level wherever the CPU has it (every CPU CI runs on): the same instructions, so the same bits, on a
    # CPU with AVX-512 or without; the table's cells are the same at avx512, avx2 and sse2 on these files.
    env = dict(os.environ)
    levels = subprocess.run([exe, "--version"], capture_output=True, text=True).stdout
    if re.search(r"\(of [^)]*\bavx2\b", levels):  # "vector kernels avx512 (of sse2, avx2, avx512)"
        env["DAMPBENCH_ISA"] = "avx2"
    run = subprocess.run([exe, "run", work / "utfsm_sample.toml", "-o", work / "out", "--quiet", "--no-report",
                          "--threads", "1"], env=env, capture_output=True, text=True)
    if run.returncode:
        sys.exit(f"the sampled utfsm preset failed:\n{run.stderr}")
    with open(work / "out" / "errors.csv") as f:
        table = list(csv.reader(f))
    columns = [next(i for i, h in enumerate(table[0]) if h.startswith(m + " ")) for m in MODELS]
    return {row[0]: [row[i] for i in columns] for row in table[1:] if row[0] != "mean"}


def main():
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    exe, root, work, data = sys.argv[1], *(pathlib.Path(a) for a in sys.argv[2:5])
    if not (data / "utfsm-mr-damper").is_dir():
        print(f"skipped: the UTFSM records are absent ({data / 'utfsm-mr-damper'}); CI has them beside the repository")
        return 77
    shutil.rmtree(work, ignore_errors=True)
    rows, mean = docs_table(root / "docs" / "reproduce.md")
    failures = []
    if len(rows) != 30 or mean is None:
        failures.append(f"the table has {len(rows)} files (30 expected) and {'a' if mean else 'no'} mean row")
    for name, ours in sampled_run(exe, root, work, data).items():
        for model, docs, value in zip(MODELS, rows.get(name, ["-"] * 4), ours):
            if docs != value:
                failures.append(f"{name} {model}: docs/reproduce.md {docs}, the preset writes {value}")
    values = {m: [float(r[i].rstrip("†")) for r in rows.values()] for i, m in enumerate(MODELS)}
    for i, model in enumerate(MODELS):
        if mean and f"{sum(values[model]) / len(values[model]):.4f}" != mean[i]:
            failures.append(f"{model}: mean row {mean[i]}, the rows' mean {sum(values[model]) / len(values[model]):.6f}")
    for name, r in rows.items():
        spencer, bouc_wen, bingham = (float(r[MODELS.index(m)].rstrip("†"))
                                      for m in ("mrd.spencer", "mrd.bouc_wen", "mrd.bingham"))
        if not spencer <= bouc_wen <= bingham:
            failures.append(f"{name}: Spencer <= Bouc-Wen <= Bingham does not hold ({spencer}, {bouc_wen}, {bingham})")
    readme = (root / "README.md").read_text()
    bullet = readme[readme.index("**Real MR-damper data**"):]
    bullet = bullet[:bullet.index("\n- ")]
    for model, label in README_NAMES.items():
        wanted = f"{label} {sum(values[model]) / len(values[model]):.3f}"
        if wanted not in bullet:
            failures.append(f"README's Real MR-damper data bullet lacks '{wanted}'")
    for f in failures:
        print("FAIL:", f)
    print(f"{len(SAMPLE)} files x {len(MODELS)} models checked against docs/reproduce.md; {len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
