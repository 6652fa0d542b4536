// errors: the metric of each model's best run on each dataset, fitted and predicted.
#include <map>
#include <set>

#include <fmt/format.h>

#include "engine/sweep/tables/kinds.hpp"

namespace dampbench::sweep::tables {
void errors_tables(const Context& c, std::vector<Table>& out) {
  // One table per optimized metric; a column per series (model, and optimizer or split when they vary).
  std::map<int, std::vector<Series>> by_metric;
  for (const auto& s : c.series()) by_metric[static_cast<int>(s.metric)].push_back(s);
  for (const auto& [key, list] : by_metric) {
    const Metric optimized = static_cast<Metric>(key);
    const Metric shown = c.t.metric.empty() ? optimized : parse_metric(c.t.metric);
    const int m = static_cast<int>(shown);
    std::vector<std::string> cols{"Dataset"};
    for (const auto& s : list) {
      std::string col = series_column(c, s);
      if (c.many_splits && !c.split_name(s.split).empty()) col += " [" + c.split_name(s.split) + "]";
      cols.push_back(std::move(col));
    }
    Table r = c.table("errors" + (c.many_metrics ? file_stem("_" + std::string(metric_name(optimized))) : std::string()),
                        fmt::format("{} of each model's best run per dataset{}", metric_name(shown),
                                    shown != optimized ? fmt::format(" (runs optimized {})", metric_name(optimized)) : ""),
                        cols);
    const bool fits = c.t.role != "predict", predictions = c.t.role != "fit";
    const std::set<int> datasets = series_datasets(c, list, fits, predictions);
    std::vector<double> sums(list.size(), 0);
    std::vector<int> counts(list.size(), 0);
    bool averaged = false, predicted_any = false, unconverged_any = false;
    for (int d : datasets) {
      if (!c.t.where.everything() && !c.matches(c.t.where, d)) continue;
      std::vector<Cell> row{txt(c.dataset(d).name)};
      bool any = false;
      for (std::size_t i = 0; i < list.size(); ++i) {
        const SeriesValue v = series_value(c, list[i], d, m, fits, predictions);
        const std::optional<double>& value = v.value;
        const bool predicted = v.predicted, unconverged = v.unconverged;
        averaged |= v.averaged;
        if (!value) {
          row.push_back(none());
          continue;
        }
        any = true;
        predicted_any |= predicted;
        row.push_back({format_number(*value) + (predicted ? "*" : "") + (unconverged ? kUnconvergedMark : ""), *value});
        unconverged_any |= unconverged;
        sums[i] += *value;
        ++counts[i];
      }
      if (any) r.rows.push_back(std::move(row));
    }
    if (r.rows.size() > 1) {
      std::vector<Cell> row{txt("mean")};
      for (std::size_t i = 0; i < list.size(); ++i) row.push_back(counts[i] ? num(sums[i] / counts[i]) : none());
      r.rows.push_back(std::move(row));
    }
    std::string note;
    if (predicted_any) note = "* predicted: the dataset was not fitted, the fit of other conditions was evaluated on it.";
    if (averaged) note += std::string(note.empty() ? "" : " ") + "A dataset predicted by several fits shows the mean over them.";
    if (unconverged_any) note += std::string(note.empty() ? "" : " ") + kUnconvergedNote;
    r.note = note;
    out.push_back(std::move(r));
  }
}

}  // namespace dampbench::sweep::tables
