"""simulate, evaluate, models and optimizers against the command line of the same build: the same bits, the same
messages; and known answers where they are cheap."""
import io
import math

import numpy as np
import pytest

import dampbench
from conftest import FVD_RECORD, SOURCE_DIR, cli_json, run_cli

GV_ELASTIC = ("fvd.gv_linear_elastic", {"m": 12.5, "C": 2.1e5, "alpha": 0.35, "K1": 3.0e6})
BOUC_WEN = ("mrd.bouc_wen", {"c0": 1000.0, "k0": 2000.0, "x0": 0.001, "alpha": 5.0e4, "beta": 300.0,
                             "gamma": 200.0, "A": 1.2, "n": 2.0})
SINE = "amp=0.02,freq=2,cycles=2,fs=500"
UTFSM = ("--columns", "t,x,v,F", "--units", "x=mm,v=mm/s", "--conditions", "utfsm")
UTFSM_LOADER = dict(columns="t,x,v,F", units="x=mm,v=mm/s", conditions="utfsm")


def params_text(params):
    return ",".join(f"{k}={v!r}" for k, v in params.items())


def cli_simulate(exe, model, params, *args):
    """`dampbench simulate` parsed: {column: array}. %.17g reads back to the same doubles."""
    code, out, err = run_cli(exe, "simulate", "--model", model, "--params", params_text(params), *args)
    assert code == 0, err
    table = np.loadtxt(io.StringIO(out), delimiter=",", skiprows=1, ndmin=2)
    assert out.startswith("t,x,v,a,F\n")
    return {name: table[:, k] for k, name in enumerate("txvaF")}


def assert_same_bits(python, cli):
    assert set(python) == set("txvaF")
    for name in "txvaF":
        assert python[name].dtype == np.float64
        assert python[name].tobytes() == cli[name].tobytes(), f"column {name} differs from the command line's"


def cli_error(exe, *args):
    """The command line's message (without 'dampbench: error: ') and exit code for a failing command."""
    code, _, err = run_cli(exe, *args)
    assert code != 0
    prefix = "dampbench: error: "
    assert err.startswith(prefix), err
    return code, err[len(prefix):].strip()


# simulate ----------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("model,params", [GV_ELASTIC, BOUC_WEN], ids=["algebraic", "ode"])
def test_simulate_on_a_sine_is_the_command_line_bit_for_bit(exe, model, params):
    python = dampbench.simulate(model, params, sine=SINE)
    assert_same_bits(python, cli_simulate(exe, model, params, "--sine", SINE))
    as_dict = dampbench.simulate(model, params, sine={"amp": 0.02, "freq": 2, "cycles": 2, "fs": 500})
    assert_same_bits(as_dict, python)
    assert len(python["t"]) >= 500 and np.ptp(python["F"]) > 0  # two cycles at 2 Hz sampled at 500 Hz


@pytest.mark.parametrize("model,params", [GV_ELASTIC, BOUC_WEN], ids=["algebraic", "ode"])
def test_simulate_on_a_record_is_the_command_line_bit_for_bit_from_a_path_a_record_and_arrays(exe, model, params):
    cli = cli_simulate(exe, model, params, "--input", FVD_RECORD)
    from_path = dampbench.simulate(model, params, record=FVD_RECORD)
    assert_same_bits(from_path, cli)
    rec = dampbench.load_record(FVD_RECORD)
    assert_same_bits(dampbench.simulate(model, params, record=rec), cli)
    # The record's t and x as arrays: v and a differentiated as for the file.
    assert_same_bits(dampbench.simulate(model, params_text(params), t=rec.t, x=rec.x), cli)
    assert not np.array_equal(cli["F"], rec.F)  # the model's force, not the record's


def test_simulate_noise_and_operating_variables_follow_the_command_line(exe):
    model, params = BOUC_WEN
    cli = cli_simulate(exe, model, params, "--sine", SINE, "--noise-rel", "0.05", "--seed", "7")
    assert_same_bits(dampbench.simulate(model, params, sine=SINE, noise_rel=0.05, seed=7), cli)
    clean = dampbench.simulate(model, params, sine=SINE)
    assert not np.array_equal(clean["F"], cli["F"])
    # A law on c0 over the current I, with I given by set: the same as the command line's --set.
    # (A is the gauge of z there: the law model does not fit it.)
    law_params = {k: v for k, v in params.items() if k not in ("c0", "A")}
    law_params.update({"c0_I0": 800.0, "c0_I1": 400.0})
    args = ("--laws", "c0=poly(I,1)", "--sine", SINE, "--set", "I=0.5")
    assert_same_bits(dampbench.simulate(model, law_params, laws={"c0": "poly(I,1)"}, sine=SINE, set={"I": 0.5}),
                     cli_simulate(exe, model, law_params, *args))


