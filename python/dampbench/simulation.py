"""simulate, evaluate, models and optimizers: `dampbench simulate`, `dampbench evaluate` and `dampbench models`
on Records, files or numpy arrays, with the command line's results to the bit, and the optimizers by name."""
import json
import os

from dampbench import _core
from dampbench._core import Record, UsageError
from dampbench.fitting import _laws_text
from dampbench.records import as_records, key_values, load_record, loader_args, record as record_from_arrays


def _model_args(model, params, laws, model_file):
    return dict(model=model or "", laws=_laws_text(laws), params=key_values(params, "params"),
                model_file=os.fspath(model_file) if model_file is not None else "")


def simulate(model=None, params=None, *, t=None, x=None, record=None, sine=None, laws=None, fixture=None,
             model_file=None, noise_rel=0.0, seed=1, set=None, units=None, columns=None, transform=None,
             average_cycles=None, conditions=None, fixed_step=0, threads=None, isa=None):
    """The force of a model under a displacement, as `dampbench simulate` computes it (the same bits).

    The model: `model` (an id of models()) with `params`, or `fixture` (a published law fixture, e.g.
    "mfm.table3", whose coefficients are the defaults of `params`), or `model_file` (what fit(save_model=...)
    writes) alone. params: {name: value} in SI or the command line's "name=value,..."; every parameter is needed
    unless a fixture gives it. laws: {"c0": "poly(I,1)"} or "c0=poly(I,1);...", whose coefficients params then
    gives.

    The displacement, exactly one of:
      t, x: numpy arrays, time [s] (strictly increasing) and displacement [m]; velocity and acceleration are
        differentiated as for a record file (transform, average_cycles and conditions apply as in record());
      record: a Record, or a file path read with the loader options units, columns, transform, average_cycles,
        conditions (as load_record; no force column needed);
      sine: {"amp": 0.01, "freq": 2, "cycles": 3, "fs": 1000} (amp [m], freq [Hz] or vpeak [m/s], fs [Hz]) or
        the command line's "amp=0.01,freq=2,cycles=3,fs=1000".
    set: {"I": 0.5} operating variables (I [A], V [V], phi [deg], amp [m], freq [Hz]) for the model's laws.
    noise_rel: Gaussian noise of std noise_rel x RMS(F) added to F, from `seed`. threads and isa as in fit.
    fixed_step: N > 0 steps the model sample by sample with N fixed RK4 sub-steps per interval (`simulate
    --fixed-step N`), following a record's varying I, V or phi column.

    Returns {"t", "x", "v", "a", "F"}: numpy arrays in SI (s, m, m/s, m/s^2, N), what the command line prints as
    CSV. The interpreter is released while the engine works. Errors raise UsageError or DataError with the
    command line's message (an unknown model or parameter, a missing parameter, NaN in x, t not increasing).
    """
    given = [name for name, value in (("t and x", t if t is not None else x), ("record", record), ("sine", sine))
             if value is not None]
    if len(given) != 1:
        raise UsageError("simulate: give exactly one displacement: t and x (arrays), record (a Record or file) or "
                         f"sine (got {', '.join(given) or 'none'})")
    file_options = dict(units=units, columns=columns)
    record_options = dict(transform=transform, average_cycles=average_cycles, conditions=conditions)
    path, rec = "", None
    if record is not None and not isinstance(record, Record):
        if not isinstance(record, (str, os.PathLike)):
            raise UsageError(f"simulate: record: expected a Record or a file path, got {type(record).__name__}")
        path = os.fspath(record)
    else:
        unused = [k for k, v in {**file_options, **(record_options if t is None and x is None else {})}.items()
                  if v is not None]
        if unused:
            raise UsageError(f"simulate: {', '.join(unused)} read a record file: give them with record=PATH")
        if record is not None:
            rec = record
        elif sine is None:
            if t is None or x is None:
                raise UsageError("simulate: give both t and x (arrays in s and m)")
            rec = record_from_arrays(t, x, name="arrays", require_force=False, **record_options)
    loader = loader_args(**file_options, **record_options, set=set) if path else loader_args(set=set)
    return _core.simulate(**_model_args(model, params, laws, model_file), fixture=fixture or "", record=rec,
                          path=path, loader=loader, sine=key_values(sine, "sine"), noise_rel=float(noise_rel),
                          seed=seed, fixed_step=int(fixed_step), threads=threads, isa=isa)


