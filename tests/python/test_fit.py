"""dampbench.fit against `dampbench fit`: the same bits from a file and from arrays, for an algebraic model, an
ODE model and a law model; every run, the verdict and the identifiability as the command line gives them; files it
writes; threads; bad input raising the command line's message in the class of its exit code."""
import numpy as np
import pytest

import dampbench
from conftest import FVD_RECORD, cli_json, run_cli

# Bouc-Wen (mrd.bouc_wen) parameters of the synthetic ODE records, in SI.
BOUC_WEN = "c0=2000,k0=500,x0=0,alpha=8000,beta=3e5,gamma=3e5,A=120,n=2"


def simulated(exe, tmp_path, name, model, params, laws=None, current=None):
    """A record simulated by the command line (a 1 Hz, 10 mm sine at 400 Hz, 2 cycles), as a CSV file."""
    path = tmp_path / f"{name}.csv"
    args = ["simulate", "--model", model, "--params", params, "--sine", "amp=0.01,freq=1,cycles=2,fs=400", "-o", path]
    if laws:
        args += ["--laws", laws]
    if current is not None:
        args += ["--set", f"I={current}"]
    code, _, err = run_cli(exe, *args)
    assert code == 0, err
    return path


def from_arrays(path, **operating):
    """The file's columns as a record made from arrays, named as the file (its stem): the runs' keys match."""
    rec = dampbench.load_record(path)
    return dampbench.record(rec.t, rec.x, rec.F, v=rec.v, a=rec.a, name=rec.name, set=operating or None)


def assert_same_fit(result, cli):
    """Every number of the fit the same bits as the command line's."""
    assert result.params == cli["best_params"]
    assert result.metrics == cli["metrics"]
    assert [r["best_value"] for r in result.runs] == [r["best_value"] for r in cli["run_results"]]
    assert [r["best_params"] for r in result.runs] == [r["best_params"] for r in cli["run_results"]]
    assert result.converged == cli["convergence"]["converged"]
    assert result.verdict == cli["convergence"]["verdict"]
    assert result.identifiability == cli["identifiability"]
    assert result.budget == cli["budget"]
    assert [h.tolist() for h in result.history] == cli["history"]


def test_algebraic_model_from_file_and_arrays_equals_cli(exe):
    cli = cli_json(exe, "fit", "--model", "fvd.gv_quadratic_elastic", "--data", FVD_RECORD)
    from_file = dampbench.fit("fvd.gv_quadratic_elastic", FVD_RECORD)
    assert_same_fit(from_file, cli)
    assert_same_fit(dampbench.fit("fvd.gv_quadratic_elastic", from_arrays(FVD_RECORD)), cli)
    assert from_file.model == "fvd.gv_quadratic_elastic"
    assert set(from_file.params) == {"m", "C", "alpha", "K1", "K2"}


def test_ode_model_from_file_and_arrays_equals_cli(exe, tmp_path):
    path = simulated(exe, tmp_path, "bouc_wen_sine", "mrd.bouc_wen", BOUC_WEN)
    budget = dict(pop=16, iters=10, runs=2, seed=7)
    cli = cli_json(exe, "fit", "--model", "mrd.bouc_wen", "--data", path, "--pop", 16, "--iters", 10, "--runs", 2,
                   "--seed", 7)
    assert_same_fit(dampbench.fit("mrd.bouc_wen", path, **budget), cli)
    # the population search in float64 lanes (the default is mixed): the command line's bits too
    dbl = cli_json(exe, "fit", "--model", "mrd.bouc_wen", "--data", path, "--pop", 16, "--iters", 10, "--runs", 2,
                   "--seed", 7, "--precision", "double")
    assert dbl["precision"] == "double" and cli["precision"] == "mixed"
    assert_same_fit(dampbench.fit("mrd.bouc_wen", path, precision="double", **budget), dbl)
    assert_same_fit(dampbench.fit("mrd.bouc_wen", from_arrays(path), **budget), cli)
    # The record is noise-free: the fit reproduces its force (a known answer, not only agreement).
    assert cli["metrics"]["of_abs"] < 1e-6


