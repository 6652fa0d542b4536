#!/usr/bin/python3
"""The papers' numbers in datasets/papers/*.toml are the ones the papers print.

Every number of every [[tables]] row and [[laws]] coefficient of each paper file must occur in the text of the paper the file's `source`
names (`seed <id>`, the file <id>.txt of SEEDS_DIR): as a decimal ("1.270", "-0.334"), as a mantissa times a power
of ten ("2.065 \\times 10^{-3}", "6.079×10^3") or as a term of a parenthesized sum times a power of ten
("(1.870 + 2.240I) \\times 10^3" holds 1870 and 2240), or with a decimal comma ("5,703381", "2,03E+00": a comma
between digits is read both ways, as the fvd paper's Tables 11-14 print their decimals), or with the decimal colon of a
value after "=" ("c = 16:48": the lssvm paper's text renders its decimal point so). Equal within 1e-9 relative, so a transcription that drops a
digit, a sign of an exponent or a row fails here. Signs are not compared (a printed "−" may be a dash of the table's
layout); a row label, a scale (`scale = 0.01` for a paper's %) and comments are not numbers of the paper.

usage: paper_transcriptions_test.py REPO_ROOT SEEDS_DIR
Exit 77 (ctest: skipped) when SEEDS_DIR is absent (a clone without ../shared).
"""
import pathlib
import re
import sys
import tomllib

POWER = r"\s*×\s*10\^\{?\s*([+\-]?\d+)\s*\}?"
DECIMAL = r"\d+(?:\.\d+)?"


def printed_numbers(text):
    """Absolute values of the numbers the text prints, in the forms the module's docstring lists."""
    t = text.replace("−", "-").replace("\\times", "×").replace("\\cdot", "×")
    found = [float(m.group(0)) for m in re.finditer(rf"(?<![\w.]){DECIMAL}(?:[eE][+\-]?\d+)?", t)]
    for m in re.finditer(r"(?<![\w.,])(\d+),(\d+)([eE][+\-]?\d+)?", t):
        found.append(float(f"{m.group(1)}.{m.group(2)}{m.group(3) or ''}"))
    for m in re.finditer(r"=\s*(\d+):(\d+)(?![\d:])", t):
        found.append(float(f"{m.group(1)}.{m.group(2)}"))
    for m in re.finditer(rf"({DECIMAL}){POWER}", t):
        found.append(float(m.group(1)) * 10 ** int(m.group(2)))
    for m in re.finditer(rf"\(([^()]*)\){POWER}", t):
        found += [float(x) * 10 ** int(m.group(2)) for x in re.findall(rf"(?<![\w.]){DECIMAL}", m.group(1))]
    return found


def transcribed(paper_file):
    """(table, row label, value) of every number of the file's [[tables]] rows, and the seed id of its source."""
    data = tomllib.loads(paper_file.read_text())
    seed = re.search(r"seed (\w+)", data.get("source", ""))
    if not seed:
        sys.exit(f"{paper_file}: source names no seed ('seed <id>, Tables ...')")
    numbers = [(t["table"], row[0], value) for t in data.get("tables", []) for row in t["rows"] for value in row[1:]]
    numbers += [(law["table"], name, value) for law in data.get("laws", []) for name, value in law["coefficients"]]
    return seed.group(1), numbers


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    root, seeds = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
    if not seeds.is_dir():
        print(f"skipped: no papers' texts at {seeds} (../shared/seeds beside the repository)")
        sys.exit(77)
    failures, checked = [], 0
    for paper_file in sorted((root / "datasets" / "papers").glob("*.toml")):
        seed, numbers = transcribed(paper_file)
        text_file = seeds / f"{seed}.txt"
        if not text_file.exists():
            failures.append(f"{paper_file.name}: its source {seed} has no text at {text_file}")
            continue
        printed = printed_numbers(text_file.read_text())
        for table, row, value in numbers:
            checked += 1
            if not any(abs(abs(value) - p) <= 1e-9 * max(1.0, abs(value)) for p in printed):
                failures.append(f"{paper_file.name}, {table}, row '{row}': {value:g} is not printed in {seed}.txt")
        if not numbers:
            failures.append(f"{paper_file.name}: no [[tables]] numbers to check")
    for f in failures:
        print("FAIL:", f)
    if failures or checked == 0:
        sys.exit(1)
    print(f"{checked} transcribed numbers of the papers' tables found in their texts")


if __name__ == "__main__":
    main()
