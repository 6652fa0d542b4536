// overview: groups, tasks, failures, wall time and candidate-samples/s of a part.
#include <fmt/format.h>

#include "engine/sweep/tables/kinds.hpp"

namespace dampbench::sweep::tables {

void overview_table(const Context& c, std::vector<Table>& out) {
  long long groups = 0, failed = 0, tasks = 0, evaluations = 0, expected = 0, expected_tasks = 0;
  double wall = 0, cs = 0;
  for (const auto& g : c.R.groups) {
    if (g.part != c.part) continue;
    ++groups;
    failed += g.failed;
    tasks += g.runs;
    evaluations += g.evaluations;
    wall += g.wall_time_s;
    cs += g.candidate_samples;
  }
  expected = c.R.header.groups;
  expected_tasks = c.R.header.tasks;
  Table r = c.table("overview", "Sweep overview — " + c.spec.name, {"Quantity", "Value"});
  r.rows = {{txt("task groups stored"), num(static_cast<double>(groups))},
            {txt("tasks (runs) stored"), num(static_cast<double>(tasks))},
            {txt("failed task groups"), num(static_cast<double>(failed))},
            {txt("evaluations"), num(static_cast<double>(evaluations))},
            {txt("candidate-samples"), num(cs)},
            {txt("group wall time, summed [s]"), num(wall)},
            {txt("candidate-samples/s (per group)"), wall > 0 ? num(cs / wall) : none()}};
  r.note = fmt::format("The whole sweep has {} task groups and {} tasks over {} part(s).", expected, expected_tasks,
                       c.R.part_count());
  out.push_back(std::move(r));
}

}  // namespace dampbench::sweep::tables
