// landscape: the objective of a group's best run over a grid of two of its parameters, ±range around their values
// (fdsp Fig. 4: the error of eq. 8 over a_c0 and a_c1 at 1.5 Hz, which the paper reads as convex), and whether it
// is convex along each parameter (the smallest second difference over the grid's lines).
#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/evaluation/batch_evaluator.hpp"
#include "engine/sweep/tables/kinds.hpp"

namespace dampbench::sweep::tables {
namespace {

/// Grid value k of n around v: v·(1 + range·(2k/(n − 1) − 1)); around 0, ±range itself.
double grid_value(double v, double range, int k, int n) {
  const double t = range * (2.0 * k / (n - 1) - 1.0);
  return v == 0 ? t : v * (1 + t);
}

/// The smallest second difference f[i−1] − 2f[i] + f[i+1] over the grid's lines along one axis (rows: along the
/// second parameter; columns: along the first).
double min_second_difference(const std::vector<double>& f, int n, bool along_rows) {
  double lowest = std::numeric_limits<double>::infinity();
  for (int line = 0; line < n; ++line)
    for (int i = 1; i + 1 < n; ++i) {
      auto at = [&](int k) { return f[static_cast<std::size_t>(along_rows ? line * n + k : k * n + line)]; };
      lowest = std::min(lowest, at(i - 1) - 2 * at(i) + at(i + 1));
    }
  return lowest;
}

/// The landscape of group g on its one fit record, and its convexity; false (with `why`) when it cannot be drawn.
bool group_landscape(const Context& c, const Series& s, const GroupRecord& g, std::vector<Table>& out, std::string& why) {
  const auto& fs = c.fitset(g);
  if (fs.fit.size() != 1) return why = "it fits several records at once", false;
  const Signals* record = c.R.record(c.part, fs.fit[0], why);
  if (!record) return false;
  const Model& model = c.model(g);
  const int n = c.t.points;
  int j[2];
  try {
    for (int a = 0; a < 2; ++a) j[a] = model.parameter_index(c.t.params[a]);
  } catch (const InputError& e) {
    return why = e.what(), false;
  }
  const std::vector<double>& best = g.run_results.at(static_cast<std::size_t>(g.best_run())).params;
  CandidateBatch batch(model.dim(), n * n);
  for (int r = 0; r < n; ++r)
    for (int k = 0; k < n; ++k) {
      std::vector<double> p = best;
      p[j[0]] = grid_value(best[j[0]], c.t.range, r, n);
      p[j[1]] = grid_value(best[j[1]], c.t.range, k, n);
      batch.set_candidate(r * n + k, p);
    }
  std::vector<double> f(static_cast<std::size_t>(n * n));
  BatchEvaluator(model, *record).evaluate(batch, g.metric, f);
  const std::string& p0 = c.t.params[0], & p1 = c.t.params[1];
  const std::string id = "landscape" + c.suffix(s) + "_" + file_stem(c.label(g));
  std::vector<std::string> cols{fmt::format("{} \\ {}", p0, p1)};
  for (int k = 0; k < n; ++k) cols.push_back(format_number(grid_value(best[j[1]], c.t.range, k, n)));
  Table t = c.table(id, fmt::format("{} of {}'s best run on {} over {} and {}, ±{:g} % around its values — {}",
                                    metric_name(g.metric), c.model_name(s.model), c.label(g), p0, p1, 100 * c.t.range,
                                    c.describe(s)),
                    cols);
  for (int r = 0; r < n; ++r) {
    std::vector<Cell> row{num(grid_value(best[j[0]], c.t.range, r, n))};
    for (int k = 0; k < n; ++k) row.push_back(num(f[static_cast<std::size_t>(r * n + k)]));
    t.rows.push_back(std::move(row));
  }
  t.note = fmt::format("Rows: {}; columns: {} (SI). The best run is at the centre ({}, {}).", p0, p1,
                       format_number(best[j[0]]), format_number(best[j[1]]));
  Table convex = c.table(id + "_convexity",
                         fmt::format("Convexity of that landscape: the smallest second difference along each parameter "
                                     "(above 0: convex along every line of the grid) — {}",
                                     c.label(g)),
                         {"Along", "min second difference"});
  convex.rows.push_back({txt(p0), num(min_second_difference(f, n, false))});
  convex.rows.push_back({txt(p1), num(min_second_difference(f, n, true))});
  convex.paper = "";
  out.push_back(std::move(t));
  out.push_back(std::move(convex));
  return true;
}

}  // namespace

void landscape_tables(const Context& c, std::vector<Table>& out) {
  if (c.t.params.size() != 2) {  // a sweep file's entry names them; `dampbench table --kind landscape` cannot
    Table t = c.table("landscape", "No landscape", {"Why"});
    t.rows.push_back({txt("a landscape needs params = [\"p1\", \"p2\"] in a [[tables]] entry of the sweep file")});
    out.push_back(std::move(t));
    return;
  }
  for (const Series& s : c.series())
    for (const GroupRecord* g : s.groups) {
      std::string why;
      if (!group_landscape(c, s, *g, out, why)) {
        Table t = c.table("landscape" + c.suffix(s) + "_" + file_stem(c.label(*g)),
                          fmt::format("No landscape of {} on {}", c.model_name(s.model), c.label(*g)), {"Why"});
        t.rows.push_back({txt(why)});
        out.push_back(std::move(t));
      }
    }
}

}  // namespace dampbench::sweep::tables