def test_law_model_over_two_currents_equals_cli(exe, tmp_path):
    laws = "f_c=poly(I,1)"
    truth = "f_c_I0=100,f_c_I1=400,c0=2000,f0=5"
    paths = [simulated(exe, tmp_path, f"bingham_{i}A", "mrd.bingham", truth, laws, i) for i in (0, 1)]
    for path, current in zip(paths, (0, 1)):  # each file states its current, as a rig's file would
        path.write_text(f"# operating: I={current}\n" + path.read_text())
    cli = cli_json(exe, "fit", "--model", "mrd.bingham", "--laws", laws, "--data", paths[0], "--data", paths[1],
                   "--runs", 3, "--seed", 2)
    result = dampbench.fit("mrd.bingham", paths, laws={"f_c": "poly(I,1)"}, runs=3, seed=2)
    assert_same_fit(result, cli)
    records = [from_arrays(p, I=i) for p, i in zip(paths, (0, 1))]
    assert_same_fit(dampbench.fit("mrd.bingham", records, laws=laws, runs=3, seed=2), cli)
    assert set(result.params) == {"f_c_I0", "f_c_I1", "c0", "f0"}


def test_thread_count_does_not_change_the_bits():
    one = dampbench.fit("fvd.gv_linear_elastic", FVD_RECORD, runs=6, seed=3, threads=1)
    two = dampbench.fit("fvd.gv_linear_elastic", FVD_RECORD, runs=6, seed=3, threads=2)
    assert one.json["run_results"] == two.json["run_results"]


def test_model_file_and_report_are_the_command_lines(exe, tmp_path):
    cli_model = tmp_path / "cli_model.json"
    py_model = tmp_path / "py_model.json"
    report = tmp_path / "fit.html"
    cli_json(exe, "fit", "--model", "fvd.gv_linear_elastic", "--data", FVD_RECORD, "--runs", 4, "--save-model", cli_model)
    dampbench.fit("fvd.gv_linear_elastic", FVD_RECORD, runs=4, save_model=py_model, report=report)
    assert py_model.read_text() == cli_model.read_text()
    assert report.read_text().lstrip().lower().startswith("<!doctype html")


def test_result_shapes():
    result = dampbench.fit("fvd.gv_linear_elastic", FVD_RECORD, runs=5, seed=4)
    assert len(result.runs) == 5 and len(result.history) == 5
    for h in result.history:
        assert h.ndim == 2 and h.shape[1] == 2 and np.all(np.diff(h[:, 0]) > 0) and np.all(np.diff(h[:, 1]) <= 0)
    assert result.correlation.shape == (4, 4)
    assert min(r["best_value"] for r in result.runs) == result.metrics["of_abs"]


def cli_error(exe, *args):
    """The exit code and message of a failing command line ("dampbench: error: MESSAGE")."""
    code, _, err = run_cli(exe, *args)
    assert code != 0
    prefix = "dampbench: error: "
    line = next(line for line in err.splitlines() if line.startswith(prefix))
    return code, line[len(prefix):]


@pytest.mark.parametrize("cli_args, py_args, py_kwargs, error", [
    (["--model", "fvd.nope", "--data", FVD_RECORD], ("fvd.nope", FVD_RECORD), {}, dampbench.UsageError),
    (["--model", "fvd.gv_linear_elastic", "--data", "/nonexistent/r.csv"], ("fvd.gv_linear_elastic", "/nonexistent/r.csv"),
     {}, dampbench.DataError),
    (["--model", "fvd.gv_linear_elastic", "--data", FVD_RECORD, "--bounds", "C=5:1"],
     ("fvd.gv_linear_elastic", FVD_RECORD), {"bounds": "C=5:1"}, dampbench.UsageError),
    (["--model", "fvd.gv_linear_elastic", "--data", FVD_RECORD, "--optimizer", "sa"],
     ("fvd.gv_linear_elastic", FVD_RECORD), {"optimizer": "sa"}, dampbench.UsageError),
    (["--model", "fvd.gv_linear_elastic", "--data", FVD_RECORD, "--budget", "sometimes"],
     ("fvd.gv_linear_elastic", FVD_RECORD), {"budget": "sometimes"}, dampbench.UsageError),
    (["--model", "fvd.gv_linear_elastic", "--data", FVD_RECORD, "--units", "x=furlong"],
     ("fvd.gv_linear_elastic", FVD_RECORD), {"units": "x=furlong"}, dampbench.DataError),
])
def test_bad_input_raises_the_command_lines_message(exe, cli_args, py_args, py_kwargs, error):
    code, message = cli_error(exe, "fit", *cli_args)
    with pytest.raises(error) as raised:
        dampbench.fit(*py_args, **py_kwargs)
    assert str(raised.value) == message
    assert raised.value.exit_code == code


