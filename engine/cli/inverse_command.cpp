#include "engine/cli/inverse_command.hpp"

#include <iostream>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "engine/common/error.hpp"
#include "engine/common/text_file.hpp"
#include "engine/fit/fit.hpp"

namespace dampbench::cli {

void add_inverse_options(CLI::App* c, InverseOptions& o) {
  add_model_by_name_options(c, o.damper);
  c->add_option("--data", o.data.path, "record of the motion and the desired force: t, x (v, a) and F")->required();
  add_data_options(c, o.data);
  c->add_option("--range", o.range, "the commanded variable and its range, e.g. I=0:1")->required();
  c->add_option("--law", o.law, "inverse (default: the command whose force is the desired one) or on-off");
  c->add_option("--substeps", o.substeps, "the model's fixed RK4 sub-steps per sample interval (default 4)");
  c->add_option("-o,--output", o.output, "CSV of t, the command, F_desired, F_model and reachable (1/0)");
  c->add_option("--format", o.format, "md or json on stdout (default md)");
}

namespace {

std::string summary_markdown(const InverseRun& r) {
  const auto& x = r.result;
  std::string s = fmt::format("# Inverse of {} on {}: {} in [{}, {}], {}\n\n", r.model.model.model->id(), r.record.name,
                              r.settings.variable, r.settings.low, r.settings.high,
                              r.settings.law == control::InverseLaw::on_off ? "on/off rule" : "inverse model");
  s += "| samples | reachable | at low | at high | tracking error (reachable) |\n|---:|---:|---:|---:|---:|\n";
  s += fmt::format("| {} | {:.1f} % | {:.1f} % | {:.1f} % | {:.3g} % |\n", r.record.size(), 100 * x.share_reachable,
                   100 * x.share_at_low, 100 * x.share_at_high, 100 * x.tracking_error);
  return s;
}

nlohmann::ordered_json summary_json(const InverseRun& r) {
  const auto& x = r.result;
  return {{"model", r.model.model.model->id()}, {"record", r.record.name}, {"variable", r.settings.variable},
          {"low", r.settings.low}, {"high", r.settings.high},
          {"law", r.settings.law == control::InverseLaw::on_off ? "on-off" : "inverse"},
          {"samples", r.record.size()}, {"share_reachable", x.share_reachable}, {"share_at_low", x.share_at_low},
          {"share_at_high", x.share_at_high}, {"tracking_error", x.tracking_error}};
}

}  // namespace

InverseRun run_inverse(const InverseOptions& o) {
  check_format(o.format);
  check_output_folder("-o", o.output);
  if (o.law != "inverse" && o.law != "on-off")
    throw InputError(fmt::format("--law: expected inverse or on-off, got '{}'", o.law));
  InverseRun r;
  const CommandRange range = parse_command_range(o.range, "--range");
  r.settings = {range.variable, range.low, range.high};
  r.settings.law = o.law == "on-off" ? control::InverseLaw::on_off : control::InverseLaw::inverse;
  r.settings.substeps = o.substeps;
  r.model = load_named_model(o.damper, "inverse");
  r.record = o.record ? *o.record : load_record(o.data, true);
  if (o.record && !o.data.set.empty()) set_operating(r.record, o.data.set);
  control::check_commanded_variable(*r.model.model.model, r.settings.variable, "inverse");
  Signals signals = prepare_signals(r.record);
  signals.operating_refused.erase(r.settings.variable);  // the command replaces any column of it
  signals.operating_signals.erase(r.settings.variable);
  signals.law_variables[r.settings.variable] = r.settings.low;  // set at every step; present for the check below
  check_record(*r.model.model.model, signals);
  r.result = control::inverse_command(*r.model.model.model, r.model.params, signals, r.settings);
  return r;
}

int inverse_command(const InverseOptions& o) {
  const InverseRun r = run_inverse(o);
  if (!o.output.empty()) {
    std::string csv = fmt::format("t,{},F_desired,F_model,reachable\n", r.settings.variable);
    for (std::size_t k = 0; k < r.record.size(); ++k)
      csv += fmt::format("{:.17g},{:.17g},{:.17g},{:.17g},{}\n", r.record.t_s[k], r.result.command[k], r.record.F_N[k],
                         r.result.force_N[k], r.result.reachable[k] ? 1 : 0);
    write_text_file(o.output, csv);
  }
  std::cout << (o.format == "json" ? exact_json_text(summary_json(r)) + "\n" : summary_markdown(r));
  return 0;
}

}  // namespace dampbench::cli
