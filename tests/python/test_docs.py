"""docs/python.md's session runs: its Python blocks, in order, as one script in a scratch folder laid out as the
page assumes (the repository's datasets, ../shared/data beside it, the fvd preset's store in results/fvd)."""
import os
import re
import subprocess
import sys

from conftest import SOURCE_DIR, run_cli


def test_the_pages_python_blocks_run(exe, shared_data, tmp_path):
    text = (SOURCE_DIR / "docs" / "python.md").read_text(encoding="utf-8")
    blocks = re.findall(r"^```python\n(.*?)^```", text, flags=re.S | re.M)
    assert len(blocks) >= 3, "docs/python.md lost its Python blocks"
    repo = tmp_path / "repo"
    repo.mkdir()
    (repo / "datasets").symlink_to(SOURCE_DIR / "datasets")
    (tmp_path / "shared").mkdir()
    (tmp_path / "shared" / "data").symlink_to(shared_data)
    code, _, err = run_cli(exe, "run", SOURCE_DIR / "datasets" / "presets" / "fvd.toml", "-o", repo / "results" / "fvd")
    assert code == 0, err
    env = dict(os.environ, MPLBACKEND="Agg")
    done = subprocess.run([sys.executable, "-c", "\n".join(blocks)], cwd=repo, env=env, capture_output=True, text=True)
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]
    assert (repo / "spencer_loop.png").stat().st_size > 10_000
