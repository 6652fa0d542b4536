#include "engine/sweep/store/verify_diff.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>

#include <fmt/format.h>

namespace dampbench::sweep {
namespace {

std::string bits(double v) { return fmt::format("0x{:016x} ({:.17g})", std::bit_cast<std::uint64_t>(v), v); }
bool same(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

/// The differences found so far, one line each.
struct Diff {
  std::vector<std::string> lines;
  void add(std::string line) { lines.push_back(std::move(line)); }
  /// A line when two doubles differ in any bit.
  void num(const std::string& what, double x, double y) {
    if (!same(x, y)) add(fmt::format("{}: stored {} vs recomputed {}", what, bits(x), bits(y)));
  }
};

void compare_run(const RunRecord& x, const RunRecord& y, const std::vector<std::string>& names, Diff& diff) {
  const std::string run = fmt::format("run {}", x.run);
  diff.num(run + " best_value", x.best_value, y.best_value);
  for (int m = 0; m < kMetricCount; ++m)
    diff.num(fmt::format("{} metric {}", run, metric_name(kAllMetrics[m])), x.metrics[m], y.metrics[m]);
  if (x.params.size() != y.params.size()) diff.add(run + ": parameter count differs");
  for (std::size_t j = 0; j < std::min(x.params.size(), y.params.size()); ++j)
    diff.num(fmt::format("{} params[{}]{}", run, j, j < names.size() ? " " + names[j] : ""), x.params[j], y.params[j]);
  if (x.evaluations != y.evaluations)
    diff.add(fmt::format("{} evaluations: stored {} vs recomputed {}", run, x.evaluations, y.evaluations));
  if (x.stop_reason != y.stop_reason) diff.add(fmt::format("{} stop reason: {} vs {}", run, x.stop_reason, y.stop_reason));
  if (x.at_local_optimum != y.at_local_optimum)
    diff.add(fmt::format("{} local optimum: {} vs {}", run, x.at_local_optimum, y.at_local_optimum));
  if (x.trace.size() != y.trace.size()) {
    diff.add(fmt::format("{} trace: stored {} points vs recomputed {}", run, x.trace.size(), y.trace.size()));
    return;
  }
  for (std::size_t k = 0; k < x.trace.size(); ++k) {
    if (x.trace[k].evaluations != y.trace[k].evaluations) diff.add(fmt::format("{} trace[{}] evaluations differ", run, k));
    diff.num(fmt::format("{} trace[{}]", run, k), x.trace[k].value, y.trace[k].value);
  }
}

void compare_dataset_metrics(const std::vector<DatasetMetricRecord>& a, const std::vector<DatasetMetricRecord>& b,
                             Diff& diff) {
  if (a.size() != b.size()) {
    diff.add("per-dataset metrics: count differs");
    return;
  }
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].dataset != b[i].dataset || a[i].predicted != b[i].predicted)
      diff.add(fmt::format("run {}: per-dataset metrics of other datasets or roles", a[i].run));
    for (int m = 0; m < kMetricCount; ++m)
      diff.num(fmt::format("run {} dataset {} metric {}", a[i].run, a[i].dataset, metric_name(kAllMetrics[m])),
               a[i].metrics[m], b[i].metrics[m]);
  }
}

void compare_sensitivity(const std::optional<SensitivityRecord>& a, const std::optional<SensitivityRecord>& b,
                         Diff& diff) {
  if (a.has_value() != b.has_value()) {
    diff.add("sensitivity: present in one only");
    return;
  }
  if (!a) return;
  if (a->S.size() != b->S.size() || a->SP.size() != b->SP.size()) {
    diff.add("sensitivity: size differs");
    return;
  }
  for (std::size_t j = 0; j < a->S.size(); ++j) {
    diff.num(fmt::format("sensitivity S[{}]", j), a->S[j], b->S[j]);
    diff.num(fmt::format("sensitivity SP[{}]", j), a->SP[j], b->SP[j]);
  }
}

void compare_identifiability(const std::optional<Identifiability>& a, const std::optional<Identifiability>& b,
                             const std::vector<std::string>& names, Diff& diff) {
  if (a.has_value() != b.has_value()) {
    diff.add("identifiability: present in one only");
    return;
  }
  if (!a) return;
  const auto &x = *a, &y = *b;
  if (x.std_error.size() != y.std_error.size() || x.correlation.size() != y.correlation.size()) {
    diff.add("identifiability: size differs");
    return;
  }
  for (std::size_t j = 0; j < x.std_error.size(); ++j) {
    const std::string name = j < names.size() ? " " + names[j] : "";
    diff.num(fmt::format("identifiability std_error[{}]{}", j, name), x.std_error[j], y.std_error[j]);
    diff.num(fmt::format("identifiability relative_error[{}]{}", j, name), x.relative_error[j], y.relative_error[j]);
    for (std::size_t k = 0; k < x.correlation[j].size() && k < y.correlation[j].size(); ++k)
      diff.num(fmt::format("identifiability correlation[{}][{}]", j, k), x.correlation[j][k], y.correlation[j][k]);
  }
  if (x.flags != y.flags) diff.add("identifiability: flags differ");
}

}  // namespace

void sort_dataset_metrics(std::vector<DatasetMetricRecord>& metrics) {
  std::stable_sort(metrics.begin(), metrics.end(), [](const DatasetMetricRecord& x, const DatasetMetricRecord& y) {
    return std::pair(x.run, x.dataset) < std::pair(y.run, y.dataset);
  });
}

std::vector<std::string> compare_records(const GroupRecord& stored, const GroupRecord& recomputed,
                                         const std::vector<std::string>& names) {
  // Per-dataset metrics compared in one order, whatever order each record lists them in.
  GroupRecord a = stored, b = recomputed;
  sort_dataset_metrics(a.dataset_metrics);
  sort_dataset_metrics(b.dataset_metrics);
  Diff diff;
  if (a.failed != b.failed)
    diff.add(fmt::format("status: stored {} vs recomputed {}", a.failed ? "failed" : "done", b.failed ? "failed" : "done"));
  if (a.message != b.message) diff.add(fmt::format("message: stored '{}' vs recomputed '{}'", a.message, b.message));
  if (a.task_key != b.task_key) diff.add("task key differs");
  if (a.laws != b.laws) diff.add(fmt::format("laws: stored '{}' vs recomputed '{}'", a.laws, b.laws));
  if (a.evaluations != b.evaluations)
    diff.add(fmt::format("evaluations: stored {} vs recomputed {}", a.evaluations, b.evaluations));
  diff.num("candidate_samples", a.candidate_samples, b.candidate_samples);
  if (a.run_results.size() != b.run_results.size()) {
    diff.add(fmt::format("runs: stored {} vs recomputed {}", a.run_results.size(), b.run_results.size()));
    return diff.lines;
  }
  for (std::size_t r = 0; r < a.run_results.size(); ++r) compare_run(a.run_results[r], b.run_results[r], names, diff);
  compare_dataset_metrics(a.dataset_metrics, b.dataset_metrics, diff);
  compare_sensitivity(a.sensitivity, b.sensitivity, diff);
  compare_identifiability(a.identifiability, b.identifiability, names, diff);
  return diff.lines;
}

}  // namespace dampbench::sweep
