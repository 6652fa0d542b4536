"""The files engineers have, written here by the test itself: MATLAB .mat records (v5 by scipy.io, v7.3 in the HDF5
layout MATLAB writes, by h5py), a rig's text export with a header block, volt channels, a date-time column, an
events column and five tests between DAQ Pause/Resume events, and the preprocessing such raw data needs. Each is
compared with the same data converted by hand (numpy) and written as CSV: the same records bit for bit, the same
metrics and fits."""
import json

import numpy as np
import pytest

import dampbench
from conftest import cli_json, run_cli

h5py = pytest.importorskip("h5py", reason="python3-h5py writes the v7.3 test file (scripts/install-deps.sh)")
scipy_io = pytest.importorskip("scipy.io", reason="python3-scipy writes the v5 test file (scripts/install-deps.sh)")

CURRENTS = [0.0, 0.25, 0.5, 0.75, 1.0]


def five_tests_in_si(seed=5):
    """Five 1 Hz tests at 200 Hz (x [m], F [N]) of different amplitude and force, noise on both."""
    rng = np.random.default_rng(seed)
    t = np.arange(0, 3.0, 0.005)
    out = []
    for i, current in enumerate(CURRENTS):
        x = (0.004 + 0.001 * i) * np.sin(2 * np.pi * t) + 1e-5 * rng.standard_normal(t.size)
        F = (300 + 900 * current) * np.tanh(2 * np.pi * np.cos(2 * np.pi * t) * 20) + 5 * rng.standard_normal(t.size)
        out.append((t, x, F))
    return out


def write_csv(path, t, x, F):
    with open(path, "w") as f:
        f.write("t,x,F\n")
        for row in zip(t, x, F):
            f.write(",".join(repr(float(v)) for v in row) + "\n")


def write_mat73(path, variables):
    """The HDF5 layout MATLAB writes for -v7.3: a 512-byte user block with MATLAB's header text, one dataset per
    variable, stored transposed (HDF5 is row-major, MATLAB column-major), with the attribute MATLAB_class."""
    with h5py.File(path, "w", userblock_size=512) as f:
        for name, value in variables.items():
            dataset = f.create_dataset(name, data=np.asarray(value, dtype=np.float64).T)
            # MATLAB's attribute: a null-terminated string of its own length (an h5py string attribute of another
            # padding reads back one character short in matio 1.5.23)
            tid = h5py.h5t.C_S1.copy()
            tid.set_size(6)
            tid.set_strpad(h5py.h5t.STR_NULLTERM)
            attribute = h5py.h5a.create(dataset.id, b"MATLAB_class", tid, h5py.h5s.create(h5py.h5s.SCALAR))
            attribute.write(np.array(b"double", dtype="S6"), mtype=tid)
    header = b"MATLAB 7.3 MAT-file, Platform: GLNXA64, Created on: Mon Jan  1 00:00:00 2024 HDF5 schema 1.00 ."
    with open(path, "r+b") as f:
        f.write(header.ljust(116, b" ") + b"\0" * 8 + b"\x00\x02" + b"IM")


def assert_same_records(a, b):
    assert len(a) == len(b)
    for ra, rb in zip(a, b):
        for column in "txvaF":
            assert np.array_equal(getattr(ra, column), getattr(rb, column)), (ra.name, column)
        assert ra.operating == rb.operating, ra.name


@pytest.mark.parametrize("version", ["v5", "v7.3"])
def test_mat_files_load_as_the_same_records_as_csv(exe, tmp_path, version):
    tests = five_tests_in_si()
    t = tests[0][0]
    data = np.column_stack([tests[0][1]] + [F for _, _, F in tests])  # x, then one force column per current
    csv = []
    for i, (_, _, F) in enumerate(tests):
        csv.append(tmp_path / f"hand{i + 1}.csv")
        write_csv(csv[-1], t, tests[0][1], F)
    path = tmp_path / "validation.mat"
    if version == "v5":
        scipy_io.savemat(path, {"time": t.reshape(-1, 1), "data": data, "label": "not numbers"})
    else:
        write_mat73(path, {"time": t.reshape(-1, 1), "data": data})
    # one record: a column of the matrix
    one = dampbench.load_records(path, columns={"t": "time", "x": "data[:,0]", "F": "data[:,3]"})
    assert [r.name for r in one] == ["validation"]
    assert_same_records(one, [dampbench.load_record(csv[2])])
    # several: one per force column, the currents from --set
    several = dampbench.load_records(path, columns="t=time,x=data[:,0],F=data[:,1:6]", set={"I": CURRENTS})
    assert [r.name for r in several] == [f"validation#{k}" for k in range(1, 6)]
    by_hand = [dampbench.load_record(p, set={"I": current}) for p, current in zip(csv, CURRENTS)]
    assert_same_records(several, by_hand)
    # the command line: the same metrics from the .mat file as from the CSV files
    from_mat = cli_json(exe, "evaluate", "--model", "mrd.bingham", "--params", "f_c=500,c0=2000,f0=0", "--data", path,
                        "--columns", "t=time,x=data[:,0],F=data[:,1:6]")
    from_csv = cli_json(exe, "evaluate", "--model", "mrd.bingham", "--params", "f_c=500,c0=2000,f0=0",
                        *[a for p in csv for a in ("--data", p)])
    assert list(from_mat.values()) == list(from_csv.values())
    assert list(from_mat) == [f"validation#{k}" for k in range(1, 6)]


