// The tables a part asks for (`tables` or [[tables]]; kinds: engine/sweep/tables.hpp).
#include <algorithm>
#include <cmath>

#include "engine/sweep/tables.hpp"

#include "engine/sweep/spec/reader.hpp"

namespace dampbench::sweep::spec_file {

namespace {

TableSpec read_table(const Reader& r, const PartSpec& part, const toml::node& n, const std::string& key) {
  TableSpec ts;
  if (n.is_string()) {
    ts.kind = *n.value<std::string>();
  } else {
    if (!n.is_table()) r.fail(&n, key, "expected a table kind or a table { kind, paper, split, models, ... }");
    const toml::table& t = *n.as_table();
    r.only_keys(t, key, {"kind", "name", "title", "paper", "split", "models", "optimizers", "metric", "role", "where",
                         "target_rel", "params", "range", "points"});
    ts.kind = r.required_string(t, "kind", key);
    ts.name = r.string(t, "name", key).value_or("");
    ts.title = r.string(t, "title", key).value_or("");
    ts.paper = r.string(t, "paper", key).value_or("");
    ts.splits = r.strings(t, "split", key);
    for (const auto& sp : ts.splits)
      if (part.split_index(sp) < 0) r.fail(t.get("split"), Reader::join(key, "split"), fmt::format("unknown split '{}'", sp));
    ts.models = r.strings(t, "models", key);
    check_names(r, t.get("models"), Reader::join(key, "models"), ts.models, model_names(part), "model");
    ts.optimizers = r.strings(t, "optimizers", key);
    check_names(r, t.get("optimizers"), Reader::join(key, "optimizers"), ts.optimizers, optimizer_labels(part), "optimizer");
    ts.metric = r.string(t, "metric", key).value_or("");
    if (!ts.metric.empty()) r.check(t.get("metric"), Reader::join(key, "metric"), [&] { return parse_metric(ts.metric); });
    ts.role = r.string(t, "role", key).value_or("");
    if (!ts.role.empty() && ts.role != "fit" && ts.role != "predict")
      r.fail(t.get("role"), Reader::join(key, "role"), fmt::format("expected fit or predict, got '{}'", ts.role));
    if (const toml::node* w = t.get("where")) ts.where = read_selection(r, *w, Reader::join(key, "where"));
    ts.target_rel = r.number(t, "target_rel", key).value_or(0.01);
    if (!(ts.target_rel >= 0)) r.fail(t.get("target_rel"), Reader::join(key, "target_rel"), "expected a number >= 0");
    ts.params = r.strings(t, "params", key);
    ts.range = r.number(t, "range", key).value_or(0.4);
    if (!(ts.range > 0 && ts.range < 1)) r.fail(t.get("range"), Reader::join(key, "range"), "expected a fraction in (0, 1)");
    const double points = r.number(t, "points", key).value_or(11);
    if (!(points >= 3 && points <= 101 && points == std::floor(points) && std::fmod(points, 2) == 1))
      r.fail(t.get("points"), Reader::join(key, "points"), "expected an odd whole number from 3 to 101");
    ts.points = static_cast<int>(points);
    if (ts.kind != "landscape" && !ts.params.empty())
      r.fail(t.get("params"), Reader::join(key, "params"), "params belong to kind = \"landscape\"");
  }
  if (ts.kind == "landscape" && ts.params.size() != 2)
    r.fail(&n, key, "kind = \"landscape\" needs params = [\"p1\", \"p2\"], the two parameters it varies");
  const auto kinds = table_kinds();
  if (std::find(kinds.begin(), kinds.end(), ts.kind) == kinds.end())
    r.fail(&n, key, fmt::format("unknown table kind '{}' (known: {})", ts.kind, fmt::join(kinds, ", ")));
  return ts;
}

}  // namespace

void read_tables(const Reader& r, const toml::table& root, PartSpec& part) {
  const toml::node* tables = root.get("tables");
  if (!tables) {
    // The fvd paper's set: run statistics, parameter statistics, variability and the ranking.
    TableSpec t;
    t.kind = "fvd";
    part.tables.push_back(std::move(t));
    return;
  }
  if (tables->is_string()) {
    part.tables.push_back(read_table(r, part, *tables, "tables"));
    return;
  }
  if (!tables->is_array()) r.fail(tables, "tables", "expected a table kind or an array of kinds and [[tables]]");
  const auto& a = *tables->as_array();
  for (std::size_t i = 0; i < a.size(); ++i) part.tables.push_back(read_table(r, part, *a.get(i), fmt::format("tables[{}]", i)));
}


}  // namespace dampbench::sweep::spec_file