def test_simulate_a_law_fixture_on_a_utfsm_file_reads_it_as_the_command_line(exe, shared_data):
    """The loader options reach the file: its units, columns and the current from its name (I = 0.5 A)."""
    path = shared_data / "utfsm-mr-damper" / "10mm1Hz0x5A.txt"
    code, out, err = run_cli(exe, "simulate", "--fixture", "mfm.table3", "--input", path, *UTFSM)
    assert code == 0, err
    table = np.loadtxt(io.StringIO(out), delimiter=",", skiprows=1)
    python = dampbench.simulate(fixture="mfm.table3", record=path, **UTFSM_LOADER)
    assert_same_bits(python, {name: table[:, k] for k, name in enumerate("txvaF")})
    at_zero = dampbench.simulate(fixture="mfm.table3", record=path, **{**UTFSM_LOADER, "conditions": None},
                                 set={"I": 0.0})
    assert not np.array_equal(at_zero["F"], python["F"])  # the current matters: the file's name was read


def test_simulate_linear_viscous_is_m_a_plus_c_v():
    m, c = 3.0, 1.5e4
    t = np.linspace(0.0, 1.0, 401)
    x = 0.01 * np.sin(2 * np.pi * 2.0 * t)
    out = dampbench.simulate("fvd.linear_viscous", {"m": m, "C": c}, t=t, x=x)
    assert np.array_equal(out["t"], t) and np.array_equal(out["x"], x)
    v_true = 0.01 * 2 * np.pi * 2.0 * np.cos(2 * np.pi * 2.0 * t)
    assert np.max(np.abs(out["v"][5:-5] - v_true[5:-5])) < 1e-3 * np.max(np.abs(v_true))  # differentiated
    np.testing.assert_allclose(out["F"], m * out["a"] + c * out["v"], rtol=1e-13, atol=1e-9)
    zero_mass = dampbench.simulate("fvd.linear_viscous", "m=0,C=15000", t=t, x=x)
    np.testing.assert_allclose(zero_mass["F"], c * zero_mass["v"], rtol=1e-15, atol=0)


def test_simulate_fixture_and_model_file_follow_the_command_line(exe, tmp_path):
    code, out, err = run_cli(exe, "simulate", "--fixture", "mfm.table3", "--sine", SINE, "--set", "I=0.5")
    assert code == 0, err
    table = np.loadtxt(io.StringIO(out), delimiter=",", skiprows=1)
    assert dampbench.simulate(fixture="mfm.table3", sine=SINE, set={"I": 0.5})["F"].tobytes() == table[:, 4].tobytes()
    # A model file of a short fit (fit --save-model): its coefficients, as the command line reads them.
    model_file = tmp_path / "model.json"
    code, _, err = run_cli(exe, "fit", "--model", "fvd.linear_viscous", "--data", FVD_RECORD, "--runs", "1", "--pop",
                           "4", "--iters", "2", "--save-model", model_file)
    assert code == 0, err
    code, out, err = run_cli(exe, "simulate", "--model-file", model_file, "--input", FVD_RECORD)
    assert code == 0, err
    table = np.loadtxt(io.StringIO(out), delimiter=",", skiprows=1)
    from_file = dampbench.simulate(model_file=model_file, record=FVD_RECORD)
    assert from_file["F"].tobytes() == table[:, 4].tobytes()
    with pytest.raises(dampbench.UsageError, match="--model-file gives the model"):
        dampbench.simulate("fvd.linear_viscous", model_file=model_file, record=FVD_RECORD)


# simulate: bad input ---------------------------------------------------------------------------------------


def test_unknown_model_raises_usage_error_with_the_command_line_message(exe):
    code, message = cli_error(exe, "simulate", "--model", "fvd.nope", "--params", "C=1", "--sine", SINE)
    with pytest.raises(dampbench.UsageError) as raised:
        dampbench.simulate("fvd.nope", {"C": 1.0}, sine=SINE)
    assert str(raised.value) == message
    assert type(raised.value).exit_code == code == 2


