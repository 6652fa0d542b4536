// [[splits]]: which datasets each split fits and predicts, how it groups them, and its sensitivity analysis.

#include "engine/fit/held_out.hpp"
#include "engine/sweep/spec/reader.hpp"

namespace dampbench::sweep::spec_file {

namespace {

SensitivitySpec read_sensitivity(const Reader& r, const toml::node& n, const std::string& key) {
  SensitivitySpec s;
  if (n.is_boolean()) {
    s.enabled = *n.value<bool>();
    return s;
  }
  if (!n.is_table()) r.fail(&n, key, "expected true or a table { points, range, objective, normalized, where }");
  const toml::table& t = *n.as_table();
  r.only_keys(t, key, {"points", "range", "objective", "normalized", "where"});
  s.enabled = true;
  s.points = static_cast<int>(r.integer(t, "points", key, 21, 3));
  s.range = r.number(t, "range", key).value_or(0.5);
  if (!(s.range > 0 && s.range < 1)) r.fail(t.get("range"), Reader::join(key, "range"), "expected a number in (0, 1)");
  s.objective = r.string(t, "objective", key).value_or("rms");
  if (s.objective != "rms") r.check(t.get("objective"), Reader::join(key, "objective"), [&] { return parse_metric(s.objective); });
  s.normalized = r.boolean(t, "normalized", key, false);
  if (const toml::node* w = t.get("where")) s.where = read_selection(r, *w, Reader::join(key, "where"));
  return s;
}

/// `folds`: "leave-setting" or "leave-one:VAR"; a split with folds fits each fold's datasets together (by = "all").
void read_folds(const Reader& r, const toml::table& t, const std::string& key, SplitSpec& s) {
  const auto folds = r.string(t, "folds", key);
  if (!folds) return;
  const std::string fkey = Reader::join(key, "folds");
  const std::string_view variable = leave_one_variable(*folds);
  if (*folds != "leave-setting" && !(!variable.empty() && known_variable(variable)))
    r.fail(t.get("folds"), fkey,
           fmt::format("expected \"leave-setting\" or \"leave-one:VAR\" with VAR one of I, V, phi, amp, freq, w, got '{}'",
                       *folds));
  if (t.contains("by") && s.by != SplitSpec::By::all)
    r.fail(t.get("by"), Reader::join(key, "by"), "a split with folds fits each fold's datasets together: by = \"all\" or none");
  s.folds = *folds;
  s.by = SplitSpec::By::all;
}

}  // namespace

void read_splits(const Reader& r, const toml::table& root, PartSpec& part) {
  const toml::node* splits = root.get("splits");
  if (!splits) {
    part.splits.push_back(SplitSpec{});
    return;
  }
  if (!splits->is_array_of_tables() || splits->as_array()->empty())
    r.fail(splits, "splits", "expected one or more [[splits]] tables");
  const auto& a = *splits->as_array();
  for (std::size_t i = 0; i < a.size(); ++i) {
    const std::string key = fmt::format("splits[{}]", i);
    const toml::table& t = *a.get(i)->as_table();
    r.only_keys(t, key, {"name", "datasets", "models", "optimizers", "fit", "predict", "by", "folds", "sensitivity"});
    SplitSpec s;
    s.name = r.string(t, "name", key).value_or(fmt::format("split{}", i + 1));
    if (part.split_index(s.name) >= 0) r.fail(t.get("name"), Reader::join(key, "name"), fmt::format("split name '{}' is used twice", s.name));
    s.collections = r.strings(t, "datasets", key);
    check_names(r, t.get("datasets"), Reader::join(key, "datasets"), s.collections, part.collections, "dataset entry");
    s.models = r.strings(t, "models", key);
    check_names(r, t.get("models"), Reader::join(key, "models"), s.models, model_names(part), "model");
    s.optimizers = r.strings(t, "optimizers", key);
    check_names(r, t.get("optimizers"), Reader::join(key, "optimizers"), s.optimizers, optimizer_labels(part), "optimizer");
    if (const toml::node* f = t.get("fit")) s.fit = read_selection(r, *f, Reader::join(key, "fit"));
    if (const toml::node* p = t.get("predict")) s.predict = read_selection(r, *p, Reader::join(key, "predict"));
    if (const toml::node* b = t.get("by")) {
      const std::string bkey = Reader::join(key, "by");
      if (b->is_string() && *b->value<std::string>() == "each") s.by = SplitSpec::By::each;
      else if (b->is_string() && *b->value<std::string>() == "all") s.by = SplitSpec::By::all;
      else if (b->is_array()) {
        s.by = SplitSpec::By::variables;
        s.by_variables = r.strings(*b, bkey);
        for (const auto& v : s.by_variables)
          if (!known_variable(v)) r.fail(b, bkey, fmt::format("unknown operating variable '{}' (known: I, V, phi, amp, freq, w)", v));
        if (s.by_variables.empty()) s.by = SplitSpec::By::all;
      } else {
        r.fail(b, bkey, "expected \"each\", \"all\" or an array of operating variables, e.g. [\"I\"]");
      }
    }
    read_folds(r, t, key, s);
    if (const toml::node* n = t.get("sensitivity")) s.sensitivity = read_sensitivity(r, *n, Reader::join(key, "sensitivity"));
    part.splits.push_back(std::move(s));
  }
}

}  // namespace dampbench::sweep::spec_file
