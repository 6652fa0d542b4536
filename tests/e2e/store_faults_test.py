#!/usr/bin/python3
"""The results store under faults. For each fault: a clear `dampbench: error:` message and its exit
code, no finished task group lost, and a later run that resumes to the same bits as an uninterrupted run.

  - a store in use by another `dampbench run` (lock): refused at once (exit 4), the first run unharmed;
  - SIGTERM and SIGINT mid-run: groups in flight finish and are stored, exit 130; resumed;
  - a full disk (the file-size limit RLIMIT_FSIZE, as a full disk looks to a process: writes fail with EFBIG):
    exit 4 with SQLite's message, the groups committed before stay; resumed without the limit;
  - a read-only output folder (a read-only tmpfs where mounting is allowed, else a mode-555 folder when not
    root, else skipped with a message): exit 4 naming the folder;
  - a truncated and a corrupted store: `table`, `report` and `run` refuse it (exit 4) without crashing;
    `run --fresh` starts over and ends bit-identical.

usage: store_faults_test.py DAMPBENCH WORK_DIR
"""
import os
import resource
import shutil
import signal
import subprocess
import sys
import time

from store_test_support import GROUPS, contents, differences, stored_groups, write_sweep

DAMPBENCH, WORK = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
failures = []


def check(ok, message):
    if not ok:
        failures.append(message)
        print("FAIL:", message)


def run(out, *extra, limit_bytes=None):
    """`dampbench run` of the small sweep into `out` (store out/store.sqlite); returns the finished process."""
    def limited():
        if limit_bytes is not None:
            signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # a write past the limit fails with EFBIG instead
            resource.setrlimit(resource.RLIMIT_FSIZE, (limit_bytes, limit_bytes))
    return subprocess.run([DAMPBENCH, "run", SPEC, "-o", out, "--quiet", "--no-report", "--threads", "2", *extra],
                          capture_output=True, text=True, preexec_fn=limited, timeout=600)