def test_unknown_and_missing_parameters_raise_usage_error_with_the_command_line_message(exe):
    model, params = GV_ELASTIC
    bad = {**params, "K9": 1.0}
    code, message = cli_error(exe, "simulate", "--model", model, "--params", params_text(bad), "--sine", SINE)
    with pytest.raises(dampbench.UsageError) as raised:
        dampbench.simulate(model, bad, sine=SINE)
    assert str(raised.value) == message and "K9" in message
    missing = dict(params)
    del missing["alpha"]
    code, message = cli_error(exe, "simulate", "--model", model, "--params", params_text(missing), "--sine", SINE)
    with pytest.raises(dampbench.UsageError, match="missing parameter 'alpha'") as raised:
        dampbench.simulate(model, missing, sine=SINE)
    assert str(raised.value) == message


def test_nan_in_x_and_time_not_increasing_raise_data_error_naming_the_sample():
    model, params = GV_ELASTIC
    t = np.linspace(0.0, 1.0, 101)
    x = 0.01 * np.sin(2 * np.pi * t)
    x[17] = np.nan
    with pytest.raises(dampbench.DataError, match=r"column 'x', sample 17: value is not finite"):
        dampbench.simulate(model, params, t=t, x=x)
    t[40] = t[39]
    with pytest.raises(dampbench.DataError, match=r"time must increase strictly \(.* at sample 40"):
        dampbench.simulate(model, params, t=t, x=0.01 * np.sin(2 * np.pi * t))
    assert issubclass(dampbench.DataError, dampbench.UsageError) and dampbench.DataError.exit_code == 3


def test_simulate_needs_exactly_one_displacement():
    model, params = GV_ELASTIC
    with pytest.raises(dampbench.UsageError, match="exactly one displacement"):
        dampbench.simulate(model, params)
    with pytest.raises(dampbench.UsageError, match="exactly one displacement"):
        dampbench.simulate(model, params, sine=SINE, record=FVD_RECORD)
    with pytest.raises(dampbench.UsageError, match="give both t and x"):
        dampbench.simulate(model, params, t=np.linspace(0, 1, 50))
    with pytest.raises(dampbench.UsageError, match="units read a record file"):
        dampbench.simulate(model, params, sine=SINE, units="x=mm")


# evaluate ----------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("model,params", [GV_ELASTIC, BOUC_WEN], ids=["algebraic", "ode"])
def test_evaluate_is_the_command_line_bit_for_bit(exe, model, params):
    cli = cli_json(exe, "evaluate", "--model", model, "--params", params_text(params), "--data", FVD_RECORD)
    python = dampbench.evaluate(model, params, str(FVD_RECORD))
    assert list(python) == list(cli) == [str(FVD_RECORD)]
    row, expected = python[str(FVD_RECORD)], cli[str(FVD_RECORD)]
    assert list(row) == list(expected) and len(row) > 5
    for metric, value in expected.items():
        assert (value is None and not math.isfinite(row[metric])) or row[metric] == value, metric
    by_record = dampbench.evaluate(model, params, [dampbench.load_record(FVD_RECORD)])
    assert by_record == {"test3_20mm_460mms": row}


def test_evaluate_known_answer_the_truth_of_a_simulated_record_has_zero_error():
    model, params = GV_ELASTIC
    sim = dampbench.simulate(model, params, sine=SINE)
    rec = dampbench.record(sim["t"], sim["x"], sim["F"], v=sim["v"], a=sim["a"], name="own")
    metrics = dampbench.evaluate(model, params, rec)["own"]
    assert metrics["of_abs"] == 0 and metrics["rmse"] == 0
    worse = dampbench.evaluate(model, {**params, "C": 2.2e5}, rec)["own"]
    assert worse["rmse"] > 0


def test_evaluate_bad_input_raises_the_command_line_message(exe):
    model, params = GV_ELASTIC
    missing = {k: v for k, v in params.items() if k != "m"}
    code, message = cli_error(exe, "evaluate", "--model", model, "--params", params_text(missing), "--data", FVD_RECORD)
    with pytest.raises(dampbench.UsageError) as raised:
        dampbench.evaluate(model, missing, FVD_RECORD)
    assert str(raised.value) == message
    with pytest.raises(dampbench.UsageError, match="at least one record"):
        dampbench.evaluate(model, params, [])


# models and optimizers -------------------------------------------------------------------------------------


def test_models_is_the_command_line_list(exe):
    listed = dampbench.models()
    assert listed == cli_json(exe, "models")["models"]
    assert "fvd.linear_viscous" in listed and "mrd.spencer" in listed
    names = [p["name"] for p in listed["fvd.linear_viscous"]["parameters"]]
    assert names == ["m", "C"]


