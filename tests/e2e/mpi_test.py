"""Sweeps under MPI and as shards, end to end through the dampbench executable.

Compared with `dampbench run` in one process (2 threads), bit for bit (every stored number, read with SQLite
itself, and every table file):
  - `mpirun -np 1/2/3 dampbench run` of the fvd preset and of a mixed sweep (an algebraic model per current with
    PSO and DE, Bouc-Wen (ODE) per current, a current-dependent Bingham law fitted at 0 and 1 A predicting 0.5 A,
    a regression of f_c on I, a sensitivity study) on records made by `dampbench simulate`;
  - three shards (`run --shard i/3`) merged by `dampbench merge`, and `verify` of the merged store;
  - an MPI job killed with SIGKILL (the whole process group) mid-way, resumed by another mpirun;
  - an MPI job whose worker rank is killed mid-way: the job ends with an error, the store stays valid, and a
    single-process run resumes it.
  - shard 2/3 run under `mpirun -np 3`.
Merging parts of two different sweeps is refused with exit code 2 and a message naming the part; ranks that run
another sweep file than rank 0 (an MPMD launch) are refused with both fingerprints.

usage: mpi_test.py DAMPBENCH WORK_DIR
Exit 77 (ctest: skipped) when mpirun is missing or dampbench was built without MPI; scripts/install-deps.sh
installs OpenMPI, so CI runs it. Ranks are oversubscribed on one machine (--oversubscribe); as root, OpenMPI
needs OMPI_ALLOW_RUN_AS_ROOT (set here).
"""
import fcntl
import glob
import os
import shutil
import signal
import sqlite3
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import store_test_support as support  # noqa: E402

DAMPBENCH, WORK = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
MPIRUN = shutil.which("mpirun")
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OMPI_MCA_btl_vader_single_copy_mechanism="none")
FVD = os.path.join(support.ROOT, "datasets", "presets", "fvd.toml")


def relocated(preset_text):
    """The fvd preset's text with its relative paths (records, the paper's numbers) made absolute, for a copy."""
    return (preset_text.replace('file = "../fvd/', f'file = "{support.ROOT}/datasets/fvd/')
            .replace('published = "../papers/', f'published = "{support.ROOT}/datasets/papers/'))


failures = []


def check(ok, message):
    if not ok:
        failures.append(message)
        print("FAIL:", message, flush=True)


def run(args, ok=True, mpi=0, timeout=600):
    """dampbench ARGS, under `mpirun -np MPI` if given; a job that hangs is killed whole (its process group)."""
    cmd = ([MPIRUN, "--oversubscribe", "--bind-to", "none", "-np", str(mpi)] if mpi else []) + [DAMPBENCH, *args]
    proc = subprocess.Popen(cmd, cwd=WORK, env=ENV, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            start_new_session=True)
    try:
        out, err = proc.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.communicate()
        sys.exit(f"{' '.join(cmd)}: no end after {timeout} s (a deadlock?); killed")
    p = subprocess.CompletedProcess(cmd, proc.returncode, out, err)
    if ok and p.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed ({p.returncode}):\n{p.stdout}\n{p.stderr}")
    return p


def wait_unlocked(store, seconds=60):
    """Waits until no process holds the store's lock (ranks of a killed job may take a moment to go)."""
    deadline = time.time() + seconds
    with open(store + ".lock", "a") as f:
        while True:
            try:
                fcntl.flock(f, fcntl.LOCK_EX | fcntl.LOCK_NB)
                fcntl.flock(f, fcntl.LOCK_UN)
                return True
            except OSError:
                if time.time() > deadline:
                    return False
                time.sleep(0.1)


MIXED = support.current_sweep(
    "mixed", 3, each_split_extra='sensitivity = { points = 5, range = 0.5, objective = "rms", where = { I = 1 } }')


def make_mixed():
    support.write_current_records(DAMPBENCH, WORK)
    path = os.path.join(WORK, "mixed.toml")
    with open(path, "w") as f:
        f.write(MIXED)
    return path


def table_files(out):
    """{file name: bytes} of the tables `run` wrote (summary.md holds wall times and paths: left out)."""
    files = {}
    for p in sorted(glob.glob(os.path.join(WORK, out, "*"))):
        name = os.path.basename(p)
        if name.endswith((".csv", ".md")) and name != "summary.md":
            with open(p, "rb") as f:
                files[name] = f.read()
    return files


def same_as_single(label, store, single_store, out=None, single_out=None):
    diff = support.differences(support.contents(single_store), support.contents(store))
    check(not diff, f"{label}: stored numbers differ from one process: {diff}")
    if out:
        a, b = table_files(single_out), table_files(out)
        check(len(a) > 3 and a == b, f"{label}: tables differ from one process: "
              f"{sorted(k for k in set(a) | set(b) if a.get(k) != b.get(k))}")