def start(out):
    return subprocess.Popen([DAMPBENCH, "run", SPEC, "-o", out, "--quiet", "--no-report", "--threads", "2"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def wait_for_groups(store, n, timeout_s=60):
    end = time.monotonic() + timeout_s
    while time.monotonic() < end:
        if stored_groups(store) >= n:
            return True
        time.sleep(0.01)
    return False


def expect_error(p, code, words, what):
    check(p.returncode == code and p.stderr.startswith("dampbench: error:") and words in p.stderr,
          f"{what}: exit {p.returncode} (expected {code}), stderr {p.stderr.strip()!r} (expected '{words}')")


def same_as_reference(out, what):
    diff = differences(REFERENCE, contents(os.path.join(out, "store.sqlite")))
    check(not diff, f"{what}: the resumed store differs from the uninterrupted one: {diff}")


def lock():
    out = os.path.join(WORK, "lock")
    first = start(out)
    check(wait_for_groups(os.path.join(out, "store.sqlite"), 1), "lock: the first run stored nothing")
    # Stopped, the first run keeps its lock and cannot finish before the others try: a sweep of about a second
    # would otherwise race them on a loaded machine.
    first.send_signal(signal.SIGSTOP)
    try:
        second = run(out)
        expect_error(second, 4, "is in use by another dampbench run", "a second run on the same store")
        fresh = run(out, "--fresh")
        expect_error(fresh, 4, "is in use by another dampbench run", "a second run with --fresh on the same store")
    finally:
        first.send_signal(signal.SIGCONT)
    first.communicate()
    check(first.returncode == 0, f"lock: the first run ended with {first.returncode}")
    same_as_reference(out, "lock")


def stop_signal(sig, name):
    out = os.path.join(WORK, name)
    p = start(out)
    check(wait_for_groups(os.path.join(out, "store.sqlite"), 2), f"{name}: nothing stored before the signal")
    p.send_signal(sig)
    _, err = p.communicate()
    stored = stored_groups(os.path.join(out, "store.sqlite"))
    check(p.returncode == 130 and "interrupted" in err, f"{name}: exit {p.returncode}, stderr {err.strip()!r}")
    check(2 <= stored < GROUPS, f"{name}: {stored} of {GROUPS} groups stored after the signal")
    again = run(out)
    check(again.returncode == 0, f"{name}: the resumed run failed: {again.stderr}")
    same_as_reference(out, name)


def full_disk():
    out = os.path.join(WORK, "full")
    p = run(out, limit_bytes=150_000)
    stored = stored_groups(os.path.join(out, "store.sqlite"))
    expect_error(p, 4, "store", "a full disk")
    check("full" in p.stderr or "I/O error" in p.stderr, f"a full disk: SQLite's reason is missing: {p.stderr.strip()!r}")
    check(0 < stored < GROUPS, f"full disk: {stored} groups stored before the disk filled (expected some, not all)")
    again = run(out)
    check(again.returncode == 0, f"full disk: the resumed run failed: {again.stderr}")
    same_as_reference(out, "full disk")


def read_only():
    folder = os.path.join(WORK, "ro")
    os.makedirs(folder)
    mounted = subprocess.run(["mount", "-t", "tmpfs", "-o", "ro,size=1m", "tmpfs", folder], capture_output=True).returncode == 0
    if not mounted:
        if os.geteuid() == 0:
            print("SKIP read-only folder: cannot mount a tmpfs here and root ignores folder modes")
            return
        os.chmod(folder, 0o555)
    try:
        p = run(os.path.join(folder, "out"))
        check(p.returncode == 4 and p.stderr.startswith("dampbench: error:") and
              ("Read-only" in p.stderr or "Permission denied" in p.stderr),
              f"read-only folder: exit {p.returncode}, stderr {p.stderr.strip()!r}")
    finally:
        if mounted:
            subprocess.run(["umount", folder])
        else:
            os.chmod(folder, 0o755)


def damaged_store(kind):
    out = os.path.join(WORK, kind)
    shutil.copytree(os.path.join(WORK, "reference"), out)
    store = os.path.join(out, "store.sqlite")
    size = os.path.getsize(store)
    with open(store, "r+b") as f:
        if kind == "truncated":
            f.truncate(size // 2)
        else:  # corrupted: garbage over the middle pages, the header intact
            f.seek(size // 3)
            f.write(bytes((i * 37 + 11) % 256 for i in range(size // 3)))
    for args in (["table", store, "--kind", "runs"], ["report", store, "-o", os.path.join(out, "r.html")]):
        p = subprocess.run([DAMPBENCH, *args], capture_output=True, text=True)
        expect_error(p, 4, "store", f"{kind} store, {args[0]}")
        check(not os.path.exists(os.path.join(out, "r.html")), f"{kind} store: a report file was written")
    p = run(out)
    expect_error(p, 4, "store", f"{kind} store, run")
    p = run(out, "--fresh")
    check(p.returncode == 0, f"{kind} store: run --fresh failed: {p.stderr}")
    same_as_reference(out, f"{kind} store after --fresh")


def main():
    global SPEC, REFERENCE
    shutil.rmtree(WORK, ignore_errors=True)
    os.makedirs(WORK)
    SPEC = write_sweep(WORK)
    reference = run(os.path.join(WORK, "reference"))
    if reference.returncode != 0:
        sys.exit(f"the reference run failed: {reference.stderr}")
    REFERENCE = contents(os.path.join(WORK, "reference", "store.sqlite"))
    lock()
    stop_signal(signal.SIGTERM, "sigterm")
    stop_signal(signal.SIGINT, "sigint")
    full_disk()
    read_only()
    damaged_store("truncated")
    damaged_store("corrupted")
    print(f"{len(failures)} failures" if failures else "OK: lock, SIGTERM, SIGINT, full disk, read-only folder, "
          "truncated and corrupted stores")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
