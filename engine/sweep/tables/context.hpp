#pragma once
// What every table kind reads: the groups a table request selects from a store, cut into series (every group
// of one split, model, optimizer and optimized metric, ordered by fit set), with the names, labels and file
// stems that tell the series apart. Shared by the kinds (kinds.hpp); not part of the sweep's interface.
#include <algorithm>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "engine/common/statistics.hpp"
#include "engine/common/table.hpp"
#include "engine/identification/convergence.hpp"
#include "engine/sweep/tables.hpp"

namespace dampbench::sweep::tables {

inline Cell num(double v) { return number_cell(v); }
inline Cell txt(std::string s) { return {std::move(s), std::nullopt}; }
inline Cell none() { return {"-", std::nullopt}; }

/// Whether table kind `name` reads a request's `where` as its rows (Kind::where_picks_rows, in the registry) rather than
/// as the series' fits; false for an unknown name.
bool where_picks_rows(std::string_view name);

/// `s` with every character a file name may not hold replaced by '_'.
std::string file_stem(std::string s);

/// Every group of one (split, model, optimizer, optimized metric), ordered by fit set.
struct Series {
  int split = 0, model = 0, optimizer = 0;
  Metric metric = Metric::of_abs;
  std::vector<const GroupRecord*> groups;
};

struct Context {
  const StoreResults& R;
  int part;
  const TableSpec& t;
  const PartSpec& spec;
  std::vector<const GroupRecord*> selected;
  bool many_models = false, many_optimizers = false, many_metrics = false, many_splits = false;

  /// Selects the part's finished groups that the request's splits, models, optimizers, metric and `where` keep.
  Context(const StoreResults& results, int p, const TableSpec& request);

  [[nodiscard]] const StoreModel& store_model(int m) const {
    return R.header.models.at(static_cast<std::size_t>(R.header.model(part, m)));
  }
  [[nodiscard]] std::string model_name(int m) const { return store_model(m).name; }
  [[nodiscard]] std::string optimizer_label(int o) const {
    return R.header.optimizers.at(static_cast<std::size_t>(R.header.optimizer(part, o))).label;
  }
  [[nodiscard]] std::string split_name(int s) const { return R.header.split_name(part, s); }
  [[nodiscard]] const StoreFitSet& fitset(const GroupRecord& g) const {
    return R.header.fitsets.at(static_cast<std::size_t>(R.header.fitset(part, g.split, g.fitset)));
  }
  [[nodiscard]] const StoreDataset& dataset(int d) const {
    return R.header.datasets.at(static_cast<std::size_t>(R.header.dataset(part, d)));
  }
  [[nodiscard]] bool matches(const Selection& s, int d) const { return s.matches(dataset(d).name, dataset(d).variables); }
  [[nodiscard]] const Model& model(int m) const { return R.model(part, m); }
  /// The model of a group's parameters (the law model it chose, for laws = "auto").
  [[nodiscard]] const Model& model(const GroupRecord& g) const { return R.model(g); }
  /// Whether a series' groups chose their own laws (laws = "auto"): their parameters differ from group to group.
  [[nodiscard]] static bool chose_laws(const Series& s) {
    return std::any_of(s.groups.begin(), s.groups.end(), [](const GroupRecord* g) { return !g->laws.empty(); });
  }
  [[nodiscard]] std::string label(const GroupRecord& g) const { return fitset(g).label; }
  [[nodiscard]] std::string title(std::string fallback) const { return t.title.empty() ? fallback : t.title; }

  [[nodiscard]] std::vector<Series> series() const;
  /// "_model[_optimizer][_metric][_split]": the parts that tell this series from the others.
  [[nodiscard]] std::string suffix(const Series& s, bool with_model = true) const;
  [[nodiscard]] std::string describe(const Series& s, bool with_model = true) const;
  /// A table; `id` starts with the kind, which the request's `name` replaces.
  [[nodiscard]] Table table(std::string id, std::string title_text, std::vector<std::string> columns) const;
  /// Parameter values in paper units of every run of a group.
  [[nodiscard]] std::vector<std::vector<double>> paper_params(const GroupRecord& g) const;
  /// Per parameter, per condition (group of the series): the summary over the runs, in paper units.
  [[nodiscard]] std::vector<std::vector<Summary>> parameter_summaries(const Series& s) const;
};

std::vector<double> best_values(const GroupRecord& g);

/// Metric `metric` of group `g`'s best run on dataset `d`: as fitted (its own fit or a joint fit's dataset), or as
/// predicted; none when the group does not fit (or predict) `d`.
std::optional<double> dataset_value(const Context& c, const GroupRecord& g, int d, bool predicted, int metric);

/// The datasets the series' groups fit (with `fits`) and predict (with `predictions`).
std::set<int> series_datasets(const Context& c, const std::vector<Series>& list, bool fits, bool predictions);

/// One series' value on one dataset: the fit value when the series fits it (and `fits`), else the prediction of it
/// (when `predictions`), the mean over the series' groups that fit or predict it.
struct SeriesValue {
  std::optional<double> value;
  bool predicted = false, unconverged = false, averaged = false;
};
SeriesValue series_value(const Context& c, const Series& s, int d, int metric, bool fits, bool predictions);

inline constexpr const char* kUnconvergedMark = "†";
inline constexpr const char* kUnconvergedNote =
    "† not converged: the runs disagree (median run > 2 % above the best), a single run cannot show agreement, or "
    "the best still improved by > 1 % in the last fifth of its budget (a hybrid whose local stage stopped at a local "
    "optimum is not asked to stall); raise runs, population or iterations "
    "before trusting it.";
inline constexpr const char* kUndeterminedMark = "‡";
inline constexpr const char* kAtBoundMark = "⊥";

/// Series grouped by (split, metric) for tables with one column or row per model.
std::map<std::pair<int, int>, std::vector<Series>> by_split_metric(const std::vector<Series>& all);
/// The id suffix of a (split, metric)'s tables: "_METRIC", "_SPLIT" for what the request holds several of.
std::string split_metric_suffix(const Context& c, int split, Metric metric);
/// The same in a title's words: "Split kwok, nrmse: " when the request holds several splits or metrics, else "".
std::string split_metric_head(const Context& c, int split, Metric metric);
/// A series' column head: its model, and its optimizer when the table compares optimizers.
std::string series_column(const Context& c, const Series& s);

}  // namespace dampbench::sweep::tables