def test_models_of_a_record_scale_exactly_the_parameters_with_a_record_rule(shared_data):
    path = shared_data / "utfsm-mr-damper" / "10mm1Hz0x5A.txt"
    fixed = dampbench.models()
    scaled = dampbench.models(path, **UTFSM_LOADER)
    assert dampbench.models(dampbench.load_record(path, **UTFSM_LOADER)) == scaled
    assert list(scaled) == list(fixed)
    ruled = 0
    for model_id, entry in fixed.items():
        for before, after in zip(entry["parameters"], scaled[model_id]["parameters"]):
            changed = (before["lower"], before["upper"]) != (after["lower"], after["upper"])
            assert changed == ("record_rule" in before), (model_id, before["name"])
            ruled += changed
    assert ruled > 0


def test_models_of_a_record_known_answer_bouc_wen_scales_with_peak_force_velocity_and_amplitude(shared_data):
    """mrd.bouc_wen's record rules: c0 in 0..2 F/V, k0 in 0..1 F/X, x0 in -X..X, n in 1..3 (F, V: peak force and
    velocity, X: half the displacement's peak to peak)."""
    rec = dampbench.load_record(shared_data / "utfsm-mr-damper" / "10mm1Hz0x5A.txt", **UTFSM_LOADER)
    F, V, X = np.max(np.abs(rec.F)), np.max(np.abs(rec.v)), 0.5 * np.ptp(rec.x)
    box = {p["name"]: (p["lower"], p["upper"]) for p in dampbench.models(rec)["mrd.bouc_wen"]["parameters"]}
    assert box["c0"] == (0.0, pytest.approx(2 * F / V, rel=1e-14))
    assert box["k0"] == (0.0, pytest.approx(F / X, rel=1e-14))
    assert box["x0"] == (pytest.approx(-X, rel=1e-14), pytest.approx(X, rel=1e-14))
    fixed = {p["name"]: (p["lower"], p["upper"]) for p in dampbench.models()["mrd.bouc_wen"]["parameters"]}
    assert box["n"] == (1.0, 3.0) and fixed["n"] == (0.5, 3.0)  # the rule "1..3 x 1": no scale


def test_optimizers_names_settings_and_fit_defaults():
    listed = dampbench.optimizers()
    assert list(listed) == ["pso", "ga", "aga", "de", "cmaes", "ga-sqp", "ga-lm"]
    # optimizers/registry.hpp's table of settings
    assert listed["pso"]["settings"] == ["variant", "inertia", "inertia_end", "cognitive", "social", "vmax_fraction"]
    assert listed["de"]["settings"] == ["strategy", "F", "CR"]
    assert {"pc", "pm", "preset"} <= set(listed["ga"]["settings"])
    assert {"global", "lm_iterations", "geodesic"} <= set(listed["ga-lm"]["settings"])
    # engine/fit/fit_defaults.cpp's class defaults
    assert listed["pso"]["fit_default_for"] == {
        "algebraic": {"optimizer": "pso", "population": 50, "iterations": 100, "runs": 50}}
    assert listed["ga-lm"]["fit_default_for"] == {
        "internal_states": {"optimizer": "ga-lm", "population": 24, "iterations": 30, "runs": 4}}
    assert listed["de"]["fit_default_for"] == {}


def test_every_listed_setting_is_one_fit_knows(exe):
    """fit's message for an unknown setting lists what optimizers() gives."""
    for name, entry in dampbench.optimizers().items():
        _, message = cli_error(exe, "fit", "--model", "fvd.linear_viscous", "--data", FVD_RECORD, "--optimizer", name,
                               "--optimizer-settings", "zz=1", "--runs", "1", "--pop", "4", "--iters", "2")
        assert message.endswith(f"(known: {', '.join(entry['settings'])})"), message


# inverse and fixed-step simulation ------------------------------------------------------------------------------

def test_inverse_finds_the_current_of_a_fixed_step_simulation_as_the_command_line(exe, tmp_path):
    t = np.linspace(0.0, 2.0, 2001)
    x = 0.01 * np.sin(2 * np.pi * t)
    stepped = dampbench.simulate(fixture="mfm.table3", t=t, x=x, set={"I": 0.4}, fixed_step=4)
    desired = dampbench.record(t, x, stepped["F"], v=stepped["v"], a=stepped["a"], name="desired")
    out = dampbench.inverse(fixture="mfm.table3", record=desired, range="I=0:1")
    assert out["variable"] == "I"
    assert out["share_reachable"] > 0.99 and out["tracking_error"] < 1e-6
    moving = np.abs(stepped["v"][1:]) > 0.02  # where the piston moves, the force determines the current
    assert np.all(np.abs(out["command"][:-1][moving] - 0.4) < 1e-3)
    csv = tmp_path / "desired.csv"
    np.savetxt(csv, np.column_stack([t, x, stepped["v"], stepped["a"], stepped["F"]]), delimiter=",",
               header="t,x,v,a,F", comments="", fmt="%.17g")
    cli = cli_json(exe, "inverse", "--fixture", "mfm.table3", "--data", csv, "--range", "I=0:1")
    assert cli["share_reachable"] == out["share_reachable"] and cli["tracking_error"] == out["tracking_error"]
    with pytest.raises(dampbench.UsageError, match="has no law in V"):
        dampbench.inverse(fixture="mfm.table3", record=desired, range="V=0:1")


