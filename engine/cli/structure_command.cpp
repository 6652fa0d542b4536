#include "engine/cli/structure_command.hpp"

#include <cmath>
#include <filesystem>
#include <iostream>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "engine/common/error.hpp"
#include "engine/common/key_values.hpp"
#include "engine/common/text_file.hpp"
#include "engine/cli/structure_plot.hpp"
#include "engine/structure/lqr.hpp"

namespace dampbench::cli {

void add_structure_options(CLI::App* c, StructureOptions& o) {
  add_model_by_name_options(c, o.damper);
  c->add_option("--building", o.building, "building TOML file (datasets/buildings/utfsm_case_1.toml, ...)")->required();
  c->add_option("--ground", o.ground, "ground acceleration CSV with columns t [s] and ag [m/s^2]")->required();
  c->add_option("--scale", o.scale, "factor on the ground acceleration (default 1)");
  c->add_option("--step", o.step_s, "the building's time step [s] (default 1/4096, the UTFSM study's control rate)");
  c->add_option("--damper-substeps", o.damper_substeps, "the damper's fixed RK4 sub-steps per building step (default 4)");
  c->add_option("--set", o.set, "the damper's operating variables, e.g. I=1 (passive; on-off sets the commanded one)");
  c->add_option("--control", o.control, "passive (default) or on-off: the clipped-optimal rule of an LQR gain");
  c->add_option("--command", o.command, "on-off: the commanded variable and its range, e.g. I=0:1");
  c->add_option("--lqr-r", o.lqr_r, "on-off: R of the LQR cost (Q weighs twice the building's energy) [J/N^2] (default 1e-6)");
  c->add_option("--output-every", o.output_every, "building steps between rows of structure.csv (default 8)");
  c->add_option("-o,--output", o.output, "folder for structure.csv (time histories), structure.svg (their plot), structure.json and structure.md");
  c->add_option("--format", o.format, "md or json on stdout (default md)");
}

namespace {

double reduction_percent(double bare, double damped) { return bare > 0 ? 100.0 * (1.0 - damped / bare) : std::nan(""); }

nlohmann::ordered_json response_json(const structure::SeismicResponse& r) {
  nlohmann::ordered_json j;
  j["peak_displacement_m"] = std::vector<double>(r.peak_u_m.begin(), r.peak_u_m.end());
  j["peak_drift_m"] = std::vector<double>(r.peak_drift_m.begin(), r.peak_drift_m.end());
  j["peak_absolute_acceleration_m_s2"] = std::vector<double>(r.peak_abs_acc_m_s2.begin(), r.peak_abs_acc_m_s2.end());
  j["peak_damper_force_N"] = json_number(r.peak_force_N);
  j["energy_J"] = {{"input", r.energy.input_J}, {"structural_damping", r.energy.structural_J},
                   {"damper", r.energy.damper_J}, {"kinetic", r.energy.kinetic_J}, {"strain", r.energy.strain_J}};
  j["energy_balance_error"] = json_number(r.energy.balance_error);
  j["steps"] = r.steps;
  j["unconverged_steps"] = r.unconverged_steps;
  j["high_command_share"] = json_number(r.high_share);
  return j;
}

nlohmann::ordered_json result_json(const StructureOptions& o, const StructureResult& r) {
  nlohmann::ordered_json j;
  j["building"] = r.run.building.name;
  j["ground"] = {{"file", o.ground}, {"scale", o.scale}, {"peak_m_s2", [&] {
                    double peak = 0;
                    for (double a : r.run.ground.ag_m_s2) peak = std::max(peak, std::fabs(a));
                    return peak;
                  }()}};
  j["damper"] = {{"model", r.damper_id}, {"storey", r.run.building.damper_storey},
                 {"control", o.control}, {"substeps", o.damper_substeps}};
  if (r.run.control)
    j["damper"]["command"] = {{"variable", r.run.control->variable}, {"low", r.run.control->low},
                              {"high", r.run.control->high}, {"lqr_r", o.lqr_r}, {"riccati_residual", r.lqr_residual}};
  else
    j["damper"]["variables"] = r.run.damper->variables;
  j["step_s"] = r.run.step_s;
  j["bare"] = response_json(r.bare);
  j["damped"] = response_json(r.damped);
  return j;
}

std::string result_markdown(const StructureOptions& o, const StructureResult& r) {
  std::string s = fmt::format("# {} under {} (x {}), damper {} at storey {}, {}\n\n", r.run.building.name,
                              r.run.ground.name, o.scale, r.damper_id, r.run.building.damper_storey,
                              r.run.control ? fmt::format("on/off in {} {}:{}", r.run.control->variable,
                                                          r.run.control->low, r.run.control->high)
                                            : "passive");
  s += "| storey | peak drift bare [mm] | with damper [mm] | reduction | peak abs. acc. bare [m/s2] | with damper [m/s2] | reduction |\n";
  s += "|---:|---:|---:|---:|---:|---:|---:|\n";
  for (int i = 0; i < r.run.building.storeys(); ++i)
    s += fmt::format("| {} | {:.3f} | {:.3f} | {:.1f} % | {:.3f} | {:.3f} | {:.1f} % |\n", i + 1,
                     1e3 * r.bare.peak_drift_m[i], 1e3 * r.damped.peak_drift_m[i],
                     reduction_percent(r.bare.peak_drift_m[i], r.damped.peak_drift_m[i]), r.bare.peak_abs_acc_m_s2[i],
                     r.damped.peak_abs_acc_m_s2[i],
                     reduction_percent(r.bare.peak_abs_acc_m_s2[i], r.damped.peak_abs_acc_m_s2[i]));
  const auto& e = r.damped.energy;
  s += fmt::format("\nPeak damper force {:.1f} N. Energy with the damper: input {:.4g} J = structural damping {:.4g} + "
                   "damper {:.4g} + kinetic {:.4g} + strain {:.4g} (balance error {:.2g}).\n",
                   r.damped.peak_force_N, e.input_J, e.structural_J, e.damper_J, e.kinetic_J, e.strain_J, e.balance_error);
  if (r.run.control) s += fmt::format("High command on {:.1f} % of the steps.\n", 100.0 * r.damped.high_share);
  if (r.damped.unconverged_steps > 0)
    s += fmt::format("WARNING: the damper force did not converge on {} of {} steps.\n", r.damped.unconverged_steps,
                     r.damped.steps);
  return s;
}

std::string time_history_csv(const StructureResult& r) {
  const auto& d = r.damped;
  const int n = r.run.building.storeys();
  std::string s = "t,ag";
  for (const char* name : {"u", "drift", "abs_acc"})
    for (int i = 1; i <= n; ++i) s += fmt::format(",{}{}", name, i);
  s += ",F,command\n";
  for (std::size_t k = 0; k < d.t_s.size(); ++k) {
    const auto row = static_cast<Eigen::Index>(k);
    s += fmt::format("{:.17g},{:.17g}", d.t_s[k], d.ag_m_s2[k]);
    for (const auto* m : {&d.u_m, &d.drift_m, &d.abs_acc_m_s2})
      for (int i = 0; i < n; ++i) s += fmt::format(",{:.17g}", (*m)(row, i));
    s += fmt::format(",{:.17g},{:.17g}\n", d.force_N[k], d.command[k]);
  }
  return s;
}

}  // namespace

StructureResult run_structure(const StructureOptions& o) {
  check_format(o.format);
  if (!o.output.empty() && !std::filesystem::is_directory(o.output))
    throw InputError(fmt::format("-o: '{}' is not a folder (create it first)", o.output));
  if (o.control != "passive" && o.control != "on-off")
    throw InputError(fmt::format("--control: expected passive or on-off, got '{}'", o.control));
  if (o.control == "on-off" && o.command.empty())
    throw InputError("--control on-off: give the commanded variable and its range with --command, e.g. I=0:1");
  if (o.control == "passive" && !o.command.empty())
    throw InputError("--command: only with --control on-off (a passive damper takes its variables from --set)");
  StructureResult r;
  r.run.building = structure::read_building_file(o.building);
  r.run.ground = structure::read_ground_motion(o.ground, o.scale);
  r.run.step_s = o.step_s;
  r.run.output_every = o.output_every;
  r.damper_model = load_named_model(o.damper, "structure");
  structure::Damper damper{r.damper_model.model.model, r.damper_model.params, {}, o.damper_substeps};
  for (const auto& [name, value] : parse_key_values(o.set, "--set")) damper.variables[name] = parse_number(value, "--set " + name);
  r.damper_id = std::string(damper.model->id());
  if (o.control == "on-off") {
    const CommandRange command = parse_command_range(o.command, "--command");
    if (!(command.low <= command.high)) throw InputError(fmt::format("--command: expected LOW <= HIGH, got '{}'", o.command));
    structure::OnOffControl control{command.variable, command.low, command.high, {}};
    const structure::Modes modes = structure::modes_of(r.run.building);
    const auto gain = structure::lqr_gain(structure::state_space(r.run.building, modes),
                                          structure::energy_weight(r.run.building), o.lqr_r);
    control.gain = gain.G;
    r.lqr_residual = gain.riccati_residual;
    r.run.control = control;
  }
  r.bare = structure::simulate_seismic(r.run);
  r.run.damper = damper;
  try {
    r.damped = structure::simulate_seismic(r.run);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{} (the damper's operating variables come from --set, e.g. --set I=1)", e.what()));
  }
  return r;
}

int structure_command(const StructureOptions& o) {
  const StructureResult r = run_structure(o);
  const std::string md = result_markdown(o, r);
  const std::string json = exact_json_text(result_json(o, r));
  if (!o.output.empty()) {
    const std::filesystem::path dir(o.output);
    write_text_file((dir / "structure.csv").string(), time_history_csv(r));
    write_text_file((dir / "structure.json").string(), json);
    write_text_file((dir / "structure.md").string(), md);
    const std::string title = fmt::format("{} under {} (x {}), {}", r.run.building.name, r.run.ground.name, o.scale,
                                          r.run.control ? "on/off" : "passive");
    write_text_file((dir / "structure.svg").string(),
                    structure_svg(title, r.run.building.damper_storey, r.bare, r.damped,
                                  r.run.control ? r.run.control->variable : ""));
  }
  std::cout << (o.format == "json" ? json + "\n" : md);
  return 0;
}

}  // namespace dampbench::cli
