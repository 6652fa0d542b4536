// Reading finished groups back: one pass over each table in group order, whatever the number of groups.
#include <map>
#include <memory>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "engine/sweep/store.hpp"
#include "engine/sweep/store/schema.hpp"
#include "engine/sweep/store/sqlite_access.hpp"

namespace dampbench::sweep {

using json = nlohmann::json;
using store_db::json_column;
using store_db::kGroupColumns;
using store_db::Stmt;
using store_db::trace_points;

namespace {

GroupRecord read_group_row(const Stmt& s) {
  GroupRecord g;
  g.index = s.integer(0);
  g.part = static_cast<int>(s.integer(1));
  g.split = static_cast<int>(s.integer(2));
  g.fitset = static_cast<int>(s.integer(3));
  g.model = static_cast<int>(s.integer(4));
  g.optimizer = static_cast<int>(s.integer(5));
  g.metric = parse_metric(s.text(6));
  g.runs = static_cast<int>(s.integer(7));
  g.task_key = store_db::stored_integer(s.text(8), 16, "groups.task_key");
  g.failed = s.text(9) == "failed";
  g.message = s.text(10);
  g.wall_time_s = s.real(11);
  g.candidate_samples = s.real(12);
  g.evaluations = s.integer(13);
  g.dampbench_version = s.text(14);
  g.build_flags = s.text(15);
  g.spec_hash = s.text(16);
  g.dataset_hash = s.text(17);
  g.finished_at = s.text(18);
  g.laws = s.text(19);
  return g;
}

/// Run results, per-dataset metrics and sensitivity of the groups `where` selects ("grp=?" bound to `grp`,
/// or "" for every group), each row attached through `slot` (group number → record, nullptr to skip).
template <class Slot>
void read_details(sqlite3* db, const std::string& where, long long grp, bool runs, bool traces, bool details, Slot&& slot) {
  auto prepare = [&](const std::string& sql) {
    auto s = std::make_unique<Stmt>(db, sql.c_str());
    if (!where.empty()) s->bind(1, grp);
    return s;
  };
  const std::string filter = where.empty() ? "" : " WHERE " + where;
  if (runs) {
    const auto r = prepare(fmt::format("SELECT grp, run, best_value, metrics, params, evaluations, stop_reason, local_optimum{} "
                                       "FROM runs{} ORDER BY grp, run",
                                       traces ? ", trace" : "", filter));
    while (r->step()) {
      GroupRecord* g = slot(r->integer(0));
      if (!g) continue;
      RunRecord x;
      x.run = static_cast<int>(r->integer(1));
      x.best_value = r->real(2);
      x.metrics = r->metric_row(3);
      x.params = r->doubles(4);
      x.evaluations = r->integer(5);
      x.stop_reason = r->text(6);
      x.at_local_optimum = r->integer(7) != 0;
      if (traces) x.trace = trace_points(r->doubles(8));
      g->run_results.push_back(std::move(x));
    }
  }
  if (details) {
    const auto d = prepare("SELECT grp, run, dataset, role, metrics FROM dataset_metrics" + filter + " ORDER BY grp, run, dataset");
    while (d->step())
      if (GroupRecord* g = slot(d->integer(0)))
        g->dataset_metrics.push_back({static_cast<int>(d->integer(1)), static_cast<int>(d->integer(2)),
                                      d->text(3) == "predict", d->metric_row(4)});
    const auto t = prepare("SELECT grp, dataset, S, SP FROM sensitivity" + filter);
    while (t->step())
      if (GroupRecord* g = slot(t->integer(0)))
        g->sensitivity = SensitivityRecord{static_cast<int>(t->integer(1)), t->doubles(2), t->doubles(3)};
    const auto i = prepare("SELECT grp, samples, std_error, relative_error, correlation, flags FROM identifiability" + filter);
    while (i->step())
      if (GroupRecord* g = slot(i->integer(0))) {
        Identifiability id;
        id.samples = static_cast<int>(i->integer(1));
        id.std_error = i->doubles(2);
        id.relative_error = i->doubles(3);
        const std::vector<double> correlation = i->doubles(4);
        const std::size_t p = id.std_error.size();
        for (std::size_t r = 0; r < p && (r + 1) * p <= correlation.size(); ++r)
          id.correlation.emplace_back(correlation.begin() + static_cast<std::ptrdiff_t>(r * p),
                                      correlation.begin() + static_cast<std::ptrdiff_t>((r + 1) * p));
        id.flags = json_column<std::vector<std::vector<std::string>>>(*i, 5, "identifiability.flags");
        g->identifiability = std::move(id);
      }
  }
}

}  // namespace

std::vector<GroupRecord> Store::groups(const GroupQuery& q) const {
  std::vector<GroupRecord> out;
  Stmt s(db_, fmt::format("SELECT {} FROM groups {} ORDER BY grp", kGroupColumns, q.part >= 0 ? "WHERE part=?" : "").c_str());
  if (q.part >= 0) s.bind(1, q.part);
  while (s.step()) out.push_back(read_group_row(s));
  // One pass over each table in group order, not one query per group: a store may hold 10^5 groups.
  std::map<long long, std::size_t> index;
  for (std::size_t i = 0; i < out.size(); ++i) index[out[i].index] = i;
  read_details(db_, "", 0, q.runs, q.traces, q.details, [&](long long grp) -> GroupRecord* {
    const auto it = index.find(grp);
    return it == index.end() ? nullptr : &out[it->second];
  });
  return out;
}

std::optional<GroupRecord> Store::group(long long index, bool traces) const {
  Stmt s(db_, fmt::format("SELECT {} FROM groups WHERE grp=?", kGroupColumns).c_str());
  s.bind(1, index);
  if (!s.step()) return std::nullopt;
  GroupRecord g = read_group_row(s);
  read_details(db_, "grp=?", index, true, traces, true, [&](long long) { return &g; });
  return g;
}

}  // namespace dampbench::sweep
