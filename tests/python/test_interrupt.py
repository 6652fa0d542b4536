"""Ctrl-C during a long fit: the engine stops at its next generation and the fit raises KeyboardInterrupt; the
process stays usable (a fit after it gives the same bits as one in a fresh process)."""
import signal
import subprocess
import sys
import textwrap

from conftest import FVD_RECORD

SCRIPT = textwrap.dedent(f"""
    import sys
    import dampbench
    record = dampbench.load_record({str(FVD_RECORD)!r})
    print("fitting", flush=True)
    try:
        # Hours of work uninterrupted: 4 runs of 5000 x 100000 evaluations.
        dampbench.fit("fvd.gv_quadratic_elastic", record, optimizer="de", pop=5000, iters=100000, runs=4)
        print("finished", flush=True)
    except KeyboardInterrupt:
        print("interrupted", flush=True)
    after = dampbench.fit("fvd.gv_linear_elastic", record, runs=3, seed=5)
    print(repr(after.params), flush=True)
""")


def test_ctrl_c_stops_a_fit_with_keyboard_interrupt():
    child = subprocess.Popen([sys.executable, "-c", SCRIPT], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert child.stdout.readline().strip() == "fitting"
        # Let the fit start its generations, then interrupt it as a terminal's Ctrl-C does.
        try:
            child.wait(timeout=2)
        except subprocess.TimeoutExpired:
            pass
        child.send_signal(signal.SIGINT)
        out, err = child.communicate(timeout=120)
    finally:
        if child.poll() is None:
            child.kill()
    lines = out.splitlines()
    assert child.returncode == 0, err
    assert lines[0] == "interrupted", out + err
    import dampbench
    fresh = dampbench.fit("fvd.gv_linear_elastic", str(FVD_RECORD), runs=3, seed=5)
    assert lines[1] == repr(fresh.params)
