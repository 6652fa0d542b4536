// regression: the sweep's [[regressions]]: law coefficients, R², residuals, and on how many conditions the parameter
// was not identifiable.
#include <algorithm>
#include <map>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/model/parameter_law.hpp"
#include "engine/sweep/analysis.hpp"
#include "engine/sweep/tables/kinds.hpp"

namespace dampbench::sweep::tables {

RegressionResult law_regression(const Context& c, const RegressionSpec& reg) {
  RegressionResult out;
  out.spec = &reg;
  const int model_index = c.spec.model_index(reg.model);
  const int split = reg.split.empty() ? -1 : c.spec.split_index(reg.split);
  const int optimizer = reg.optimizer.empty() ? -1 : c.spec.optimizer_index(reg.optimizer);
  // The lowest metric per condition among the per-condition fits of the model.
  std::map<int, const GroupRecord*> per_dataset;
  for (const auto& g : c.R.groups) {
    if (g.part != c.part || g.failed || g.run_results.empty() || g.model != model_index) continue;
    if ((split >= 0 && g.split != split) || (optimizer >= 0 && g.optimizer != optimizer)) continue;
    const auto& fs = c.fitset(g);
    if (fs.fit.size() != 1 || !c.matches(reg.where, fs.fit[0])) continue;
    const GroupRecord*& slot = per_dataset[fs.fit[0]];
    auto best = [](const GroupRecord* x) { return x->run_results[static_cast<std::size_t>(x->best_run())].best_value; };
    if (!slot || best(&g) < best(slot)) slot = &g;
  }
  std::vector<std::vector<double>> params;
  std::vector<const GroupRecord*> groups;
  for (const auto& [d, g] : per_dataset) {
    out.variables.push_back(c.dataset(d).variables);
    params.push_back(g->run_results[static_cast<std::size_t>(g->best_run())].params);
    out.conditions.push_back(c.dataset(d).name);
    groups.push_back(g);
  }
  try {
    const Model& model = c.model(model_index);
    for (const auto& [name, law] : parse_laws(reg.laws, "laws")) {
      const int j = model.parameter_index(name);
      std::vector<double> y;
      for (const auto& p : params) y.push_back(p[static_cast<std::size_t>(j)]);
      LawRegression l{name, law, fit_law(law, name, out.variables, y), {}};
      // Conditions where parameter j was not determined by its record (‡ in the params table).
      for (const GroupRecord* g : groups) l.undetermined.push_back(g->identifiability && !g->identifiability->determined(j));
      out.laws.push_back(std::move(l));
    }
  } catch (const InputError& e) {
    out.laws.clear();
    out.error = e.what();
  }
  return out;
}

void regression_tables(const Context& c, std::vector<Table>& out) {
  for (const RegressionSpec& reg : c.spec.regressions) {
    if (!c.t.models.empty() && std::find(c.t.models.begin(), c.t.models.end(), reg.model) == c.t.models.end()) continue;
    const RegressionResult result = law_regression(c, reg);
    const std::string id = file_stem("regression_" + reg.name);
    Table coef = c.table(id, fmt::format("Regression of {}'s identified parameters on operating variables ({} conditions)",
                                           reg.model, result.conditions.size()),
                           {"Parameter", "Law", "Coefficient", "Value", "R2", "RMS residual", "Not identifiable at"});
    coef.paper = reg.paper.empty() ? c.t.paper : reg.paper;
    std::vector<std::string> res_cols{"Condition"};
    bool any_undetermined = false;
    for (const LawRegression& l : result.laws) {
      const RegressionFit& f = l.fit;
      const auto count = std::count(l.undetermined.begin(), l.undetermined.end(), true);
      any_undetermined |= count > 0;
      const std::string where = count == 0 ? "none" : fmt::format("{} {} of {}", kUndeterminedMark, count, l.undetermined.size());
      for (std::size_t k = 0; k < f.names.size(); ++k)
        coef.rows.push_back({txt(k == 0 ? l.parameter : ""), txt(k == 0 ? l.law.text() : ""), txt(f.names[k]), num(f.coefficients[k]),
                             k == 0 ? num(f.r2) : txt(""), k == 0 ? num(f.rms_residual) : txt(""), txt(k == 0 ? where : "")});
      for (const char* s : {"observed", "fitted", "residual"}) res_cols.push_back(fmt::format("{} {}", l.parameter, s));
    }
    coef.note = !result.error.empty() ? result.error
                                      : fmt::format("Least squares on the best run per condition{}{} (SI units).{}",
                                                    reg.split.empty() ? "" : ", split " + reg.split,
                                                    reg.optimizer.empty() ? "" : ", optimizer " + reg.optimizer,
                                                    any_undetermined ? fmt::format(
                                                        " Not identifiable at: conditions whose record does not determine the "
                                                        "parameter ({} in the residuals; relative standard error > 100 % or "
                                                        "|correlation| > 0.99): the regression fits their noise too.",
                                                        kUndeterminedMark)
                                                                     : "");
    out.push_back(std::move(coef));
    if (result.laws.empty()) continue;
    Table res = c.table(id + "_residuals", fmt::format("Residuals of the regression of {} per condition", reg.model), res_cols);
    res.paper = "";
    for (std::size_t i = 0; i < result.conditions.size(); ++i) {
      std::vector<Cell> row{txt(result.conditions[i])};
      for (const LawRegression& l : result.laws) {
        const RegressionFit& f = l.fit;
        const double observed = f.fitted[i] + f.residuals[i];
        row.push_back({format_number(observed) + (l.undetermined[i] ? kUndeterminedMark : ""), observed});
        row.push_back(num(f.fitted[i]));
        row.push_back(num(f.residuals[i]));
      }
      res.rows.push_back(std::move(row));
    }
    out.push_back(std::move(res));
  }
}

}  // namespace dampbench::sweep::tables
