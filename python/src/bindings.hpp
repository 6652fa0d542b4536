#pragma once
// What the binding files of the Python module share: each one adds its functions to the module, and long calls
// run through run_released, which frees the interpreter while the engine works and turns Ctrl-C into a stop.
#include <atomic>
#include <functional>
#include <optional>
#include <string>

#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "engine/record/record_options.hpp"

namespace dampbench::python {

namespace py = pybind11;

void bind_errors(py::module_& m);    // errors.cpp: the exception classes, one per exit-code class
void bind_records(py::module_& m);   // records.cpp: Record, load_record, record from arrays
void bind_fit(py::module_& m);       // fit.cpp: fit
void bind_simulate(py::module_& m);  // simulate.cpp: simulate, evaluate, models, optimizers
void bind_store(py::module_& m);     // store.cpp: a store's runs, groups and tables; report
void bind_control(py::module_& m);   // control.cpp: structure, export_c

/// A copy of `values` as a 1-D numpy array.
inline py::array_t<double> to_numpy(const std::vector<double>& values) {
  return py::array_t<double>(static_cast<py::ssize_t>(values.size()), values.data());
}

/// The loader options of a record file, from the six strings python/dampbench/records.py's loader_args makes
/// (units, columns, transform, average_cycles, conditions, set).
inline RecordOptions loader_options(const std::string& path, const std::vector<std::string>& loader) {
  RecordOptions o;
  o.path = path;
  o.units = loader.at(0);
  o.columns = loader.at(1);
  o.transform = loader.at(2);
  o.average = loader.at(3);
  o.conditions = loader.at(4);
  o.set = loader.at(5);
  return o;
}

/// Where the engine works for one call: at most `threads` worker threads (none: every core) and the vector level
/// `isa` (none: the one already chosen), restored afterwards.
struct EngineLimits {
  std::optional<int> threads;
  std::optional<std::string> isa;
};

/// Runs `work` on a worker thread with the interpreter released, under `limits`. Every 50 ms the calling thread
/// checks for Ctrl-C (Python's signal handlers run there); on one it sets `stop`, which the engine checks each
/// generation, waits for the work to end, and raises KeyboardInterrupt. An exception of the work is re-thrown
/// here, with the interpreter held, for the translators of errors.cpp.
void run_released(const std::function<void()>& work, std::atomic<bool>& stop, const EngineLimits& limits);

}  // namespace dampbench::python
