#!/usr/bin/python3
"""The README's commands run, so the front door cannot rot.

Every command in a fenced code block of README.md is run, in the order shown, against the built binary:

  - `./build/dampbench ...` runs as written (through bash, so quoting, globs and `$VAR` work) in a fresh
    folder WORK_DIR/repo that holds `build/dampbench` (a link to the binary under test) and `datasets/` (a link
    to the repository's). No budget flags are appended: the README shows each command in a form cheap enough
    to run here, and a command that takes longer than TIMEOUT_S fails.
  - `NAME=value` lines set a shell variable for the rest of their block.
  - The set-up commands (`bash scripts/fvd.sh`, `bash scripts/test.sh`, with `DAMPBENCH_QUICK=1` or not, and
    `cmake --install build --component python`) are not run: they install packages, build and install, and this
    test runs under the build they make.
  - A ```python block runs as one script under /usr/bin/python3 in the same folder, with the build's Python
    package (the folder `python` beside the binary) on PYTHONPATH; without it (a build without the module) the
    block is skipped with a message.
  - Anything else is an unknown command and fails the test, so a new kind of README command needs a rule here.

`../shared/data` in a command is the real data beside the repository: WORK_DIR/shared/data links to DATA_DIR
($DAMPBENCH_SHARED_DATA_DIR, else the argument, else REPO/../shared/data, as the binary finds it). When DATA_DIR is absent, commands that
read it are skipped with a message and the others still run.

A command fails the test when it exits non-zero, or when a file it names with -o/--report is missing or empty
afterwards. The test also fails when README.md is over 200 lines, when it shows a command outside a fenced
block (where this test would not see it), and when a relative link in README.md or docs/*.md points to a
file or heading that does not exist.

usage: readme_examples_test.py DAMPBENCH REPO_ROOT WORK_DIR [DATA_DIR]
"""
import os
import re
import shlex
import shutil
import subprocess
import sys
import time

TIMEOUT_S = 300          # per command; the README's commands take seconds in a release build
MAX_README_LINES = 200
MIN_COMMANDS = 5         # the README shows five examples: fewer run commands means the parser lost some

SETUP = re.compile(r"^((DAMPBENCH_QUICK=1\s+)?bash scripts/(fvd|test)\.sh|cmake --install build --component python)(\s|$)")
ASSIGNMENT = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*=\S*$")
DAMPBENCH_CMD = re.compile(r"^\./build/dampbench(\s|$)")
SHARED_DATA = "../shared/data"

failures = []


def fail(message):
    failures.append(message)
    print("FAIL:", message, flush=True)


def fenced_blocks(lines):
    """(first line number, language, [lines]) of each fenced code block; also the lines outside any fence."""
    blocks, outside, current, start, language = [], [], None, 0, ""
    for number, line in enumerate(lines, 1):
        if line.lstrip().startswith("```"):
            if current is None:
                current, start, language = [], number, line.strip()[3:].strip()
            else:
                blocks.append((start, language, current))
                current = None
        elif current is not None:
            current.append(line)
        else:
            outside.append((number, line))
    if current is not None:
        fail(f"README.md:{start}: a code block is never closed")
    return blocks, outside


def commands(block):
    """The block's commands: continuation lines joined, blank and comment-only lines dropped."""
    result, pending = [], ""
    for line in block:
        if line.rstrip().endswith("\\"):
            pending += line.rstrip()[:-1] + " "
            continue
        text = (pending + line).strip()
        pending = ""
        if text and not text.startswith("#"):
            result.append(text)
    if pending.strip():
        result.append(pending.strip())
    return result


def named_outputs(command):
    """Files a command says it writes (-o FILE, --report FILE); [] when the command cannot be split."""
    try:
        words = shlex.split(command, comments=True)
    except ValueError:
        return []
    return [words[i + 1] for i, w in enumerate(words[:-1]) if w in ("-o", "--report")]


def github_anchor(heading):
    """The anchor GitHub gives a Markdown heading."""
    text = heading.strip().lower()
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def check_links(repo):
    """Relative links of README.md and docs/*.md point to existing files and headings."""
    pages = [os.path.join(repo, "README.md")]
    docs = os.path.join(repo, "docs")
    pages += sorted(os.path.join(docs, f) for f in os.listdir(docs) if f.endswith(".md"))
    anchors = {}

    def anchors_of(path):
        if path not in anchors:
            found, fence = set(), False
            with open(path, encoding="utf-8") as f:
                for line in f:
                    if line.lstrip().startswith("```"):
                        fence = not fence
                    elif not fence and line.startswith("#"):
                        found.add(github_anchor(line.lstrip("#")))
            anchors[path] = found
        return anchors[path]

    checked = 0
    for page in pages:
        with open(page, encoding="utf-8") as f:
            text = re.sub(r"```.*?```", "", f.read(), flags=re.S)
        for target in re.findall(r"\]\(([^)\s]+)\)", text):
            if re.match(r"^[a-z]+:", target):
                continue
            path, _, anchor = target.partition("#")
            resolved = os.path.normpath(os.path.join(os.path.dirname(page), path)) if path else page
            where = os.path.relpath(page, repo)
            checked += 1
            if not os.path.exists(resolved):
                fail(f"{where}: link '{target}': no file {os.path.relpath(resolved, repo)}")
            elif anchor and resolved.endswith(".md") and anchor not in anchors_of(resolved):
                fail(f"{where}: link '{target}': no heading with anchor #{anchor} in {os.path.relpath(resolved, repo)}")
    print(f"links: {checked} relative links checked in {len(pages)} pages")