def test_structure_gives_the_command_lines_peaks_and_energies(exe, tmp_path):
    t = np.arange(0.0, 2.0, 0.005)
    ground = tmp_path / "ground.csv"
    np.savetxt(ground, np.column_stack([t, 2.0 * np.sin(3 * np.pi * t) * np.exp(-t)]), delimiter=",",
               header="t,ag", comments="", fmt="%.17g")
    building = SOURCE_DIR / "datasets" / "buildings" / "utfsm_case_1.toml"
    out = dampbench.structure(fixture="mfm.table3", set={"I": 0.5}, building=building, ground=ground)
    cli = cli_json(exe, "structure", "--fixture", "mfm.table3", "--set", "I=0.5", "--building", building,
                   "--ground", ground)
    for run in ("bare", "damped"):
        assert list(out[run]["peak_drift"]) == cli[run]["peak_drift_m"]
        assert out[run]["peak_abs_acc"].tolist() == cli[run]["peak_absolute_acceleration_m_s2"]
        assert out[run]["steps"] == cli[run]["steps"]
    assert out["damped"]["energy"]["damper"] == cli["damped"]["energy_J"]["damper"]
    assert out["damped"]["peak_force"] == cli["damped"]["peak_damper_force_N"]
    assert out["bare"]["peak_force"] == 0.0 and out["damped"]["peak_force"] > 0.0
    # the time histories: one row per output step, one column per storey; the peak over them is at most the peak
    # over every step
    drift = out["damped"]["drift"]
    assert drift.shape == (len(out["damped"]["t"]), 3)
    assert np.all(np.max(np.abs(drift), axis=0) <= out["damped"]["peak_drift"])
    with pytest.raises(dampbench.UsageError, match="--control: expected passive or on-off"):
        dampbench.structure(fixture="mfm.table3", building=building, ground=ground, control="sometimes")


def test_export_c_is_the_command_lines_text_and_refuses_what_it_does_not_cover(exe, tmp_path):
    out = dampbench.export_c(fixture="mfm.table3", substeps=3, output=tmp_path)
    cli_dir = tmp_path / "cli"
    cli_dir.mkdir()
    code, _, err = run_cli(exe, "export", "--fixture", "mfm.table3", "--substeps", "3", "-o", cli_dir)
    assert code == 0, err
    for name, key in (("dampbench_model.h", "header"), ("dampbench_model.c", "source")):
        assert (cli_dir / name).read_text() == out[key] == (tmp_path / name).read_text()
    assert "#define DBM_SUBSTEPS 3" in out["header"]
    assert out["dt_max_s"] == 0 and "Step size: not checked" in out["header"]  # a fixture: no fitted range
    model_file = SOURCE_DIR / "datasets" / "models" / "utfsm_spencer_I.json"
    checked = dampbench.export_c(model_file=model_file)
    assert f"checked stable for dt <= {checked['dt_max_s']:.3g} s" in checked["header"]
    assert dampbench.export_c("mrd.bingham", {"f_c": 300, "c0": 2000, "f0": -5})["dt_max_s"] == math.inf
    spencer = {"c0": 4110, "c1": 4.542e5, "k0": 42.83, "k1": 561.2, "x0": -6.678e-2, "alpha": 166.01, "beta": 6.079e3,
               "gamma": 1.083e4, "A": 5.021e4, "n": 0.9929}
    slow = dampbench.export_c("mrd.spencer", spencer, stroke_m=0.02, velocity_m_s=0.0628)["dt_max_s"]
    fast = dampbench.export_c("mrd.spencer", spencer, stroke_m=0.02, velocity_m_s=0.5)["dt_max_s"]
    assert 0 < fast < slow  # a faster motion stiffens the hysteresis
    with pytest.raises(dampbench.UsageError, match="--stroke-m: expected a finite number above 0"):
        dampbench.export_c("mrd.spencer", spencer, stroke_m=-1, velocity_m_s=0.1)
    with pytest.raises(dampbench.UsageError, match="fvd.linear_viscous"):
        dampbench.export_c("fvd.linear_viscous", {"m": 0, "C": 1000})
