// energy: the energy each model's best run dissipates per cycle on each record beside the measured one (the loop's
// area, ∫F dx: the fvd paper's argument for the quadratic elastic model, the text under its Figs. 3-4).
#include <cmath>
#include <map>
#include <set>

#include <fmt/format.h>

#include "engine/record/loop_work.hpp"
#include "engine/sweep/tables/kinds.hpp"

namespace dampbench::sweep::tables {
namespace {

/// Whole cycles in a record: its duration times its frequency estimate (fdsp eq. 15), rounded, at least 1.
double record_cycles(const Signals& s) {
  const double cycles = std::round(s.duration_s * s.excitation_freq_hz);
  return cycles >= 1 ? cycles : 1.0;
}

/// The work of group g's best run on record `s` [J], or none when the model's force is not finite there.
std::optional<double> best_run_work(const Context& c, const GroupRecord& g, const Signals& s) {
  const auto& best = g.run_results.at(static_cast<std::size_t>(g.best_run()));
  const std::vector<double> force = c.model(g).simulate(best.params, s);
  const double work = loop_work_j(force, s.x_m);
  return std::isfinite(work) ? std::optional<double>(work) : std::nullopt;
}

/// A series' relative energy error on dataset d [%]: that of the groups fitting d, else the mean over the groups
/// predicting it (`predicted` then set).
std::optional<double> series_energy_error(const Context& c, const Series& s, int d, const Signals& record,
                                          double measured_work, bool fits, bool predictions, bool& predicted) {
  for (const bool role : {false, true}) {
    if (role ? !predictions : !fits) continue;
    double sum = 0;
    int count = 0;
    for (const GroupRecord* g : s.groups) {
      const auto& fs = c.fitset(*g);
      const auto& list = role ? fs.predict : fs.fit;
      if (std::find(list.begin(), list.end(), d) == list.end()) continue;
      const auto work = best_run_work(c, *g, record);
      if (!work) continue;
      sum += 100.0 * (*work - measured_work) / std::fabs(measured_work);
      ++count;
    }
    if (count > 0) {
      predicted = role;
      return sum / count;
    }
  }
  return std::nullopt;
}

}  // namespace

void energy_tables(const Context& c, std::vector<Table>& out) {
  std::map<int, std::vector<Series>> by_metric;
  for (const auto& s : c.series()) by_metric[static_cast<int>(s.metric)].push_back(s);
  for (const auto& [key, list] : by_metric) {
    const Metric optimized = static_cast<Metric>(key);
    std::vector<std::string> cols{"Dataset", "Cycles", "E measured [J/cycle]"};
    for (const auto& s : list) cols.push_back(fmt::format("dE % ({})", series_column(c, s)));
    Table r = c.table("energy" + (c.many_metrics ? file_stem("_" + std::string(metric_name(optimized))) : std::string()),
                      "Energy dissipated per cycle (the loop's area, the integral of F dx): measured, and each model's best "
                      "run as its difference from the measured in %",
                      cols);
    const bool fits = c.t.role != "predict", predictions = c.t.role != "fit";
    const std::set<int> datasets = series_datasets(c, list, fits, predictions);
    std::vector<std::string> unavailable;
    bool predicted_any = false;
    for (int d : datasets) {
      if (!c.t.where.everything() && !c.matches(c.t.where, d)) continue;
      std::string why;
      const Signals* record = c.R.record(c.part, d, why);
      if (record && (record->is_system() || !record->has_measured()))
        record = nullptr, why = "not a rig record with a measured force";
      std::vector<Cell> row{txt(c.dataset(d).name)};
      if (!record) {
        unavailable.push_back(fmt::format("{}: {}", c.dataset(d).name, why));
        continue;
      }
      const double cycles = record_cycles(*record), work = loop_work_j(record->F_N, record->x_m);
      row.push_back(num(cycles));
      row.push_back(num(work / cycles));
      for (const auto& s : list) {
        bool predicted = false;
        const auto error = series_energy_error(c, s, d, *record, work, fits, predictions, predicted);
        predicted_any |= error && predicted;
        row.push_back(error ? Cell{fmt::format("{:+.2f}{}", *error, predicted ? "*" : ""), *error} : none());
      }
      r.rows.push_back(std::move(row));
    }
    std::string note = "dE % = 100 (E model - E measured) / |E measured|: above 0 the model dissipates more than the "
                       "record. Cycles: the record's duration times its frequency estimate (fdsp eq. 15), rounded.";
    if (predicted_any) note += " * predicted: the dataset was not fitted, the fit of other conditions was evaluated on it.";
    if (!unavailable.empty())
      note += fmt::format(" Not shown, the records could not be read again: {}.", fmt::join(unavailable, "; "));
    r.note = note;
    out.push_back(std::move(r));
  }
}

}  // namespace dampbench::sweep::tables
