#include "engine/cli/export_command.hpp"

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <numbers>
#include <optional>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/common/text_file.hpp"
#include "engine/export/c_export.hpp"
#include "engine/export/fixed_step_check.hpp"
#include "engine/fit/fitted_range.hpp"
#include "engine/model/law_model.hpp"

namespace dampbench::cli {

void add_export_options(CLI::App* c, ExportOptions& o) {
  add_model_by_name_options(c, o.model);
  c->add_option("--lang", o.lang, "c (default; C99, no dependency but libm)");
  c->add_option("--substeps", o.substeps, "fixed RK4 sub-steps per step, as simulate --fixed-step (default 4)");
  c->add_option("--stroke-m", o.stroke_m,
                "peak-to-peak stroke [m] of the motion the step size is checked on (default: the fitted records')");
  c->add_option("--velocity-m-s", o.velocity_m_s,
                "peak |v| [m/s] of that motion (default: the fitted records')");
  c->add_option("-o,--output", o.output, "folder for dampbench_model.h and dampbench_model.c")->required();
}

namespace {

/// A record's stroke and peak velocity: its "motion" key, or for a file written before it a sinusoid's from the
/// record's stated amp [m] and vamp [m/s] (or 2π·amp·freq).
std::pair<double, double> record_motion(const ModelFileRecord& r) {
  if (r.displacement_ptp_m > 0) return {r.displacement_ptp_m, r.velocity_max_abs_m_s};
  const auto value = [&](const char* name) {
    return r.operating.contains(name) ? r.operating.at(name).at("value").get<double>() : 0.0;
  };
  const double amp = value("amp"), vamp = value("vamp") > 0 ? value("vamp") : 2 * std::numbers::pi * amp * value("freq");
  return {2 * amp, vamp};
}

/// The records' operating values as FittedRange reads them, a column that varied over a record as two points, its
/// ends (the record's value is then the column's mean; the loader's source text holds the ends).
std::vector<std::map<std::string, double>> fitted_points(const ModelFile& file) {
  std::vector<std::map<std::string, double>> points;
  for (const ModelFileRecord& r : file.records) {
    std::map<std::string, double> low, high;
    for (const auto& [name, entry] : r.operating.items()) {
      double lo = entry.at("value").get<double>(), hi = lo, from = 0, to = 0;
      if (std::sscanf(entry.at("source").get<std::string>().c_str(), "column varying from %lf to %lf", &from, &to) == 2)
        lo = from, hi = to;
      low[name] = lo;
      high[name] = hi;
    }
    points.push_back(std::move(low));
    points.push_back(std::move(high));
  }
  return points;
}

/// Every combination of `points` values evenly spread over each range (2: the ends).
std::vector<std::map<std::string, double>> grid(const std::vector<std::pair<std::string, std::pair<double, double>>>& ranges,
                                               int points) {
  std::vector<std::map<std::string, double>> out{{}};
  for (const auto& [name, range] : ranges) {
    std::vector<std::map<std::string, double>> next;
    const int n = range.first == range.second ? 1 : points;
    for (const auto& point : out)
      for (int i = 0; i < n; ++i) {
        auto p = point;
        p[name] = n == 1 ? range.first : range.first + (range.second - range.first) * i / (n - 1);
        next.push_back(std::move(p));
      }
    out = std::move(next);
  }
  return out;
}

/// The head comment's step-size lines: the check on the fitted motion, or why there is none.
std::string step_statement(const ExportOptions& o, const LoadedModel& loaded, exporting::FixedStepCheck& check) {
  check.has_states = exporting::steps_states(*loaded.model.model);
  if (!check.has_states) return exporting::fixed_step_statement(check, o.substeps);
  exporting::CheckedMotion motion;
  for (const ModelFileRecord& r : loaded.file.records) {
    const auto [stroke, velocity] = record_motion(r);
    motion.stroke_m = std::max(motion.stroke_m, stroke);
    motion.velocity_max_abs_m_s = std::max(motion.velocity_max_abs_m_s, velocity);
  }
  if (o.stroke_m) motion.stroke_m = *o.stroke_m;
  if (o.velocity_m_s) motion.velocity_max_abs_m_s = *o.velocity_m_s;
  const FittedRange fitted(*loaded.model.model, fitted_points(loaded.file));
  std::vector<std::pair<std::string, std::pair<double, double>>> ranges;  // in the laws' order of variables
  if (const auto* law = dynamic_cast<const LawModel*>(loaded.model.model))
    for (const std::string& name : law->law_variables()) {
      const auto range = fitted.ranges().find(name);
      if (range == fitted.ranges().end())
        return " * Step size: not checked (the law variables' fitted range is unknown: export from a model file whose\n"
               " * records state them).\n";
      ranges.push_back(*range);
    }
  motion.variables = grid(ranges, 2);
  motion.probes = grid(ranges, ranges.size() > 2 ? 5 : 9);
  if (!(motion.stroke_m > 0) || !(motion.velocity_max_abs_m_s > 0))
    return " * Step size: not checked (no motion known: export from a model file, or give --stroke-m and\n"
           " * --velocity-m-s).\n";
  check = exporting::check_fixed_step(*loaded.model.model, loaded.params, o.substeps, motion);
  return exporting::fixed_step_statement(check, o.substeps);
}

}  // namespace

ExportedModel run_export(const ExportOptions& o) {
  if (o.lang != "c") throw InputError(fmt::format("--lang: expected c, got '{}'", o.lang));
  if (o.substeps < 1 || o.substeps > exporting::kMaxExportSubsteps)
    throw InputError(fmt::format("--substeps: expected a whole number from 1 to {}, got {}", exporting::kMaxExportSubsteps,
                                 o.substeps));
  for (const auto& [option, value] : {std::pair{"--stroke-m", o.stroke_m}, std::pair{"--velocity-m-s", o.velocity_m_s}})
    if (value && !(std::isfinite(*value) && *value > 0))
      throw InputError(fmt::format("{}: expected a finite number above 0, got {}", option, *value));
  const LoadedModel loaded = load_named_model(o.model, "export");
  const std::string description =
      o.model.model_file.empty() ? "From the command line's parameters."
                                 : fmt::format("From {} (metric {} {:.6g} on the fitted records).", o.model.model_file,
                                               loaded.file.metric, loaded.file.fitted_value);
  // The exporter's refusal comes before the check, which would step a model it does not cover.
  exporting::require_exportable(*loaded.model.model);
  ExportedModel out;
  out.model_id = std::string(loaded.model.model->id());
  const std::string statement = step_statement(o, loaded, out.check);
  out.c = exporting::export_c(*loaded.model.model, loaded.params, o.substeps, description, statement);
  return out;
}

int export_command(const ExportOptions& o) {
  if (!std::filesystem::is_directory(o.output))
    throw InputError(fmt::format("-o: '{}' is not a folder (create it first)", o.output));
  // Both files are made before either is written, so a model the exporter refuses leaves no file behind.
  const ExportedModel e = run_export(o);
  const std::filesystem::path dir(o.output);
  write_text_file((dir / "dampbench_model.h").string(), e.c.header);
  write_text_file((dir / "dampbench_model.c").string(), e.c.source);
  std::cout << fmt::format("wrote {} and {} ({}, {} RK4 sub-steps per step)\n", (dir / "dampbench_model.h").string(),
                           (dir / "dampbench_model.c").string(), e.model_id, o.substeps);
  if (!e.check.has_states) std::cout << "step size: no states, any dt\n";
  else if (e.check.dt_max_s > 0)
    std::cout << fmt::format("step size: checked stable for dt <= {} s on {:.6g} m stroke, {:.6g} m/s peak velocity\n",
                             exporting::printed_step(e.check), e.check.motion.stroke_m, e.check.motion.velocity_max_abs_m_s);
  else if (e.check.dt_tried_last_s > 0)
    std::cout << fmt::format("step size: NOT stable down to dt = {:.3g} s: raise --substeps\n", e.check.dt_tried_last_s);
  else
    std::cout << "step size: not checked (see the head comment)\n";
  return 0;
}

}  // namespace dampbench::cli