def inverse(model=None, params=None, *, record, range, law="inverse", laws=None, fixture=None, model_file=None,
            substeps=4, set=None, units=None, columns=None, transform=None, average_cycles=None, conditions=None):
    """The command that makes a damper model give a desired force, as `dampbench inverse` computes it.

    The model as in simulate (model_file, or model/fixture with laws and params); it needs a law in the commanded
    variable. record: a Record or a file path (loader options as load_record) holding the motion and the desired
    force F. range: "I=0:1" (the variable and its limits). law: "inverse" (the command whose force is the desired
    one, the nearer limit where it is out of reach) or "on-off". substeps: the model's fixed RK4 sub-steps per
    sample interval.

    Returns {"t", "command", "F_desired", "F_model", "reachable"} (arrays; the command holds from its sample to
    the next) and "variable", "share_reachable", "share_at_low", "share_at_high", "tracking_error" (relative RMS
    over the reachable samples).
    """
    path, rec = "", None
    if isinstance(record, Record):
        rec = record
    elif isinstance(record, (str, os.PathLike)):
        path = os.fspath(record)
    else:
        raise UsageError(f"inverse: record: expected a Record or a file path, got {type(record).__name__}")
    file_options = dict(units=units, columns=columns, transform=transform, average_cycles=average_cycles,
                        conditions=conditions)
    loader = loader_args(**file_options, set=set) if path else loader_args(set=set)
    return _core.inverse(**_model_args(model, params, laws, model_file), fixture=fixture or "", record=rec,
                         path=path, loader=loader, range=range, law=law, substeps=int(substeps))


def evaluate(model=None, params=None, records=None, *, laws=None, model_file=None, isa=None, units=None,
             columns=None, transform=None, average_cycles=None, conditions=None, set=None):
    """Every metric of a model at given parameters on each record, as `dampbench evaluate` (the same bits).

    model with params ({name: value} in SI or "name=value,...", every parameter needed) and optionally laws, or
    model_file alone. records: a Record, a file path, or a list of them (files read with the loader options, as
    load_record); each needs a force. isa: "sse2", "avx2" or "avx512" for this call.

    Returns {key: {metric: value}} in the records' order, keyed as `dampbench evaluate --format json` keys them:
    a path as given (str), a Record by its name; the metrics are those of the command line (of_abs, of_sq, rmse,
    nrmse, ...), a value that the command line prints as null is NaN or infinite here.
    """
    if records is None or (isinstance(records, (list, tuple)) and not records):
        raise UsageError("evaluate: give at least one record (a Record or a file path)")
    loader = dict(units=units, columns=columns, transform=transform, average_cycles=average_cycles,
                  conditions=conditions, set=set)
    items = records if isinstance(records, (list, tuple)) else [records]
    keys = [r.name if isinstance(r, Record) else os.fspath(r) if isinstance(r, (str, os.PathLike)) else None
            for r in items]
    rows = _core.evaluate(**_model_args(model, params, laws, model_file), records=as_records(list(items), loader),
                          isa=isa)
    return dict(zip(keys, rows))


def models(record=None, *, units=None, columns=None, transform=None, average_cycles=None, conditions=None,
           set=None):
    """Every model with its citation, law and parameters, as `dampbench models --format json` lists them.

    Returns {model id: {"citation", "law", "parameters"}}, in the command line's order; "parameters" is a list,
    in the model's order, of {"name", "unit" (SI), "lower", "upper", "paper_unit"} and "record_rule" where the
    default box scales with the record fitted (F, V, X: its peak force, peak velocity, amplitude).

    record: a Record, a file path (read with the loader options, as load_record; no force needed) or a list of
    them: lower and upper are then the default bounds for fitting those records (what fit searches when no bounds
    are given); without it (or for a record without force) the fixed default bounds.
    """
    loader = dict(units=units, columns=columns, transform=transform, average_cycles=average_cycles,
                  conditions=conditions, set=set)
    if record is None:
        if any(v is not None for v in loader.values()):
            raise UsageError("models: the loader options read a record file: give it with record=PATH")
        records = []
    else:
        items = record if isinstance(record, (list, tuple)) else [record]
        records = [load_record(r, require_force=False, **loader) if isinstance(r, (str, os.PathLike)) else r
                   for r in items]
        as_records(records, loader)  # the message for anything that is not a Record
    return json.loads(_core.models(records))


