// held-out: a model fitted on several records at once (parameter laws across conditions) on every record it fitted
// and every record it predicted, beside that record's own fit (the same registered model fitted to it alone) and
// their ratio. A model of the whole damper gives up some accuracy against describing each test alone; the ratio
// says how much, and on the records it never saw it is the honest measure of prediction.
#include <optional>
#include <set>
#include <vector>

#include <fmt/format.h>

#include "engine/fit/held_out.hpp"
#include "engine/sweep/tables/kinds.hpp"

namespace dampbench::sweep::tables {
namespace {

/// Whether a series fits several records jointly or predicts some: the series this table is about.
bool spans_records(const Context& c, const Series& s) {
  for (const GroupRecord* g : s.groups)
    if (c.fitset(*g).fit.size() > 1 || !c.fitset(*g).predict.empty()) return true;
  return false;
}

/// A record's own fit: its metric, and whether that fit's runs converged.
struct OwnFit {
  double value = 0;
  bool converged = true;
};

/// The per-file reference of dataset `d`: the lowest `metric` of the best runs of the part's groups that fit `d`
/// alone with the registered model `model_id`, no laws and no fixture, optimized for `optimized`.
std::optional<OwnFit> per_file_reference(const Context& c, const std::string& model_id, Metric optimized, int d,
                                         int metric) {
  std::optional<OwnFit> best;
  for (const GroupRecord& g : c.R.groups) {
    if (g.part != c.part || g.failed || g.run_results.empty() || g.metric != optimized) continue;
    const StoreModel& m = c.store_model(g.model);
    const StoreFitSet& fs = c.fitset(g);
    if (m.model_id != model_id || !m.laws.empty() || !m.fixture.empty() || fs.fit.size() != 1 || fs.fit[0] != d)
      continue;
    const std::optional<double> v = dataset_value(c, g, d, false, metric);
    if (v && (!best || *v < best->value)) best = OwnFit{*v, group_convergence(g).converged};
  }
  return best;
}

Table held_out_table(const Context& c, const Series& s) {
  const Metric shown = c.t.metric.empty() ? s.metric : parse_metric(c.t.metric);
  const int m = static_cast<int>(shown);
  const std::string& model_id = c.store_model(s.model).model_id;
  Table r = c.table("held-out" + c.suffix(s),
                    fmt::format("{}: {} of each record it fitted and predicted, beside the record's own fit ({} "
                                "fitted to it alone)",
                                c.describe(s), metric_name(shown), model_id),
                    {"Dataset", "role", c.model_name(s.model), "own fit", "ratio"});
  bool unconverged_any = false, missing_any = false;
  std::string summary_note;
  for (const bool predicted : {false, true}) {
    if (c.t.role == (predicted ? "fit" : "predict")) continue;
    std::set<int> datasets;
    for (const GroupRecord* g : s.groups) {
      const std::vector<int>& list = predicted ? c.fitset(*g).predict : c.fitset(*g).fit;
      datasets.insert(list.begin(), list.end());
    }
    const char* role = predicted ? "held out" : "fitted";
    std::vector<RecordError> referenced;  // the records with an own fit to compare with
    for (int d : datasets) {
      if (!c.t.where.everything() && !c.matches(c.t.where, d)) continue;
      const SeriesValue v = series_value(c, s, d, m, !predicted, predicted);
      if (!v.value) continue;
      const std::optional<OwnFit> ref = per_file_reference(c, model_id, s.metric, d, m);
      unconverged_any |= v.unconverged || (ref && !ref->converged);
      missing_any |= !ref;
      const std::string name = c.dataset(d).name;
      const bool usable = ref && ref->value > 0;
      r.rows.push_back({txt(name), txt(role), {format_number(*v.value) + (v.unconverged ? kUnconvergedMark : ""), *v.value},
                        ref ? Cell{format_number(ref->value) + (ref->converged ? "" : kUnconvergedMark), ref->value} : none(),
                        usable ? num(*v.value / ref->value) : none()});
      if (usable) referenced.push_back({role, "", name, *v.value, ref->value, std::nullopt});
    }
    if (referenced.empty()) continue;
    const ErrorSummary sum = summarize_errors(referenced);
    r.rows.push_back({txt(fmt::format("mean of {}", sum.count - sum.failed)), txt(role), num(sum.mean),
                      num(sum.mean_per_file), num(sum.ratio_of_means)});
    summary_note += fmt::format(" Worst {}: {} ({:.3g}).", role, sum.worst_record, sum.worst_ratio);
    if (sum.failed > 0)
      summary_note += fmt::format(" {} {} record{} without a finite value, not in the mean.", sum.failed, role,
                                  sum.failed == 1 ? "" : "s");
  }
  r.note = "ratio = the model's value / the record's own fit; a mean row's ratio is the ratio of the means." +
           summary_note;
  if (missing_any) r.note += " - : the sweep has no fit of that record alone with " + model_id + ".";
  if (unconverged_any) r.note += std::string(" ") + kUnconvergedNote;
  return r;
}

}  // namespace

void held_out_tables(const Context& c, std::vector<Table>& out) {
  for (const Series& s : c.series())
    if (spans_records(c, s)) out.push_back(held_out_table(c, s));
}

}  // namespace dampbench::sweep::tables
