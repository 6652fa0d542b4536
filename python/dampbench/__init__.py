"""dampbench from Python: fit, simulate and evaluate damper models on numpy arrays, and read sweep stores as
pandas tables. The engine is the command line's own (the same inputs, seed and vector level give the same bits);
docs/python.md shows it at work.

    import dampbench
    rec = dampbench.load_record("fvd_record.csv")
    result = dampbench.fit("fvd", rec, seed=1)
    result.params, result.converged, result.metrics
"""
from dampbench._core import (  # noqa: F401  (the exception classes, one per exit code of the command line)
    DataError,
    Error,
    InternalError,
    Record,
    StoreError,
    UsageError,
    build_flags,
    version,
)
from dampbench.records import load_record, load_records, record  # noqa: F401
from dampbench.fitting import FitResult, fit  # noqa: F401
from dampbench.simulation import evaluate, export_c, inverse, models, optimizers, simulate, structure  # noqa: F401
from dampbench.store import Store, report  # noqa: F401

__version__ = version
__all__ = [
    "DataError", "Error", "FitResult", "InternalError", "Record", "Store", "StoreError", "UsageError",
    "evaluate", "export_c", "fit", "inverse", "load_record", "load_records", "models", "optimizers", "record", "report",
    "simulate", "structure",
]
