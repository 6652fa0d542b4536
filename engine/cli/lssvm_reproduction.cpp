#include "engine/cli/lssvm_reproduction.hpp"

#include <algorithm>
#include <filesystem>

#include "engine/common/text_file.hpp"
#include "engine/sweep/paper_file.hpp"
#include "engine/sweep/spec/reader.hpp"

namespace dampbench::cli {
namespace {

Table two_column_table(const std::string& id, const std::string& title, const std::string& what,
                       const std::vector<std::pair<std::string, double>>& rows) {
  Table t{id, title, {what, "value"}, {}};
  for (const auto& [name, value] : rows) t.rows.push_back({name, number_cell(value)});
  return t;
}

}  // namespace

std::vector<Table> lssvm_reproduction_tables(const LssvmRunFigures& run) {
  std::vector<Table> tables;
  tables.push_back(two_column_table("lssvm_training", "LS-SVM training set", "quantity",
                                    {{"training samples", static_cast<double>(run.train_samples)}}));
  tables.push_back(two_column_table("lssvm_hyperparameters", "LS-SVM hyperparameters", "parameter",
                                    {{"c", run.c}, {"sigma", run.sigma}}));
  Table errors{"lssvm_errors",
               "LS-SVM test errors (e = F_measured − F_model)",
               {"record", "one-step MAE [N]", "one-step max abs [N]", "one-step MSE [N²]", "free-run MAE [N]",
                "free-run max abs [N]", "free-run MSE [N²]"},
               {}};
  Table relative{"lssvm_relative_errors",
                 "LS-SVM maximum relative errors (max |e| / max |F_measured| of the record)",
                 {"record", "one-step max rel [%]", "free-run max rel [%]"},
                 {}};
  const auto error_row = [&](const LssvmRecordErrors& r) {
    const lssvm::ErrorMetrics &one = r.one_step, &free = r.free_run;
    errors.rows.push_back({r.name, number_cell(one.mae), number_cell(one.max_abs), number_cell(one.mse),
                           number_cell(free.mae), number_cell(free.max_abs), number_cell(free.mse)});
  };
  // A relative error is each record's own (its largest error over its largest force); "largest" is the largest of
  // them, as the paper's largest figure is of its four. The pooled errors in N are the row "all".
  double largest_one = 0, largest_free = 0;
  for (const LssvmRecordErrors& r : run.records) {
    error_row(r);
    relative.rows.push_back({r.name, number_cell(100 * r.one_step.max_rel), number_cell(100 * r.free_run.max_rel)});
    largest_one = std::max(largest_one, 100 * r.one_step.max_rel);
    largest_free = std::max(largest_free, 100 * r.free_run.max_rel);
  }
  error_row(run.all);
  relative.rows.push_back({"largest", number_cell(largest_one), number_cell(largest_free)});
  tables.push_back(std::move(errors));
  tables.push_back(std::move(relative));
  return tables;
}

void check_lssvm_paper_file(const std::string& published) {
  sweep::parse_paper_file(sweep::spec_file::read_text(published, "published numbers file (--reproduce)"), published);
}

sweep::Reproduction write_lssvm_reproduction(const std::string& dir, const std::string& published,
                                             const std::string& truth, const LssvmRunFigures& run) {
  sweep::ReproductionSpec spec;
  spec.published = published;
  spec.data = truth.empty() ? "real" : "synthetic";
  spec.truth = truth;
  // The only model of the paper is the LS-SVM itself: no truth decides a comparison here.
  spec.truth_is_compared_model = false;
  if (truth.empty())
    spec.tables_not_comparable = {{"lssvm_errors", "errors in N on another damper than the paper's (of 0.6 kN): its "
                                                   "relative errors are judged instead"}};
  const sweep::Reproduction r = sweep::reproduce(spec, lssvm_reproduction_tables(run));
  std::vector<std::string> records = run.trained_on;
  for (const LssvmRecordErrors& e : run.records) records.push_back(e.name);
  write_text_file((std::filesystem::path(dir) / "reproduction.md").string(), sweep::reproduction_markdown(r));
  write_text_file((std::filesystem::path(dir) / "reproduction.json").string(), sweep::reproduction_json(r, records));
  return r;
}

}  // namespace dampbench::cli