def optimizers():
    """The optimizers of fit(optimizer=...), in the order of the command line's messages.

    Returns {name: {"settings": [...], "fit_default_for": {...}}}: settings are the names
    fit(optimizer_settings=...) takes for that optimizer with its default choices (a hybrid's global = "cmaes"
    takes cmaes's settings in place of ga's); fit_default_for maps each model class ("algebraic",
    "internal_states") for which fit uses this optimizer when none is given to that default's optimizer,
    population, iterations and runs.
    """
    return _core.optimizers()


def structure(model=None, params=None, *, building, ground, laws=None, fixture=None, model_file=None, scale=1.0,
              step=1.0 / 4096.0, substeps=4, set=None, control="passive", command=None, lqr_r=1e-6, output_every=8):
    """A damper model inside a building under a ground acceleration, as `dampbench structure` runs it (the same bits).

    The model as in simulate (model_file, or model/fixture with laws and params). building: a building TOML file
    (datasets/buildings/*.toml); ground: a CSV of t [s] and ag [m/s^2]; scale: a factor on ag; step: the building's
    time step [s]; substeps: the damper's RK4 sub-steps per step. set: the damper's operating variables ({"I": 1} or
    "I=1") for a passive damper; control="on-off" with command="I=0:1" switches the command by the clipped-optimal
    rule of an LQR gain (lqr_r: R of its cost). output_every: steps between the time histories' rows.

    Returns {"damper", "bare", "damped", "lqr_residual"}; "bare" and "damped" each hold the time histories "t", "ag",
    "u", "drift", "abs_acc" (rows: times, columns: storeys), "force", "command", the peaks over every step
    "peak_u", "peak_drift", "peak_abs_acc" (per storey), "peak_force", "high_share", "energy" ({"input",
    "structural", "damper", "kinetic", "strain", "balance_error"}), "steps" and "unconverged_steps".
    """
    return _core.structure(**_model_args(model, params, laws, model_file), fixture=fixture or "",
                           building=os.fspath(building), ground=os.fspath(ground), scale=float(scale),
                           step_s=float(step), substeps=int(substeps), set=key_values(set, "set"), control=control,
                           command=command or "", lqr_r=float(lqr_r), output_every=int(output_every))


def export_c(model=None, params=None, *, laws=None, fixture=None, model_file=None, substeps=4, output=None,
             stroke_m=None, velocity_m_s=None):
    """The model as a dependency-free C99 pair, as `dampbench export --lang c` writes it (the same text).

    The model as in simulate. substeps: RK4 sub-steps per dbm_step. Returns {"header", "source", "model",
    "dt_max_s"} (the texts of dampbench_model.h and dampbench_model.c; the largest step checked stable on the
    fitted records' motion, inf for a model without states, 0 when none passed or nothing was checked, as the
    header's comment says; stroke_m and velocity_m_s [m, m/s] set the motion checked, by default the fitted
    records'); with output (an existing folder) also writes them there.
    A model the exporter does not cover raises UsageError before anything is written.
    """
    out = _core.export_c(**_model_args(model, params, laws, model_file), fixture=fixture or "", substeps=int(substeps),
                         stroke_m=None if stroke_m is None else float(stroke_m),
                         velocity_m_s=None if velocity_m_s is None else float(velocity_m_s))
    if output is not None:
        folder = os.fspath(output)
        if not os.path.isdir(folder):
            raise UsageError(f"export_c: output: '{folder}' is not a folder (create it first)")
        for name, text in (("dampbench_model.h", out["header"]), ("dampbench_model.c", out["source"])):
            with open(os.path.join(folder, name), "w", encoding="utf-8") as f:
                f.write(text)
    return out