def test_a_struct_array_gives_one_record_per_element(tmp_path):
    tests = five_tests_in_si()
    array = np.zeros((1, len(tests)), dtype=[("t", object), ("x", object), ("F", object), ("label", object)])
    csv = []
    for k, (t, x, F) in enumerate(tests):
        n = t.size - 37 * k  # elements of different lengths
        array[0, k] = (t[:n].reshape(-1, 1), x[:n].reshape(-1, 1), F[:n].reshape(-1, 1), f"test {k}")
        csv.append(tmp_path / f"hand{k + 1}.csv")
        write_csv(csv[-1], t[:n], x[:n], F[:n])
    path = tmp_path / "tests.mat"
    scipy_io.savemat(path, {"tests": array})
    records = dampbench.load_records(path, columns="t=tests(:).t,x=tests(:).x,F=tests(:).F", set={"I": CURRENTS})
    assert [r.name for r in records] == [f"tests#{k}" for k in range(1, 6)]
    assert_same_records(records, [dampbench.load_record(p, set={"I": c}) for p, c in zip(csv, CURRENTS)])


def test_mat_file_errors_name_what_is_there(exe, tmp_path):
    path = tmp_path / "v.mat"
    scipy_io.savemat(path, {"time": np.arange(10.0).reshape(-1, 1), "data": np.ones((10, 3))})
    code, _, err = run_cli(exe, "evaluate", "--model", "mrd.bingham", "--params", "f_c=1,c0=1,f0=0", "--data", path,
                           "--columns", "t=tiempo,x=data[:,0],F=data[:,1]")
    assert code == 3 and "no channel 'tiempo'" in err and "data (10x3)" in err and "time (10x1)" in err, err
    code, _, err = run_cli(exe, "evaluate", "--model", "mrd.bingham", "--params", "f_c=1,c0=1,f0=0", "--data", path,
                           "--columns", "t=time,x=data[:,0],F=data[:,3]")
    assert code == 3 and "column 3 out of range" in err and "10x3" in err, err
    code, _, err = run_cli(exe, "evaluate", "--model", "mrd.bingham", "--params", "f_c=1,c0=1,f0=0", "--data", path,
                           "--columns", "t=time,x=data[:,0],F=data[:,1:3]", "--set", "I=0,1,2")
    assert code == 3 and "3 values for 2 records" in err, err


def rig_export(path, tests, Ts=0.005, pause_rows=(7, 3)):
    """The text a rig's DAQ software writes: a 7-line header block, sample number, date-time, two channels in
    volts (CHANNEL0 force at 980.665 N/V, CHANNEL1 displacement at 10 mm/V), events; the tests one after the other,
    each ending with DAQ Pause and the next starting with DAQ Resume."""
    rows = sum(t.size for t, _, _ in tests)
    lines = ["Header Size:  7", "Version:  2", f"Sampling Interval:  {Ts}", f"Sampling Rate:  {1 / Ts:g}",
             f"Sample Count:  {rows}", "Device Serial Number:  0", "Sample Number, Date/Time, CHANNEL0, CHANNEL1, Events"]
    volts = []
    k = 0
    for i, (_, x, F) in enumerate(tests):
        f_volts, x_volts = np.round(F / 980.665, 4), np.round(x / 10e-3, 4)  # the DAQ's 4 decimals
        volts.append((f_volts, x_volts))
        for j in range(x.size):
            k += 1
            event = "DAQ Start" if k == 1 else "DAQ Resume" if j == 0 else "DAQ Pause" if j == x.size - 1 else ""
            stamp = f"04/29/2022 12:{11 + i:02d}:{(j * Ts) % 60:06.3f} PM"
            lines.append(f"{k:10d},   {stamp}, {f_volts[j]:.4f}, {x_volts[j]:.4f}" + (f", {event}" if event else ""))
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    return volts


