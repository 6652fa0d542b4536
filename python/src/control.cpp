// The identified damper outside the fit: `structure` (the damper in a building under an earthquake) and `export_c`
// (the model as a C99 pair), through the commands' own functions, as the command line runs them.
#include <atomic>
#include <string>

#include <Eigen/Core>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "engine/cli/export_command.hpp"
#include "engine/cli/structure_command.hpp"
#include "python/src/bindings.hpp"

namespace dampbench::python {

namespace {

/// Rows × columns as a NumPy array (a copy: the response goes away with the call).
py::array_t<double> matrix_to_numpy(const Eigen::MatrixXd& m) {
  py::array_t<double> out({static_cast<py::ssize_t>(m.rows()), static_cast<py::ssize_t>(m.cols())});
  auto view = out.mutable_unchecked<2>();
  for (Eigen::Index r = 0; r < m.rows(); ++r)
    for (Eigen::Index c = 0; c < m.cols(); ++c) view(r, c) = m(r, c);
  return out;
}

py::array_t<double> vector_to_numpy(const Eigen::VectorXd& v) {
  return to_numpy(std::vector<double>(v.data(), v.data() + v.size()));
}

py::dict response_dict(const structure::SeismicResponse& r) {
  py::dict out;
  out["t"] = to_numpy(r.t_s);
  out["ag"] = to_numpy(r.ag_m_s2);
  out["u"] = matrix_to_numpy(r.u_m);
  out["drift"] = matrix_to_numpy(r.drift_m);
  out["abs_acc"] = matrix_to_numpy(r.abs_acc_m_s2);
  out["force"] = to_numpy(r.force_N);
  out["command"] = to_numpy(r.command);
  out["peak_u"] = vector_to_numpy(r.peak_u_m);
  out["peak_drift"] = vector_to_numpy(r.peak_drift_m);
  out["peak_abs_acc"] = vector_to_numpy(r.peak_abs_acc_m_s2);
  out["peak_force"] = r.peak_force_N;
  out["high_share"] = r.high_share;
  py::dict energy;
  energy["input"] = r.energy.input_J;
  energy["structural"] = r.energy.structural_J;
  energy["damper"] = r.energy.damper_J;
  energy["kinetic"] = r.energy.kinetic_J;
  energy["strain"] = r.energy.strain_J;
  energy["balance_error"] = r.energy.balance_error;
  out["energy"] = energy;
  out["steps"] = r.steps;
  out["unconverged_steps"] = r.unconverged_steps;
  return out;
}

}  // namespace

void bind_control(py::module_& m) {
  m.def(
      "structure",
      [](const std::string& model, const std::string& fixture, const std::string& laws, const std::string& params,
         const std::string& model_file, const std::string& building, const std::string& ground, double scale,
         double step_s, int substeps, const std::string& set, const std::string& control, const std::string& command,
         double lqr_r, int output_every) {
        cli::StructureOptions o;
        o.damper = {model_file, model, fixture, laws, params};
        o.building = building;
        o.ground = ground;
        o.scale = scale;
        o.step_s = step_s;
        o.damper_substeps = substeps;
        o.set = set;
        o.control = control;
        o.command = command;
        o.lqr_r = lqr_r;
        o.output_every = output_every;
        std::atomic<bool> stop{false};  // a run goes to its end: Ctrl-C is raised after it
        cli::StructureResult r;
        run_released([&] { r = cli::run_structure(o); }, stop, {std::nullopt, std::nullopt});
        py::dict out;
        out["damper"] = r.damper_id;
        out["bare"] = response_dict(r.bare);
        out["damped"] = response_dict(r.damped);
        out["lqr_residual"] = r.lqr_residual;
        return out;
      },
      py::arg("model"), py::arg("fixture"), py::arg("laws"), py::arg("params"), py::arg("model_file"),
      py::arg("building"), py::arg("ground"), py::arg("scale"), py::arg("step_s"), py::arg("substeps"), py::arg("set"),
      py::arg("control"), py::arg("command"), py::arg("lqr_r"), py::arg("output_every"));
  m.def(
      "export_c",
      [](const std::string& model, const std::string& fixture, const std::string& laws, const std::string& params,
         const std::string& model_file, int substeps, std::optional<double> stroke_m, std::optional<double> velocity_m_s) {
        cli::ExportOptions o;
        o.model = {model_file, model, fixture, laws, params};
        o.substeps = substeps;
        o.stroke_m = stroke_m;
        o.velocity_m_s = velocity_m_s;
        const cli::ExportedModel e = cli::run_export(o);
        py::dict out;
        out["header"] = e.c.header;
        out["source"] = e.c.source;
        out["model"] = e.model_id;
        // As the header prints it (rounded down); 0: not stable or not checked.
        out["dt_max_s"] = !e.check.has_states ? INFINITY : e.check.dt_max_s > 0 ? std::stod(exporting::printed_step(e.check)) : 0.0;
        return out;
      },
      py::arg("model"), py::arg("fixture"), py::arg("laws"), py::arg("params"), py::arg("model_file"),
      py::arg("substeps"), py::arg("stroke_m") = py::none(), py::arg("velocity_m_s") = py::none());
}

}  // namespace dampbench::python