def prepare(work, dampbench, repo, data_dir):
    if os.path.exists(work):
        shutil.rmtree(work)
    root = os.path.join(work, "repo")
    os.makedirs(os.path.join(root, "build"))
    os.symlink(dampbench, os.path.join(root, "build", "dampbench"))
    os.symlink(os.path.join(repo, "datasets"), os.path.join(root, "datasets"))
    if os.path.isdir(data_dir):
        os.makedirs(os.path.join(work, "shared"))
        os.symlink(data_dir, os.path.join(work, "shared", "data"))
    return root


def run_command(command, variables, root, env):
    script = "set -o pipefail\n" + "".join(v + "\n" for v in variables) + command + "\n"
    began = time.monotonic()
    try:
        p = subprocess.run(["bash", "-c", script], cwd=root, env=env, capture_output=True, text=True,
                           timeout=TIMEOUT_S)
    except subprocess.TimeoutExpired:
        fail(f"over {TIMEOUT_S} s: {command}")
        return
    seconds = time.monotonic() - began
    if p.returncode != 0:
        fail(f"exit {p.returncode} after {seconds:.1f} s: {command}\n--- stdout (end)\n{p.stdout[-2000:]}"
             f"\n--- stderr (end)\n{p.stderr[-2000:]}")
        return
    for out in named_outputs(command):
        path = os.path.join(root, out)
        if not os.path.exists(path) or (os.path.isfile(path) and os.path.getsize(path) == 0):
            fail(f"'{out}' missing or empty after: {command}")
    print(f"ok ({seconds:.1f} s): {command}", flush=True)


def run_python(start, block, root, env, package_dir):
    """A ```python block as one script; False when it failed."""
    if not os.path.isdir(package_dir):
        print(f"SKIP (no Python module at {package_dir}: a build without it): the Python block at line {start}")
        return False
    began = time.monotonic()
    script = "\n".join(block) + "\n"
    python_env = dict(env, PYTHONPATH=package_dir, MPLBACKEND="Agg")
    try:
        p = subprocess.run(["/usr/bin/python3", "-c", script], cwd=root, env=python_env, capture_output=True,
                           text=True, timeout=TIMEOUT_S)
    except subprocess.TimeoutExpired:
        fail(f"over {TIMEOUT_S} s: the Python block at README.md:{start}")
        return False
    if p.returncode != 0:
        fail(f"exit {p.returncode}: the Python block at README.md:{start}\n--- stderr (end)\n{p.stderr[-2000:]}")
        return False
    print(f"ok ({time.monotonic() - began:.1f} s): the Python block at README.md:{start}", flush=True)
    return True


def main():
    if len(sys.argv) not in (4, 5):
        sys.exit(__doc__)
    dampbench, repo, work = (os.path.abspath(a) for a in sys.argv[1:4])
    data_dir = os.environ.get("DAMPBENCH_SHARED_DATA_DIR") or (
        sys.argv[4] if len(sys.argv) == 5 else os.path.join(repo, "..", "shared", "data"))
    data_dir = os.path.abspath(data_dir)

    with open(os.path.join(repo, "README.md"), encoding="utf-8") as f:
        lines = f.read().splitlines()
    if len(lines) > MAX_README_LINES:
        fail(f"README.md has {len(lines)} lines (at most {MAX_README_LINES}): move the detail to docs/")
    blocks, outside = fenced_blocks(lines)
    for number, line in outside:
        if re.match(r"^\s{4,}(\./build/dampbench|bash |dampbench |mpirun )", line):
            fail(f"README.md:{number}: a command outside a fenced code block (this test would not run it): "
                 f"{line.strip()}")
    check_links(repo)

    root = prepare(work, dampbench, repo, data_dir)
    env = dict(os.environ, DAMPBENCH_GENERATED_DIR=os.path.join(work, "generated"))
    have_data = os.path.isdir(data_dir)
    if not have_data:
        print(f"SKIP note: no real data at {data_dir}: the commands that read {SHARED_DATA} are skipped")
    ran = 0
    package_dir = os.path.join(os.path.dirname(os.path.realpath(dampbench)), "python")
    for start, language, block in blocks:
        if language == "python":
            ran += run_python(start, block, root, env, package_dir)
            continue
        variables = []
        for command in commands(block):
            if SETUP.match(command):
                print(f"not run (set-up: installs packages and builds; ctest runs under that build): {command}")
            elif ASSIGNMENT.match(command):
                variables.append(command)
            elif DAMPBENCH_CMD.match(command):
                uses_data = SHARED_DATA in command or any(SHARED_DATA in v for v in variables)
                if uses_data and not have_data:
                    print(f"SKIP (real data absent at {data_dir}): {command}")
                    continue
                run_command(command, variables, root, env)
                ran += 1
            else:
                fail(f"README.md block at line {start}: unknown command (no rule in this test): {command}")
    if ran < MIN_COMMANDS and have_data:
        fail(f"only {ran} README commands ran (at least {MIN_COMMANDS} expected): did the code blocks change form?")
    print(f"{ran} README commands run")
    if failures:
        print(f"{len(failures)} failure(s)")
        sys.exit(1)
    print("all README commands ran")


if __name__ == "__main__":
    main()
