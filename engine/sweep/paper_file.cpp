#include "engine/sweep/paper_file.hpp"

#include <algorithm>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "engine/sweep/spec/reader.hpp"

namespace dampbench::sweep {
namespace {

using spec_file::Reader;

std::vector<PublishedTable> read_tables(const Reader& r, const toml::table& root) {
  std::vector<PublishedTable> out;
  const toml::node* node = root.get("tables");
  if (!node || !node->is_array_of_tables()) r.fail(node, "tables", "expected one or more [[tables]]");
  int i = 0;
  for (const toml::node& n : *node->as_array()) {
    const std::string key = fmt::format("tables[{}]", i++);
    const toml::table& t = *n.as_table();
    r.only_keys(t, key, {"table", "ours", "label", "columns", "rows", "compare", "scale", "numbers_not_comparable", "row_key",
                            "at_most"});
    PublishedTable p;
    p.table = r.required_string(t, "table", key);
    p.ours = r.required_string(t, "ours", key);
    p.label = r.string(t, "label", key).value_or(p.table);
    p.columns = r.strings(t, "columns", key);
    if (p.columns.empty()) r.fail(&t, key + ".columns", "expected the table's column names");
    p.compare = r.strings(t, "compare", key);
    if (p.compare.empty()) p.compare = p.columns;
    for (const auto& c : p.compare)
      if (std::find(p.columns.begin(), p.columns.end(), c) == p.columns.end())
        r.fail(t.get("compare"), key + ".compare", fmt::format("'{}' is not one of its columns", c));
    p.not_comparable = r.string(t, "numbers_not_comparable", key).value_or("");
    p.row_key = r.string(t, "row_key", key).value_or("");
    p.at_most = r.boolean(t, "at_most", key, false);
    p.scale = r.number(t, "scale", key).value_or(1.0);
    if (!(p.scale > 0)) r.fail(t.get("scale"), key + ".scale", "expected a number > 0 (printed value x scale = ours)");
    const toml::node* rows = t.get("rows");
    if (!rows || !rows->is_array()) r.fail(rows, key + ".rows", "expected rows = [[\"row label\", number, ...], ...]");
    for (const toml::node& row : *rows->as_array()) {
      const toml::array* a = row.as_array();
      if (!a || a->size() != p.columns.size() + 1 || !(*a)[0].is_string())
        r.fail(&row, key + ".rows",
               fmt::format("expected a row label and {} numbers (one per column)", p.columns.size()));
      std::vector<double> values;
      for (std::size_t j = 1; j < a->size(); ++j) values.push_back(r.number((*a)[j], key + ".rows") * p.scale);
      p.rows.emplace_back(std::string(*(*a)[0].value<std::string>()), std::move(values));
    }
    out.push_back(std::move(p));
  }
  return out;
}

const PublishedTable* published_table(const Reader& r, const toml::table& t, const std::string& key, const char* field,
                                      const std::string& name, const std::vector<PublishedTable>& tables) {
  const auto it = std::find_if(tables.begin(), tables.end(), [&](const PublishedTable& p) { return p.table == name; });
  if (it == tables.end()) r.fail(t.get(field), key + "." + field, fmt::format("no [[tables]] entry '{}'", name));
  return &*it;
}

/// The `largest` form: its table, column and row checked against the paper's own numbers.
void read_largest_claim(const Reader& r, const toml::table& t, const std::string& key, PublishedClaim& c,
                        const std::vector<PublishedTable>& tables) {
  c.table = published_table(r, t, key, "table", r.required_string(t, "table", key), tables);
  const auto& cols = c.table->columns;
  const auto j = static_cast<std::size_t>(std::find(cols.begin(), cols.end(), c.column) - cols.begin());
  if (j == cols.size()) r.fail(&t, key + ".column", fmt::format("expected one of {}'s columns", c.table->table));
  const auto& rows = c.table->rows;
  const auto top = std::max_element(rows.begin(), rows.end(), [&](const auto& a, const auto& b) { return a.second[j] < b.second[j]; });
  if (std::none_of(rows.begin(), rows.end(), [&](const auto& row) { return row.first == c.largest; }))
    r.fail(t.get("largest"), key + ".largest", fmt::format("{} has no row '{}'", c.table->table, c.largest));
  if (top->first != c.largest)
    r.fail(t.get("largest"), key + ".largest",
           fmt::format("the paper's largest {} in {} is row '{}', not '{}'", c.column, c.table->table, top->first, c.largest));
}

/// The `ours` form: a sign of one column, or columns that rise.
void read_ours_claim(const Reader& r, const toml::table& t, const std::string& key, PublishedClaim& c) {
  const std::string sign = r.string(t, "sign", key).value_or("");
  c.magnitude = r.boolean(t, "magnitude", key, false);
  c.margin = r.number(t, "margin", key).value_or(0.0);
  if (!(c.margin >= 0)) r.fail(t.get("margin"), key + ".margin", "expected a number >= 0 (in the column's unit)");
  if (sign.empty() == c.order.empty())
    r.fail(&t, key, "a claim on our table alone (`ours`) takes either `sign` and `column` or `order` (its columns, lowest first)");
  if (!sign.empty()) {
    if (sign != "positive" && sign != "negative")
      r.fail(t.get("sign"), key + ".sign", fmt::format("expected positive or negative, got '{}'", sign));
    if (c.column.empty()) r.fail(&t, key + ".column", "expected the column whose sign the claim states");
    c.sign = sign == "positive" ? 1 : -1;
  } else if (c.order.size() < 2) {
    r.fail(t.get("order"), key + ".order", "expected two or more of our table's columns, lowest first");
  }
}

std::vector<PublishedClaim> read_claims(const Reader& r, const toml::table& root, const std::vector<PublishedTable>& tables) {
  std::vector<PublishedClaim> out;
  const toml::node* node = root.get("claims");
  if (!node) return out;
  if (!node->is_array_of_tables()) r.fail(node, "claims", "expected [[claims]] tables");
  int i = 0;
  for (const toml::node& n : *node->as_array()) {
    const std::string key = fmt::format("claims[{}]", i++);
    const toml::table& t = *n.as_table();
    r.only_keys(t, key, {"id", "text", "column", "order", "note", "table", "largest", "ours", "sign", "magnitude", "margin"});
    PublishedClaim c;
    c.id = r.string(t, "id", key).value_or(fmt::format("claim {}", i));
    c.text = r.required_string(t, "text", key);
    c.column = r.string(t, "column", key).value_or("");
    c.order = r.strings(t, "order", key);
    c.note = r.string(t, "note", key).value_or("");
    c.ours = r.string(t, "ours", key).value_or("");
    c.largest = r.string(t, "largest", key).value_or("");
    if (c.ours.empty() && (t.get("sign") || t.get("magnitude") || t.get("margin")))
      r.fail(&t, key, "`sign`, `magnitude` and `margin` belong to a claim on our table alone: name it in `ours`");
    if (c.largest.empty() != !t.get("table"))
      r.fail(&t, key, "`largest` (a row) and `table` (the [[tables]] entry it is the largest of) go together");
    if (!c.ours.empty()) {
      read_ours_claim(r, t, key, c);
      out.push_back(std::move(c));
      continue;
    }
    if (!c.largest.empty()) {
      read_largest_claim(r, t, key, c, tables);
      out.push_back(std::move(c));
      continue;
    }
    if (c.order.size() < 2) r.fail(&t, key + ".order", "expected two or more tables, best first");
    for (const auto& name : c.order) {
      const PublishedTable* p = published_table(r, t, key, "order", name, tables);
      c.tables.push_back(p);
      if (c.column.empty() && p->compare.size() != 1)
        r.fail(&t, key + ".column", fmt::format("'{}' compares {} columns: name the one the claim ranks by", name,
                                                p->compare.size()));
      if (!c.column.empty() && std::find(p->columns.begin(), p->columns.end(), c.column) == p->columns.end())
        r.fail(t.get("column"), key + ".column", fmt::format("'{}' has no column '{}'", name, c.column));
    }
    out.push_back(std::move(c));
  }
  return out;
}

/// A ranking claim's order against the paper's own numbers, on the rows its tables share.
void check_ranking(const Reader& r, const PublishedClaim& c) {
  for (const auto& first_row : c.tables.front()->rows) {
    const std::string& row = first_row.first;  // a plain reference: clang 14 does not capture structured bindings
    std::vector<double> paper;
    for (const PublishedTable* p : c.tables) {
      const std::string& column = c.column.empty() ? p->compare.front() : c.column;
      const auto j = static_cast<std::size_t>(std::find(p->columns.begin(), p->columns.end(), column) - p->columns.begin());
      const auto prow = std::find_if(p->rows.begin(), p->rows.end(), [&](const auto& x) { return x.first == row; });
      if (prow == p->rows.end()) break;
      paper.push_back(prow->second[j]);
    }
    for (std::size_t a = 0; a < paper.size(); ++a)
      for (std::size_t b = a + 1; b < paper.size(); ++b)
        if (paper[a] > paper[b])
          r.fail(nullptr, "claims",
                 fmt::format("{} of {} ({:g}) is above {}'s ({:g}): `order` lists the tables best (lowest) first", row,
                             c.tables[a]->table, paper[a], c.tables[b]->table, paper[b]));
  }
}

/// The [[laws]] entries: each law parsed, its coefficients exactly the law's names for the parameter, each
/// condition giving every variable the law reads.
std::vector<PublishedLaw> read_laws(const Reader& r, const toml::table& root) {
  std::vector<PublishedLaw> out;
  const toml::node* node = root.get("laws");
  if (!node) return out;
  if (!node->is_array_of_tables()) r.fail(node, "laws", "expected [[laws]] tables");
  int i = 0;
  for (const toml::node& n : *node->as_array()) {
    const std::string key = fmt::format("laws[{}]", i++);
    const toml::table& t = *n.as_table();
    r.only_keys(t, key, {"table", "ours", "parameter", "law", "label", "scale", "coefficients", "at"});
    PublishedLaw p;
    p.table = r.required_string(t, "table", key);
    p.ours = r.required_string(t, "ours", key);
    p.parameter = r.required_string(t, "parameter", key);
    p.law = r.required_string(t, "law", key);
    p.label = r.string(t, "label", key).value_or(p.table);
    p.scale = r.number(t, "scale", key).value_or(1.0);
    p.parsed = parse_law(p.law, key + ".law");
    const ParameterLaw& law = p.parsed;
    const std::vector<std::string> names = law.coefficient_names(p.parameter);
    const toml::array* coefficients = t.get("coefficients") ? t.get("coefficients")->as_array() : nullptr;
    if (!coefficients) r.fail(&t, key + ".coefficients", "expected coefficients = [[\"name\", number], ...]");
    for (const toml::node& c : *coefficients) {
      const toml::array* a = c.as_array();
      if (!a || a->size() != 2 || !(*a)[0].is_string())
        r.fail(&c, key + ".coefficients", "expected a coefficient's name and its printed number");
      p.coefficients.emplace_back(std::string(*(*a)[0].value<std::string>()), r.number((*a)[1], key + ".coefficients"));
    }
    std::vector<std::string> given;
    for (const auto& c : p.coefficients) given.push_back(c.first);
    if (given != names)
      r.fail(coefficients, key + ".coefficients",
             fmt::format("expected the coefficients of {} = {} in order: {}", p.parameter, p.law, fmt::join(names, ", ")));
    const toml::array* at = t.get("at") ? t.get("at")->as_array() : nullptr;
    if (!at || at->empty()) r.fail(&t, key + ".at", "expected at = [{ I = 0, amp = 0.01, freq = 1 }, ...]");
    for (const toml::node& c : *at) {
      const toml::table* vars = c.as_table();
      if (!vars) r.fail(&c, key + ".at", "expected a table of operating variables");
      std::map<std::string, double> values;
      for (const auto& [name, value] : *vars) values[std::string(name.str())] = r.number(value, key + ".at");
      for (const std::string& v : law.variables())
        if (!values.contains(v)) r.fail(&c, key + ".at", fmt::format("the law reads {}, which this condition lacks", v));
      p.at.push_back(std::move(values));
    }
    out.push_back(std::move(p));
  }
  return out;
}

}  // namespace

PaperFile parse_paper_file(std::string_view text, const std::string& path) {
  const Reader r(path);
  const toml::table root = spec_file::parse_toml(text, path);
  r.only_keys(root, "", {"paper", "title", "source", "tolerance_rel", "tables", "claims", "laws"});
  PaperFile out;
  out.paper = r.required_string(root, "paper", "");
  out.title = r.required_string(root, "title", "");
  out.source = r.required_string(root, "source", "");
  out.tolerance_rel = r.number(root, "tolerance_rel", "").value_or(0.1);
  if (!(out.tolerance_rel >= 0)) r.fail(root.get("tolerance_rel"), "tolerance_rel", "expected a number >= 0");
  out.tables = read_tables(r, root);
  out.claims = read_claims(r, root, out.tables);
  out.laws = read_laws(r, root);
  for (const auto& c : out.claims)
    if (!c.tables.empty()) check_ranking(r, c);
  return out;
}

}  // namespace dampbench::sweep
