"""The README's install step: `cmake --install build --component python --prefix P` gives a package that a
fresh interpreter imports from P (a venv's or a user's prefix; the default /usr/local is Debian's python3 path)."""
import os
import subprocess
import sys

import pytest


def test_install_into_a_prefix_then_import(tmp_path):
    build = os.environ.get("DAMPBENCH_BUILD_DIR")
    cmake = os.environ.get("CMAKE_COMMAND", "cmake")
    if not build:
        pytest.skip("DAMPBENCH_BUILD_DIR is not set (run through ctest)")
    prefix = tmp_path / "prefix"
    done = subprocess.run([cmake, "--install", build, "--component", "python", "--prefix", str(prefix)],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stdout + done.stderr
    site = prefix / "lib" / f"python{sys.version_info.major}.{sys.version_info.minor}" / "site-packages"
    assert (site / "dampbench" / "__init__.py").is_file()
    # A clean environment: no PYTHONPATH to the build tree, run from a folder without the sources.
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["PYTHONPATH"] = str(site)
    check = ("import dampbench; assert dampbench.__file__.startswith(%r), dampbench.__file__; "
             "print(dampbench.version)" % str(site))
    done = subprocess.run([sys.executable, "-c", check], cwd=tmp_path, env=env, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == __import__("dampbench").version