def test_bad_arrays_raise_data_errors():
    t = np.linspace(0, 1, 50)
    x = 0.01 * np.sin(2 * np.pi * t)
    F = 1e3 * np.cos(2 * np.pi * t)
    with pytest.raises(dampbench.DataError, match=r"record 'r': column 'x', sample 3: value is not finite"):
        dampbench.record(t, np.where(np.arange(50) == 3, np.nan, x), F, name="r")
    with pytest.raises(dampbench.DataError, match=r"time must increase strictly .* at sample 10"):
        dampbench.record(np.where(np.arange(50) == 10, t[9], t), x, F, name="r")
    with pytest.raises(dampbench.DataError, match=r"column 'F' has 49 samples and column 't' 50"):
        dampbench.record(t, x, F[:-1], name="r")
    with pytest.raises(dampbench.DataError, match=r"x: expected an array of real numbers"):
        dampbench.record(t, x.astype(complex), F)
    with pytest.raises(dampbench.DataError, match=r"F: expected a 1-D array"):
        dampbench.record(t, x, np.stack([F, F]))
    with pytest.raises(dampbench.UsageError, match=r"record 'r' has no force F"):
        dampbench.fit("fvd.linear_viscous", dampbench.record(t, x, name="r"))
    assert dampbench.DataError.exit_code == 3 and issubclass(dampbench.DataError, dampbench.Error)


def test_prediction_and_vector_level_equal_cli(exe):
    """--predict (held-out records, read with the same loader options) and --isa, as the command line."""
    held_out = FVD_RECORD.with_name("test4_17mm_460mms.csv")
    cli = cli_json(exe, "--isa", "sse2", "fit", "--model", "fvd.gv_linear_elastic", "--data", FVD_RECORD,
                   "--runs", 4, "--predict", held_out)
    result = dampbench.fit("fvd.gv_linear_elastic", FVD_RECORD, runs=4, predict=[held_out], isa="sse2")
    assert_same_fit(result, cli)
    assert result.json["held_out"] == cli["held_out"]


def test_a_current_that_varies_during_the_test_is_followed_by_the_laws():
    # F = (1000 + 2000 I(t)) v with a current stepping from 0 to 1 A halfway (the command at a sample holds until
    # the next, so the force at sample k sees the current of sample k - 1): fitted exactly, which no constant current
    # could do.
    t = np.arange(200) * 0.01
    w = 2 * np.pi
    x, v = 0.01 * np.sin(w * t), 0.01 * w * np.cos(w * t)
    current = np.where(np.arange(200) < 100, 0.0, 1.0)
    held = np.where(np.arange(200) <= 100, 0.0, 1.0)
    rec = dampbench.record(t, x, (1000 + 2000 * held) * v, v=v, I=current, name="step")
    np.testing.assert_array_equal(rec.varying["I"], current)
    assert rec.operating_source["I"].startswith("column varying from 0 to 1")
    bounds = {"m": (0, 0), "C_I0": (0, 1e4), "C_I1": (0, 1e4)}
    result = dampbench.fit("fvd.linear_viscous", rec, laws={"C": "poly(I,1)"}, bounds=bounds, runs=2, iters=40,
                           metric="nrmse")
    assert result.metrics["nrmse"] < 1e-3
    assert abs(result.params["C_I1"] - 2000) < 20
