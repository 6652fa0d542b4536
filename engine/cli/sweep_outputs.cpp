#include "engine/cli/sweep_outputs.hpp"

#include <fstream>
#include <map>
#include <ostream>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/common/text_file.hpp"
#include "engine/sweep/reproduction.hpp"

namespace dampbench::cli {
namespace {

void write_file(const std::filesystem::path& path, const std::string& text) { write_text_file(path.string(), text); }

struct PartFigures {
  long long groups = 0, tasks = 0, failed = 0;
  double candidate_samples = 0, wall_s = 0;
};

PartFigures figures(const sweep::StoreResults& results, int part) {
  PartFigures f;
  for (const auto& g : results.groups) {
    if (g.part != part) continue;
    ++f.groups;
    f.tasks += g.runs;
    f.failed += g.failed;
    f.candidate_samples += g.candidate_samples;
    f.wall_s += g.wall_time_s;
  }
  return f;
}

std::string part_summary(const sweep::StoreResults& results, int part, const std::vector<Table>& tables,
                         const OutputInfo& info) {
  const auto& p = results.header.parts[static_cast<std::size_t>(part)];
  const PartFigures f = figures(results, part);
  std::string out = fmt::format("# {}\n\n", p.title);
  out += fmt::format("Sweep file `{}`, store `{}`.\n\n", p.path, info.store_path);
  out += fmt::format("- task groups stored: {} ({} tasks = identification runs), failed: {}\n", f.groups, f.tasks, f.failed);
  out += fmt::format("- candidate-samples: {:.4g} in {:.2f} s of summed group wall time ({:.3g} candidate-samples/s per "
                     "group; groups run concurrently)\n",
                     f.candidate_samples, f.wall_s, f.wall_s > 0 ? f.candidate_samples / f.wall_s : 0.0);
  out += fmt::format("- this session: {} groups run in {:.2f} s wall\n\n", info.summary.ran, info.summary.wall_time_s);
  out += "Produced tables and the paper's tables they reproduce:\n\n| file | paper | content |\n|---|---|---|\n";
  for (const auto& t : tables)
    out += fmt::format("| {}.csv | {} | {} |\n", t.id, t.paper.empty() ? "(beyond the paper)" : t.paper, t.title);
  std::map<std::string, int> collections;
  std::vector<const sweep::StoreDataset*> datasets;
  for (const auto& d : results.header.datasets)
    if (d.part == part) {
      ++collections[d.collection];
      datasets.push_back(&d);
    }
  out += "\nDatasets:\n\n";
  if (datasets.size() <= 40) {
    for (const auto* d : datasets)
      out += fmt::format("- {}: {} ({}){}\n", d->name, d->label, d->path, d->error.empty() ? "" : " — did not load: " + d->error);
  } else {
    for (const auto& [c, n] : collections) out += fmt::format("- {}: {} records\n", c, n);
  }
  std::string failures;
  for (const auto& g : results.groups)
    if (g.part == part && g.failed) failures += fmt::format("- task group {}: {}\n", g.index, g.message);
  if (!failures.empty()) out += "\nFailed task groups (see failures.csv):\n\n" + failures;
  return out;
}

}  // namespace

std::vector<std::string> write_sweep_outputs(const sweep::StoreResults& results, const std::filesystem::path& out_dir,
                                             const OutputInfo& info, std::ostream* print) {
  namespace fs = std::filesystem;
  const int parts = results.part_count();
  std::vector<std::string> written;
  const auto write_output = [&](const fs::path& relative, const std::string& text) {
    write_file(out_dir / relative, text);
    written.push_back(relative.generic_string());
  };
  std::string top;
  if (parts > 1) {
    top = fmt::format("# {}\n\nSweep file `{}`, store `{}`: {} task groups, {} tasks; this session ran {} groups in "
                      "{:.2f} s wall ({:.3g} candidate-samples/s), {} failed.\n\n| part | folder | task groups | "
                      "tasks | failed | candidate-samples | summed group time [s] |\n|---|---|---:|---:|---:|---:|---:|\n",
                      results.header.name, info.spec_path, info.store_path, results.header.groups, results.header.tasks,
                      info.summary.ran, info.summary.wall_time_s,
                      info.summary.wall_time_s > 0 ? info.summary.candidate_samples / info.summary.wall_time_s : 0.0,
                      info.summary.failed);
  }
  for (int p = 0; p < parts; ++p) {
    const auto& part = results.header.parts[static_cast<std::size_t>(p)];
    const fs::path sub = parts > 1 ? fs::path(part.name) : fs::path();
    const fs::path dir = out_dir / sub;
    fs::create_directories(dir);
    const std::vector<Table> tables = sweep::sweep_tables(results, p);
    std::string md = "# " + part.title + "\n\n";
    for (const auto& t : tables) {
      md += t.to_markdown() + "\n";
      write_output(sub / (t.id + ".csv"), t.to_csv());
      if (print && parts == 1) *print << t.to_markdown() << "\n";
    }
    write_output(sub / "tables.md", md);
    write_output(sub / "summary.md", part_summary(results, p, tables, info));
    if (const auto& reproduction = results.parts[static_cast<std::size_t>(p)].reproduction) {
      // After the tables, so that a malformed paper file loses none of them.
      const sweep::Reproduction r = sweep::reproduce(*reproduction, tables);
      std::vector<std::string> records;
      for (const auto& d : results.header.datasets)
        if (d.part == p) records.push_back(d.name);
      write_output(sub / "reproduction.md", sweep::reproduction_markdown(r));
      write_output(sub / "reproduction.json", sweep::reproduction_json(r, records));
    }
    if (parts > 1) {
      const PartFigures f = figures(results, p);
      top += fmt::format("| {} | {}/ | {} | {} | {} | {:.4g} | {:.1f} |\n", part.title, part.name, f.groups, f.tasks,
                         f.failed, f.candidate_samples, f.wall_s);
      if (print) *print << fmt::format("{}: {} tables in {}\n", part.name, tables.size(), dir.string());
    }
  }
  if (parts > 1) write_output("summary.md", top);
  return written;
}

}  // namespace dampbench::cli