def test_a_rig_export_loads_as_its_five_tests_and_fits_as_converted_by_hand(tmp_path):
    tests = five_tests_in_si()
    export = tmp_path / "ME10mm1Hz.txt"
    volts = rig_export(export, tests)
    records = dampbench.load_records(export, columns={"x": "CHANNEL1", "F": "CHANNEL0"},
                                     scale={"x": 10e-3, "F": 980.665}, split="events", set={"I": CURRENTS})
    assert [r.name for r in records] == [f"ME10mm1Hz#{k}" for k in range(1, 6)]
    assert [r.operating["I"] for r in records] == CURRENTS
    # by hand: gains to SI, time from the sampling interval; named as the split names them (the runs' random
    # streams are keyed by the record's name)
    (tmp_path / "hand").mkdir()
    hand = []
    for k, (f_volts, x_volts) in enumerate(volts):
        hand.append(tmp_path / "hand" / f"ME10mm1Hz#{k + 1}.csv")
        write_csv(hand[-1], np.arange(x_volts.size) * 0.005, x_volts * 10e-3, f_volts * 980.665)
    assert_same_records(records, [dampbench.load_record(p, set={"I": c}) for p, c in zip(hand, CURRENTS)])
    for record, path in zip(records, hand):
        ours = dampbench.fit("mrd.spencer", record, metric="nrmse", pop=16, iters=4, runs=1, seed=3)
        by_hand = dampbench.fit("mrd.spencer", path, metric="nrmse", pop=16, iters=4, runs=1, seed=3)
        assert ours.metrics["nrmse"] == by_hand.metrics["nrmse"], record.name
        assert ours.params == by_hand.params, record.name


def test_rig_export_errors(exe, tmp_path):
    tests = five_tests_in_si()[:3]
    export = tmp_path / "rig.txt"
    rig_export(export, tests)
    code, _, err = run_cli(exe, "evaluate", "--model", "mrd.bingham", "--params", "f_c=1,c0=1,f0=0", "--data", export,
                           "--columns", "x=CHANNEL1,F=CHANNEL0", "--split", "events", "--set", "I=0,1")
    assert code == 3 and "2 values for 3 records" in err, err
    text = export.read_text().replace("Header Size:  7", "Header Size:  5")
    export.write_text(text)
    code, _, err = run_cli(exe, "evaluate", "--model", "mrd.bingham", "--params", "f_c=1,c0=1,f0=0", "--data", export)
    assert code == 3 and "another shape" in err, err


def test_preprocessing_matches_a_numpy_transcription(tmp_path):
    t, x, F = five_tests_in_si()[2]
    x = x + 0.002  # an offset for the mean removal
    path = tmp_path / "raw.csv"
    write_csv(path, t, x, F)
    window = 21
    (r,) = dampbench.load_records(path, smooth=window, remove_mean=["x", "F"], whole_cycles=True)

    def centred(values):  # sample k: the mean of k - window//2 ... k - window//2 + window - 1 that exist
        out = np.empty_like(values)
        for k in range(values.size):
            lo, hi = max(0, k - window // 2), min(values.size, k - window // 2 + window)
            out[k] = values[lo:hi].mean()
        return out

    xs, Fs = centred(x), centred(F)
    xs, Fs = xs - xs.mean(), Fs - Fs.mean()
    up = np.flatnonzero((xs[:-1] < xs.mean()) & (xs[1:] >= xs.mean())) + 1
    first, last = up[0], up[-1]
    np.testing.assert_allclose(r.x, xs[first:last], rtol=0, atol=1e-15)
    np.testing.assert_allclose(r.F, Fs[first:last], rtol=0, atol=1e-9)
    np.testing.assert_allclose(r.t, t[first:last] - t[first], rtol=0, atol=1e-15)
    cycles = round(r.t[-1] + 0.005)  # whole 1 Hz cycles of the 3 s test
    assert cycles >= 1 and abs(r.t[-1] + 0.005 - cycles) < 0.02, r.t[-1]


def test_simulate_writes_a_mat_file_that_loads_again(exe, tmp_path):
    mat, csv = tmp_path / "sim.mat", tmp_path / "sim.csv"
    sine = ["--sine", "amp=0.01,freq=1,cycles=2,fs=500"]
    for out in (mat, csv):
        code, _, err = run_cli(exe, "simulate", "--model", "mrd.bingham", "--params", "f_c=500,c0=2000,f0=0", *sine,
                               "--noise-rel", "0.01", "--seed", "4", "-o", out)
        assert code == 0, err
    assert_same_records([dampbench.load_record(mat)], [dampbench.load_record(csv, columns=None)])
    scores = cli_json(exe, "evaluate", "--model", "mrd.bingham", "--params", "f_c=500,c0=2000,f0=0", "--data", mat)
    again = cli_json(exe, "evaluate", "--model", "mrd.bingham", "--params", "f_c=500,c0=2000,f0=0", "--data", csv)
    assert list(scores.values()) == list(again.values())
    assert json.dumps(scores).count("nrmse") == 1
