#!/usr/bin/python3
"""The README's Results say what the papers' presets write.

The bullets of README.md's "## Results" that start with one of CHECKED's titles quote the verdicts of presets (and of
the lssvm command's runs) that the paper_claims_<preset> tests run (their reproduction.json in WORK_DIR/paper_claims_<preset>/<preset>/). Every
number in such a bullet must be one of those items' numbers at its printed precision (paper_claims_test.py's rule:
values, the paper's, their differences in %, the models' means, the numbers of an item's detail such as "6 of 7
rows"); numbers that name a condition (5 Hz, 25 mm), a table or an equation, or a test ("test 4") are not results.
A count "N of M" must be one an item's detail gives ("on N of M rows"), since small numbers
alone occur in many items. A figure the presets no longer give then fails here instead of going stale. The other bullets hold measurements
(times, speed ratios), are checked by their own tests (Real MR-damper data: utfsm_table_test.py; In a building:
ControlCli.ExamplesBuildingTableIsTheCommandsOutput) or come from runs too long for the test command (the
whole-damper fits, the Bouc–Wen benchmark's five seeds at full budget): docs/reproduce.md and docs/performance.md
give how each was measured.

ctest runs it after the paper_claims tests (FIXTURES_REQUIRED). Exit 77 (skipped) when a preset's output is absent
(the real-data presets skip without ../shared/data).

usage: readme_results_test.py REPO_ROOT WORK_DIR
"""
import json
import pathlib
import re
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import paper_claims_test as claims  # noqa: E402  (the same reading of a number and of an item's numbers)

# Bullet title → the presets whose verdicts it quotes.
CHECKED = {
    "fvd paper": ["fvd"],
    "The other papers' claims": ["crfd_neutral", "mfm_neutral", "fdsp_neutral", "mfm_utfsm", "fdsp_utfsm"],
    "LS-SVM": ["lssvm", "lssvm_utfsm"],
}
TEST_NAME = re.compile(r"[Tt]ests?\s*$")  # "test 4": a record's name


def results_bullets(readme):
    text = readme.read_text()
    begin = text.find("\n## Results\n")
    if begin < 0:
        sys.exit("README.md has no section '## Results'")
    end = text.find("\n## ", begin + 1)
    section = text[begin:end if end >= 0 else len(text)]
    return [b.strip() for b in re.split(r"\n- ", section)[1:]]


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    root, work = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
    bullets = results_bullets(root / "README.md")
    failures = []
    for title, presets in CHECKED.items():
        bullet = next((b for b in bullets if b.startswith(f"**{title}**")), None)
        if bullet is None:
            failures.append(f"README.md's Results have no bullet '**{title}**'")
            continue
        known, details = set(), []
        for preset in presets:
            report = work / f"paper_claims_{preset}" / preset / "reproduction.json"
            if not report.exists():
                print(f"skipped: no output of paper_claims_{preset} at {report}")
                sys.exit(77)
            for item in json.loads(report.read_text())["items"]:
                known |= claims.item_numbers(item)
                details.append(item["detail"])
        text = re.sub(r"\]\([^)]*\)", "]", bullet)  # links' targets are not figures
        missing = claims.unmatched_in(text, known, TEST_NAME)
        missing += [f"{n} of {m}" for n, m in re.findall(r"(\d+) of (\d+)", text)
                    if not any(f"{n} of {m} rows" in d for d in details)]
        if missing:
            failures.append(f"README.md, Results, '{title}': {', '.join(missing)} is in no verdict of "
                            f"{', '.join(presets)}")
    for f in failures:
        print("FAIL:", f)
    if failures:
        sys.exit(1)
    print(f"{len(CHECKED)} Results bullets' figures found in the presets' verdicts")


if __name__ == "__main__":
    main()
