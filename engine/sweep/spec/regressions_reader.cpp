// [[regressions]]: laws fitted to the per-condition parameters of one model; each law is checked against the
// model here.
#include "engine/model/parameter_law.hpp"
#include "engine/sweep/analysis.hpp"
#include "engine/sweep/spec/reader.hpp"

namespace dampbench::sweep::spec_file {

void read_regressions(const Reader& r, const toml::table& root, PartSpec& part) {
  const toml::node* regs = root.get("regressions");
  // `regressions = []` is none: a file that extends another drops its base's regressions so.
  if (!regs || (regs->is_array() && regs->as_array()->empty())) return;
  if (!regs->is_array_of_tables()) r.fail(regs, "regressions", "expected [[regressions]] tables (or [] for none)");
  const auto& a = *regs->as_array();
  for (std::size_t i = 0; i < a.size(); ++i) {
    const std::string key = fmt::format("regressions[{}]", i);
    const toml::table& t = *a.get(i)->as_table();
    r.only_keys(t, key, {"name", "model", "split", "optimizer", "laws", "paper", "where"});
    RegressionSpec g;
    g.model = r.required_string(t, "model", key);
    const int m = part.model_index(g.model);
    if (m < 0) r.fail(t.get("model"), Reader::join(key, "model"), fmt::format("unknown model '{}' (known: {})", g.model, fmt::join(model_names(part), ", ")));
    g.name = r.string(t, "name", key).value_or(fmt::format("regression{}", i + 1));
    g.split = r.string(t, "split", key).value_or("");
    if (!g.split.empty() && part.split_index(g.split) < 0)
      r.fail(t.get("split"), Reader::join(key, "split"), fmt::format("unknown split '{}'", g.split));
    g.optimizer = r.string(t, "optimizer", key).value_or("");
    if (!g.optimizer.empty() && part.optimizer_index(g.optimizer) < 0)
      r.fail(t.get("optimizer"), Reader::join(key, "optimizer"), fmt::format("unknown optimizer '{}'", g.optimizer));
    g.laws = r.required_string(t, "laws", key);
    g.paper = r.string(t, "paper", key).value_or("");
    r.check(t.get("laws"), Reader::join(key, "laws"), [&] {
      const ResolvedModel model = resolve_model_or_auto_base(part.models[m]);
      for (const auto& [name, law] : parse_laws(g.laws, "laws")) {
        (void)model.model->parameter_index(name);
        if (law.kind == ParameterLaw::Kind::fixed)
          throw InputError(fmt::format("laws {}: a regression needs a law with coefficients, got a number", name));
        check_regression_law(law, name);
      }
      return 0;
    });
    if (const toml::node* w = t.get("where")) g.where = read_selection(r, *w, Reader::join(key, "where"));
    part.regressions.push_back(std::move(g));
  }
}

}  // namespace dampbench::sweep::spec_file
