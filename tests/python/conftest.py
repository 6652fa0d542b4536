"""What the Python module's tests share: the command line of the same build, the shared data folder, a scratch
folder, and running the command line for its JSON."""
import json
import os
import subprocess
from pathlib import Path

import pytest

SOURCE_DIR = Path(os.environ.get("DAMPBENCH_SOURCE_DIR", Path(__file__).resolve().parents[2]))
FVD_RECORD = SOURCE_DIR / "datasets" / "fvd" / "test3_20mm_460mms.csv"


@pytest.fixture
def exe():
    """This build's dampbench executable (ctest sets DAMPBENCH_EXE)."""
    path = os.environ.get("DAMPBENCH_EXE")
    if not path:
        pytest.skip("DAMPBENCH_EXE is not set (run through ctest)")
    return path


@pytest.fixture
def shared_data():
    """../shared/data: the real MR-damper records; the test skips with a message when it is absent."""
    path = Path(os.environ.get("DAMPBENCH_SHARED_DATA_DIR", SOURCE_DIR.parent / "shared" / "data"))
    if not (path / "utfsm-mr-damper").is_dir():
        pytest.skip(f"no shared data at {path} (set DAMPBENCH_SHARED_DATA_DIR): real-data tests skipped")
    return path


def run_cli(exe, *args):
    """Runs `dampbench ARGS`; returns (exit code, stdout, stderr)."""
    done = subprocess.run([exe, *map(str, args)], capture_output=True, text=True)
    return done.returncode, done.stdout, done.stderr


def cli_json(exe, *args):
    """`dampbench ARGS --format json`, parsed; fails the test with the command's stderr if it fails."""
    code, out, err = run_cli(exe, *args, "--format", "json")
    assert code == 0, f"dampbench {' '.join(map(str, args))} exited {code}: {err}"
    return json.loads(out)
