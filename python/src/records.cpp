// Records in Python: a Dataset (engine/record/dataset.hpp) loaded from a file with the command line's loader
// options, or made from numpy arrays with the same checks, derivatives and preparation as a file.
#include <map>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "engine/common/error.hpp"
#include "engine/record/csv_loader.hpp"
#include "engine/record/record_options.hpp"
#include "python/src/bindings.hpp"

namespace dampbench::python {

namespace {

/// The loader options of the command line (--units, --columns, --transform, --average-cycles, --conditions, --set).
RecordOptions record_options(const std::string& path, const std::string& units, const std::string& columns,
                             const std::string& transform, const std::string& average_cycles,
                             const std::string& conditions, const std::string& set) {
  return loader_options(path, {units, columns, transform, average_cycles, conditions, set});
}

}  // namespace

void bind_records(py::module_& m) {
  py::class_<Dataset>(m, "Record", "A test record in SI units: t, x, v, a, F and the operating variables.")
      .def_readonly("name", &Dataset::name, "label in tables (the file's stem for a file)")
      .def_readonly("source", &Dataset::source, "the file path, or 'arrays'")
      .def_property_readonly("t", [](const Dataset& d) { return to_numpy(d.t_s); }, "time [s]")
      .def_property_readonly("x", [](const Dataset& d) { return to_numpy(d.x_m); }, "displacement [m]")
      .def_property_readonly("v", [](const Dataset& d) { return to_numpy(d.v_m_s); }, "velocity [m/s]")
      .def_property_readonly("a", [](const Dataset& d) { return to_numpy(d.a_m_s2); }, "acceleration [m/s^2]")
      .def_property_readonly("F", [](const Dataset& d) { return to_numpy(d.F_N); }, "force [N] (empty: none)")
      .def_readonly("operating", &Dataset::operating, "operating variables (I [A], V [V], phi [deg], amp [m], freq [Hz])")
      .def_readonly("operating_source", &Dataset::operating_source, "where each operating variable comes from")
      .def_property_readonly(
          "varying",
          [](const Dataset& d) {
            py::dict out;
            for (const auto& [name, column] : d.operating_signals) out[py::str(name)] = to_numpy(column);
            return out;
          },
          "the operating variables that vary over the test, sample by sample (laws follow them)")
      .def("__len__", &Dataset::size)
      .def("__repr__", [](const Dataset& d) {
        std::string operating;
        for (const auto& [name, value] : d.operating) operating += fmt::format(", {}={:g}", name, value);
        return fmt::format("<dampbench.Record '{}': {} samples{}{}>", d.name, d.size(), d.has_force() ? ", with F" : "",
                           operating);
      });

  m.def(
      "load_record",
      [](const std::string& path, bool require_force, const std::string& units, const std::string& columns,
         const std::string& transform, const std::string& average_cycles, const std::string& conditions,
         const std::string& set) {
        return load_record(record_options(path, units, columns, transform, average_cycles, conditions, set),
                           require_force);
      },
      py::arg("path"), py::arg("require_force"), py::arg("units"), py::arg("columns"), py::arg("transform"),
      py::arg("average_cycles"), py::arg("conditions"), py::arg("set"));

  m.def(
      "load_records",
      [](const std::string& path, bool require_force, const std::string& units, const std::string& columns,
         const std::string& transform, const std::string& average_cycles, const std::string& conditions,
         const std::string& set, int skip_header, const std::string& scale, const std::string& split, int smooth,
         const std::string& remove_mean, bool whole_cycles) {
        RecordOptions o = record_options(path, units, columns, transform, average_cycles, conditions, set);
        o.skip_header = skip_header;
        o.scale = scale;
        o.split = split;
        o.smooth_samples = smooth;
        o.remove_mean = remove_mean;
        o.whole_cycles = whole_cycles;
        return load_records(o, require_force);
      },
      py::arg("path"), py::arg("require_force"), py::arg("units"), py::arg("columns"), py::arg("transform"),
      py::arg("average_cycles"), py::arg("conditions"), py::arg("set"), py::arg("skip_header"), py::arg("scale"),
      py::arg("split"), py::arg("smooth"), py::arg("remove_mean"), py::arg("whole_cycles"));

  m.def(
      "record_from_columns",
      [](const std::map<std::string, std::vector<double>>& columns, const std::string& name, bool require_force,
         const std::string& transform, const std::string& average_cycles, const std::string& conditions,
         const std::string& set) {
        return as_data_error([&] {
          CsvOptions options;
          options.require_force = require_force;
          return prepare_record(dataset_from_columns(columns, name, options),
                                record_options("", "", "", transform, average_cycles, conditions, set));
        });
      },
      py::arg("columns"), py::arg("name"), py::arg("require_force"), py::arg("transform"), py::arg("average_cycles"),
      py::arg("conditions"), py::arg("set"));
}

}  // namespace dampbench::python