def wait_for(store, n, proc, seconds=120):
    deadline = time.time() + seconds
    while time.time() < deadline and proc.poll() is None:
        if support.stored_groups(store) >= n:
            return True
        time.sleep(0.02)
    return False


def total_groups(store):
    db = sqlite3.connect(f"file:{store}?mode=ro", uri=True)
    n = int(db.execute("SELECT value FROM meta WHERE key='groups'").fetchone()[0])
    db.close()
    return n


def worker_pids(parent):
    """Processes of the job started by mpirun `parent` that are ranks > 0 (their OMPI_COMM_WORLD_RANK)."""
    pids = []
    for d in os.listdir("/proc"):
        if not d.isdigit():
            continue
        try:
            with open(f"/proc/{d}/environ", "rb") as f:
                env = dict(x.split(b"=", 1) for x in f.read().split(b"\0") if b"=" in x)
            with open(f"/proc/{d}/stat") as f:
                ppid = int(f.read().rsplit(")", 1)[1].split()[1])
        except (OSError, ValueError, IndexError):
            continue
        if ppid == parent and env.get(b"OMPI_COMM_WORLD_RANK", b"0") != b"0":
            pids.append(int(d))
    return pids


def main():
    if not MPIRUN:
        print("skipped: mpirun not found (scripts/install-deps.sh installs openmpi-bin)")
        return 77
    shutil.rmtree(WORK, ignore_errors=True)
    os.makedirs(WORK)
    version = run(["--version"]).stdout
    if "with MPI" not in version:
        print(f"skipped: this dampbench was built without MPI ({version.strip()})")
        return 77
    mixed = make_mixed()

    for name, spec in (("fvd", FVD), ("mixed", mixed)):
        single = f"{name}-single"
        run(["--threads", "2", "run", spec, "-o", single, "--quiet", "--no-report"])
        single_store = os.path.join(WORK, single, "store.sqlite")
        for ranks in (1, 2, 3):
            out = f"{name}-np{ranks}"
            p = run(["run", spec, "-o", out, "--quiet", "--no-report"], mpi=ranks)
            check(ranks == 1 or f"on {ranks} MPI ranks" in p.stdout, f"{out}: the summary does not name the ranks: {p.stdout}")
            same_as_single(f"{name}, mpirun -np {ranks}", os.path.join(WORK, out, "store.sqlite"), single_store, out, single)
            print(f"{name}: mpirun -np {ranks}: identical to one process", flush=True)

        # Shards of a job array, merged; then verify re-runs every merged group.
        parts = []
        for i in (1, 2, 3):
            parts.append(os.path.join(WORK, f"{name}-part{i}.sqlite"))
            run(["run", spec, "--shard", f"{i}/3", "--store", parts[-1], "--quiet"])
        merged = os.path.join(WORK, f"{name}-merged.sqlite")
        p = run(["merge", merged, *parts])
        check("0 found twice" in p.stdout and p.stderr == "", f"{name}: merge output: {p.stdout} {p.stderr}")
        same_as_single(f"{name}, 3 shards merged", merged, single_store)
        a = run(["table", single_store, "--kind", "sweep", "--format", "csv"]).stdout
        b = run(["table", merged, "--kind", "sweep", "--format", "csv"]).stdout
        check(a == b and len(a) > 100, f"{name}: tables of the merged store differ from one process")
        p = run(["verify", merged], ok=False)
        check(p.returncode == 0 and "identical bit for bit" in p.stdout, f"{name}: verify of the merged store: {p.stdout}")
        print(f"{name}: 3 shards merged: identical to one process, verify passes", flush=True)

    # Parts of different sweeps are not merged.
    p = run(["merge", "wrong.sqlite", os.path.join(WORK, "fvd-part1.sqlite"), os.path.join(WORK, "mixed-part2.sqlite")], ok=False)
    check(p.returncode == 2 and "another sweep spec" in p.stderr and "mixed-part2.sqlite" in p.stderr,
          f"merge of two sweeps: exit {p.returncode}, {p.stderr}")
    check(not os.path.exists(os.path.join(WORK, "wrong.sqlite")), "merge of two sweeps left a store")

    # A shard under mpirun: the same groups as that shard in one process.
    run(["run", FVD, "--shard", "2/3", "--store", "mpi-shard.sqlite", "--quiet"], mpi=3)
    diff = support.differences(support.contents(os.path.join(WORK, "fvd-part2.sqlite")),
                               support.contents(os.path.join(WORK, "mpi-shard.sqlite")))
    check(not diff, f"shard 2/3 on 3 ranks differs from shard 2/3 in one process: {diff}")

    # Ranks that would not compute the same thing (here: another sweep file on rank 1) are refused.
    other = os.path.join(WORK, "fvd-other-seed.toml")
    with open(FVD) as f, open(other, "w") as g:
        g.write(relocated(f.read().replace("seed = 1", "seed = 2")))
    cmd = [MPIRUN, "--oversubscribe", "-np", "1", DAMPBENCH, "run", FVD, "-o", "mixed-ranks", "--quiet", ":",
           "-np", "1", DAMPBENCH, "run", other, "-o", "mixed-ranks", "--quiet"]
    p = subprocess.run(cmd, cwd=WORK, capture_output=True, text=True, env=ENV, timeout=300)
    check(p.returncode != 0 and "is not running the same computation as rank 0" in p.stderr,
          f"ranks with different sweep files: exit {p.returncode}, {p.stderr[-800:]}")

    # The whole job killed with SIGKILL mid-way, resumed by another mpirun. The kills need groups that take a while:
    # the fvd preset with 4x the iterations (0.1-0.3 s a group on one thread), with its own one-process reference.
    slow = os.path.join(WORK, "fvd-slow.toml")
    with open(FVD) as f, open(slow, "w") as g:
        text = f.read()
        check("iterations = 100" in text, "the fvd preset no longer sets iterations = 100 (the kill tests slow it down)")
        g.write(relocated(text.replace("iterations = 100", "iterations = 400")))
    run(["run", slow, "-o", "fvd-slow-single", "--quiet", "--no-report"])
    single_store = os.path.join(WORK, "fvd-slow-single", "store.sqlite")
    store = os.path.join(WORK, "killed", "store.sqlite")
    # One thread per rank, so that groups finish one by one and the kill lands mid-way on any machine.
    cmd = [MPIRUN, "--oversubscribe", "-np", "3", DAMPBENCH, "--threads", "1", "run", slow, "-o", "killed", "--quiet",
           "--no-report"]
    proc = subprocess.Popen(cmd, cwd=WORK, env=ENV, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                            start_new_session=True)
    reached = wait_for(store, 3, proc)
    os.killpg(proc.pid, signal.SIGKILL)
    proc.wait()
    time.sleep(0.5)
    stored = support.stored_groups(store)
    check(reached and 3 <= stored < total_groups(store), f"kill -9 of the job: {stored} groups stored (expected some, not all)")
    check(wait_unlocked(store), "kill -9 of the job: a rank still holds the store's lock after 60 s")
    run(["run", slow, "-o", "killed", "--quiet", "--no-report"], mpi=2)
    same_as_single(f"job killed after {stored} groups, resumed on 2 ranks", store, single_store)
    print(f"fvd: job killed after {stored} groups and resumed: identical to one process", flush=True)

    # A worker rank killed mid-way: the job ends with an error and a valid store, which one process resumes.
    store = os.path.join(WORK, "worker-died", "store.sqlite")
    cmd = [MPIRUN, "--oversubscribe", "-np", "3", DAMPBENCH, "--threads", "1", "run", slow, "-o", "worker-died", "--quiet",
           "--no-report"]
    proc = subprocess.Popen(cmd, cwd=WORK, env=ENV, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            start_new_session=True)
    reached = wait_for(store, 2, proc)
    workers = worker_pids(proc.pid)
    check(reached and workers, f"worker death: no worker found to kill ({workers}) or no group stored")
    if workers:
        os.kill(workers[0], signal.SIGKILL)
    try:
        _, err = proc.communicate(timeout=120)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        _, err = proc.communicate()
        check(False, "worker death: the job did not end within 120 s")
    check(proc.returncode != 0, f"worker death: mpirun exited {proc.returncode}")
    check("noticed that process rank" in err and "signal 9" in err,
          f"worker death: no message names the lost rank: {err[-500:]}")
    stored = support.stored_groups(store)
    check(stored < total_groups(store), f"worker death: the job stored all {stored} groups (killed too late)")
    check(wait_unlocked(store), "worker death: a rank still holds the store's lock after 60 s")
    run(["run", slow, "-o", "worker-died", "--quiet", "--no-report"])
    same_as_single(f"worker killed after {stored} stored groups, resumed in one process", store, single_store)
    print(f"fvd: worker killed after {stored} groups; job ended with exit {proc.returncode}; resumed: identical", flush=True)

    if failures:
        print(f"{len(failures)} failure(s)")
        return 1
    print("mpi: every check passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
