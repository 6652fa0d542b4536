"""Records: a test record loaded from a file with the command line's loader options, or made from numpy arrays."""
import os

import numpy as np

from dampbench import _core
from dampbench._core import DataError, Record

#: Loader options shared by load_record, record and fit (the command line's --units, --columns, --transform,
#: --average-cycles, --conditions and --set).
LOADER_OPTIONS = ("units", "columns", "transform", "average_cycles", "conditions", "set")


def key_values(value, what):
    """'a=1,b=2' from a dict {a: 1, b: 2} (numbers as repr, which reads back to the same double), or a str as is."""
    if value is None:
        return ""
    if isinstance(value, str):
        return value
    if isinstance(value, dict):
        return ",".join(f"{k}={_text(v)}" for k, v in value.items())
    raise _core.UsageError(f"{what}: expected a dict or a 'name=value,...' string, got {type(value).__name__}")


def _text(value):
    if isinstance(value, (list, tuple, np.ndarray)):  # one value per record of a file of several
        return ",".join(_text(v) for v in value)
    if isinstance(value, (float, np.floating)):
        return repr(float(value))
    return str(value)


def loader_args(units=None, columns=None, transform=None, average_cycles=None, conditions=None, set=None):
    """The loader options as the strings the engine reads, in LOADER_OPTIONS order."""
    if isinstance(columns, dict):  # {"t": "time", "x": "data[:,0]"}: channels of a .mat file or a rig export
        columns = ",".join(f"{k}={v}" for k, v in columns.items())
    elif columns is not None and not isinstance(columns, str):
        columns = ",".join(columns)
    return [key_values(units, "units"), columns or "", transform or "", key_values(average_cycles, "average_cycles"),
            conditions or "", key_values(set, "set")]


def load_record(path, *, require_force=True, units=None, columns=None, transform=None, average_cycles=None,
                conditions=None, set=None):
    """Loads a record file (CSV or whitespace-separated) as `dampbench fit --data` does.

    units: {"x": "mm", "F": "kN"} or "x=mm,F=kN"; columns: ["t", "x", "F"] for a file without a header;
    transform: "slider-crank"; average_cycles: {"cycles": 10, "drop": 3}; conditions: "utfsm" (operating
    variables from the file name); set: {"I": 0.5} (operating variables). Raises DataError naming the file, line
    and column of what is wrong.
    """
    return _core.load_record(os.fspath(path), require_force,
                             *loader_args(units, columns, transform, average_cycles, conditions, set))


def load_records(path, *, require_force=True, units=None, columns=None, transform=None, average_cycles=None,
                 conditions=None, set=None, skip_header=None, scale=None, split=None, smooth=None, remove_mean=None,
                 whole_cycles=False):
    """The records of one file as `dampbench fit --data` reads them: a list, several for a MATLAB matrix with one
    force column per test (columns={"t": "time", "x": "data[:,0]", "F": "data[:,1:6]"}) or a rig export split into
    its tests (split="events": between DAQ Pause and Resume; "nan": between rows of NaN), named "<stem>#k".

    The options of load_record, and: skip_header (lines before a text export's column names; default: a
    "Header Size: N" block is detected), scale ({"x": 10e-3, "F": 980.665}: gains to SI, before units), set with
    one value per record ({"I": [0, 0.25, 0.5, 0.75, 1]}), smooth (centred moving average of x and F over N
    samples), remove_mean (["x", "F"]), whole_cycles (trim to whole cycles of x). Raises DataError naming the file.
    """
    if remove_mean is not None and not isinstance(remove_mean, str):
        remove_mean = ",".join(remove_mean)
    return _core.load_records(os.fspath(path), require_force,
                              *loader_args(units, columns, transform, average_cycles, conditions, set),
                              -1 if skip_header is None else int(skip_header), key_values(scale, "scale"), split or "",
                              int(smooth or 0), remove_mean or "", bool(whole_cycles))


def _column(name, values):
    array = np.asarray(values)
    if array.dtype.kind not in "fiu":
        raise DataError(f"{name}: expected an array of real numbers, got dtype {array.dtype}")
    if array.ndim != 1:
        raise DataError(f"{name}: expected a 1-D array, got shape {array.shape}")
    return array.astype(np.float64, copy=False)


def record(t, x, F=None, *, v=None, a=None, I=None, V=None, phi=None, name="record", require_force=None,
           transform=None, average_cycles=None, conditions=None, set=None):
    """A record from numpy arrays in SI units: time t [s] (strictly increasing), displacement x [m], force F [N],
    optionally velocity v [m/s] and acceleration a [m/s^2] (else differentiated as for a file), and the operating
    variables I [A], V [V], phi [deg] as numbers or arrays, as a file's column: constant within 5 % (its mean), or a
    command that varies over the test, which laws follow sample by sample (Record.varying). set={"amp": 0.01}
    gives any operating variable. `name` names the record in tables and keys its runs: a record made from a file's
    columns, named by the file's stem, fits to the same bits as the file. Raises DataError for NaN or infinite
    values, a time that does not increase, or arrays of different lengths.
    """
    columns = {"t": _column("t", t), "x": _column("x", x)}
    for key, values in (("F", F), ("v", v), ("a", a)):
        if values is not None:
            columns[key] = _column(key, values)
    stated = {}
    for key, values in (("I", I), ("V", V), ("phi", phi)):
        if values is None:
            continue
        if np.ndim(values) == 0:
            stated[key] = float(values)
        else:
            columns[key] = _column(key, values)
    given = key_values(set, "set")
    if stated:
        given = ",".join(filter(None, [key_values(stated, "set"), given]))
    force = F is not None if require_force is None else require_force
    return _core.record_from_columns(columns, name, force, transform or "", key_values(average_cycles, "average_cycles"),
                                     conditions or "", given)


def as_records(records, loader):
    """A list of Records from one or a list of Records and paths (paths read with the loader options)."""
    if isinstance(records, (Record, str, os.PathLike)):
        records = [records]
    out = []
    for r in records:
        if isinstance(r, Record):
            out.append(r)
        elif isinstance(r, (str, os.PathLike)):
            out.append(load_record(r, **loader))
        else:
            raise _core.UsageError(f"records: expected a Record or a file path, got {type(r).__name__}")
    return out
