#include "engine/sweep/reproduction.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "engine/sweep/spec/reader.hpp"

namespace dampbench::sweep {
namespace {

using spec_file::Reader;

/// One [[tables]] entry of a paper file.
struct PublishedTable {
  std::string table, ours, label;
  std::vector<std::string> columns, compare;
  std::vector<std::pair<std::string, std::vector<double>>> rows;  ///< row label, a value per column (in our unit)
  double scale = 1;  ///< printed value × scale = the value in our table's unit (0.01: the paper prints %)
  std::string not_comparable;  ///< why its numbers cannot be set against ours (then only rankings are judged)
  std::string row_key;         ///< our table's column whose text names a row ("": its first column)
};

struct PublishedClaim {
  std::string id, text, column;
  std::vector<std::string> order;  ///< tables, best (lowest) first
  std::string note;                ///< what a verdict on it can mean (e.g. nested models)
  std::vector<const PublishedTable*> tables;  ///< the [[tables]] entries `order` names, in its order
};

/// Relative difference of ours from the paper's (0 when equal, +inf against a published 0).
double relative(double ours, double paper) {
  if (ours == paper) return 0.0;
  return paper == 0 ? std::numeric_limits<double>::infinity() : (ours - paper) / std::fabs(paper);
}

std::size_t column_index(const Table& t, const std::string& name) {
  return static_cast<std::size_t>(std::find(t.columns.begin(), t.columns.end(), name) - t.columns.begin());
}

/// The column of our table whose text names its rows: the paper file's `row_key`, else the first; t.columns.size()
/// when our table has no such column.
std::size_t row_label_column(const Table& t, const PublishedTable& p) {
  return p.row_key.empty() ? 0 : column_index(t, p.row_key);
}

/// Our table's cell at `row` (as row_label_column names rows) and `column`, for the paper's table `p`.
const Cell* our_cell(const Table& t, const PublishedTable& p, const std::string& row, const std::string& column) {
  const std::size_t j = column_index(t, column), key = row_label_column(t, p);
  if (j >= t.columns.size() || key >= t.columns.size()) return nullptr;
  for (const auto& r : t.rows)
    if (key < r.size() && r[key].text == row && j < r.size()) return &r[j];
  return nullptr;
}

std::optional<double> our_value(const Table& t, const PublishedTable& p, const std::string& row,
                                const std::string& column) {
  const Cell* cell = our_cell(t, p, row, column);
  return cell ? cell->value : std::nullopt;
}

/// Counts, per compared table's label, the numbers of ours that carry † (the tables' mark of a group whose runs end
/// more than 2 % apart or whose best still improved late), so that a verdict says when it rests on such fits.
struct Unconverged {
  std::map<std::string, int> by_label;
  void count(const Table* t, const PublishedTable& p, const std::string& row, const std::string& column) {
    const Cell* cell = t ? our_cell(*t, p, row, column) : nullptr;
    if (cell && cell->text.find("†") != std::string::npos) ++by_label[p.label];
  }
  [[nodiscard]] std::string note(std::size_t rows) const {
    if (by_label.empty()) return "";
    std::vector<std::string> parts;
    for (const auto& [label, n] : by_label) parts.push_back(fmt::format("{} at {} of {} rows", label, n, rows));
    return fmt::format("; ours not converged (†: runs more than 2 % apart, or a best still improving late): {}",
                       fmt::join(parts, ", "));
  }
};

const Table* find_table(const std::vector<Table>& ours, const std::string& id) {
  const auto it = std::find_if(ours.begin(), ours.end(), [&](const Table& t) { return t.id == id; });
  return it == ours.end() ? nullptr : &*it;
}

bool is_not_determined(const ReproductionItem& item, const std::string& label) {
  return std::find(item.not_determined.begin(), item.not_determined.end(), label) != item.not_determined.end();
}

/// "holds" or "differs" by the tolerance, with the largest difference as the detail; numbers the records do not
/// determine are left out (all of them: not-comparable).
void judge_numbers(ReproductionItem& item, double tolerance) {
  double worst = 0;
  std::size_t at = 0, judged = 0;
  for (std::size_t i = 0; i < item.values.size(); ++i) {
    if (is_not_determined(item, item.values[i].first)) continue;
    ++judged;
    const double d = std::fabs(relative(item.values[i].second, item.paper_values[i].second));
    if (!(d <= worst) || judged == 1) worst = d, at = i;
  }
  if (!item.values.empty() && judged == 0) {
    if (item.verdict.empty()) item.verdict = "not-comparable";
    item.detail = "the records determine none of these numbers of ours (‡)";
    return;
  }
  if (item.verdict.empty()) item.verdict = worst <= tolerance ? "holds" : "differs";
  if (judged > 0) {
    const std::string words = fmt::format("largest difference {}: ours {:.6g}, paper {:.6g} ({:+.1f} %)", item.values[at].first,
                                          item.values[at].second, item.paper_values[at].second,
                                          100 * relative(item.values[at].second, item.paper_values[at].second));
    item.detail = item.detail.empty() ? words : item.detail + "; " + words;
  }
}

std::vector<PublishedTable> read_tables(const Reader& r, const toml::table& root) {
  std::vector<PublishedTable> out;
  const toml::node* node = root.get("tables");
  if (!node || !node->is_array_of_tables()) r.fail(node, "tables", "expected one or more [[tables]]");
  int i = 0;
  for (const toml::node& n : *node->as_array()) {
    const std::string key = fmt::format("tables[{}]", i++);
    const toml::table& t = *n.as_table();
    r.only_keys(t, key, {"table", "ours", "label", "columns", "rows", "compare", "scale", "numbers_not_comparable", "row_key"});
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

std::vector<PublishedClaim> read_claims(const Reader& r, const toml::table& root, const std::vector<PublishedTable>& tables) {
  std::vector<PublishedClaim> out;
  const toml::node* node = root.get("claims");
  if (!node) return out;
  if (!node->is_array_of_tables()) r.fail(node, "claims", "expected [[claims]] tables");
  int i = 0;
  for (const toml::node& n : *node->as_array()) {
    const std::string key = fmt::format("claims[{}]", i++);
    const toml::table& t = *n.as_table();
    r.only_keys(t, key, {"id", "text", "column", "order", "note"});
    PublishedClaim c{r.string(t, "id", key).value_or(fmt::format("claim {}", i)), r.required_string(t, "text", key),
                     r.string(t, "column", key).value_or(""), r.strings(t, "order", key), r.string(t, "note", key).value_or(""),
                     {}};
    if (c.order.size() < 2) r.fail(&t, key + ".order", "expected two or more tables, best first");
    for (const auto& name : c.order) {
      const auto it = std::find_if(tables.begin(), tables.end(), [&](const PublishedTable& p) { return p.table == name; });
      if (it == tables.end()) r.fail(t.get("order"), key + ".order", fmt::format("no [[tables]] entry '{}'", name));
      c.tables.push_back(&*it);
      if (c.column.empty() && it->compare.size() != 1)
        r.fail(&t, key + ".column", fmt::format("'{}' compares {} columns: name the one the claim ranks by", name,
                                                it->compare.size()));
      if (!c.column.empty() && std::find(it->columns.begin(), it->columns.end(), c.column) == it->columns.end())
        r.fail(t.get("column"), key + ".column", fmt::format("'{}' has no column '{}'", name, c.column));
    }
    out.push_back(std::move(c));
  }
  return out;
}

/// `labels` (some of the item's numbers) as "N of M: label, label, ...".
std::string marked(const ReproductionItem& item, const std::vector<std::string>& labels) {
  return fmt::format("{} of {}: {}", labels.size(), item.values.size(), fmt::join(labels, ", "));
}

ReproductionItem table_item(const PublishedTable& p, const std::vector<Table>& ours, double tolerance) {
  ReproductionItem item{p.table, fmt::format("{} ({})", p.label, fmt::join(p.compare, ", ")), {}, {}, "", "", p.table};
  if (p.scale != 1) item.detail = fmt::format("the paper's printed values x {:g}", p.scale);
  const Table* t = find_table(ours, p.ours);
  if (!p.not_comparable.empty() && !t) {  // another damper's records: no number to set beside the paper's anyway
    item.verdict = "not-comparable";
    item.detail = p.not_comparable;
    return item;
  }
  if (!t) {
    item.verdict = "not-comparable";
    item.detail = fmt::format("this run wrote no table '{}'", p.ours);
    return item;
  }
  std::vector<std::string> at_bound;
  for (const auto& [row, values] : p.rows)
    for (const auto& column : p.compare) {
      const auto j = static_cast<std::size_t>(std::find(p.columns.begin(), p.columns.end(), column) - p.columns.begin());
      const Cell* cell = our_cell(*t, p, row, column);
      if (!cell || !cell->value) {
        item.verdict = "not-comparable";
        item.detail = fmt::format("table '{}' has no number at row '{}', column '{}'", p.ours, row, column);
        continue;
      }
      const std::string label = fmt::format("{} {}", row, column);
      item.paper_values.emplace_back(label, values[j]);
      item.values.emplace_back(label, *cell->value);
      if (cell->text.find("‡") != std::string::npos) item.not_determined.push_back(label);
      if (cell->text.find("⊥") != std::string::npos) at_bound.push_back(label);
    }
  if (!p.not_comparable.empty()) {
    item.verdict = "not-comparable";
    item.detail = p.not_comparable;
    return item;
  }
  judge_numbers(item, tolerance);
  if (!item.not_determined.empty())
    item.detail += "; not determined by the records (‡, not judged) " + marked(item, item.not_determined);
  if (!at_bound.empty()) item.detail += "; at a bound of the search box (⊥) " + marked(item, at_bound);
  return item;
}

ReproductionItem claim_item(const Reader& r, const PublishedClaim& c, const std::vector<Table>& ours, double tolerance) {
  const std::vector<const PublishedTable*>& order = c.tables;
  ReproductionItem item{fmt::format("{}", fmt::join(c.order, ", ")), c.text, {}, {}, "", "", c.id};
  std::map<std::string, std::vector<std::string>> reversed;  // "A above B" → the rows where it is
  Unconverged unconverged;
  for (const auto& first_table_row : order.front()->rows) {
    const std::string& row = first_table_row.first;  // a plain reference: lambdas below capture it (clang 14
    std::vector<double> paper, here;                 // does not capture structured bindings)
    for (const PublishedTable* p : order) {
      const std::string& column = c.column.empty() ? p->compare.front() : c.column;  // one compared column each
      const auto j = static_cast<std::size_t>(std::find(p->columns.begin(), p->columns.end(), column) - p->columns.begin());
      const auto prow = std::find_if(p->rows.begin(), p->rows.end(), [&](const auto& x) { return x.first == row; });
      const Table* t = find_table(ours, p->ours);
      const auto v = t ? our_value(*t, *p, row, column) : std::nullopt;
      if (prow == p->rows.end() || !v) {
        item.verdict = "not-comparable";
        item.detail = fmt::format("row '{}' of {} is missing from the paper file or from our table '{}'", row, p->table, p->ours);
        return item;
      }
      paper.push_back(prow->second[j]);
      here.push_back(*v);
      unconverged.count(t, *p, row, column);
      const std::string label = fmt::format("{}: {}", row, p->label);
      item.paper_values.emplace_back(label, paper.back());
      item.values.emplace_back(label, here.back());
    }
    for (std::size_t a = 0; a < order.size(); ++a)
      for (std::size_t b = a + 1; b < order.size(); ++b) {
        if (paper[a] > paper[b])
          r.fail(nullptr, "claims",
                 fmt::format("{} of {} ({:g}) is above {}'s ({:g}): `order` lists the tables best (lowest) first", row,
                             order[a]->table, paper[a], order[b]->table, paper[b]));
        if (paper[a] < paper[b] && here[a] > here[b])
          reversed[fmt::format("{} above {}", order[a]->label, order[b]->label)].push_back(row);
      }
  }
  if (!reversed.empty()) {
    item.verdict = "reversed";
    std::vector<std::string> pairs;
    const std::size_t rows = order.front()->rows.size();
    for (const auto& [pair, where] : reversed)
      pairs.push_back(where.size() == rows ? fmt::format("{} on every row ({})", pair, rows)
                                           : fmt::format("{} on {} of {} rows ({})", pair, where.size(), rows,
                                                         fmt::join(where, ", ")));
    item.detail = fmt::format("ranked the other way here: {}", fmt::join(pairs, "; "));
  }
  std::string reason;  // a table whose numbers cannot be set against ours: the ranking alone is judged
  for (const PublishedTable* p : order)
    if (!p->not_comparable.empty()) reason = p->not_comparable;
  if (!reason.empty()) {
    if (item.verdict.empty()) item.verdict = "holds";
    item.detail = (item.verdict == "reversed" ? item.detail : std::string("same ranking on every row")) +
                  "; ranking only, the numbers are not comparable: " + reason;
  } else {
    judge_numbers(item, tolerance);
    if (item.verdict != "reversed") item.detail = "same ranking on every row; " + item.detail;
  }
  item.detail += unconverged.note(order.front()->rows.size());
  if (!c.note.empty()) item.detail += ". " + c.note;
  return item;
}

/// A claim judged on every row of our first table (but its mean): each pair in `order` must rank that way in ours.
ReproductionItem claim_on_our_rows(const PublishedClaim& c, const std::vector<Table>& ours, const std::string& reason) {
  const std::vector<const PublishedTable*>& order = c.tables;
  ReproductionItem item{fmt::format("{}", fmt::join(c.order, ", ")), c.text, {}, {}, "", "", c.id};
  const Table* first = find_table(ours, order.front()->ours);
  if (!first) {
    item.verdict = "not-comparable";
    item.detail = fmt::format("this run wrote no table '{}'", order.front()->ours);
    return item;
  }
  std::map<std::string, std::vector<std::string>> reversed;
  Unconverged unconverged;
  std::size_t rows = 0;
  const std::size_t key = row_label_column(*first, *order.front());
  for (const auto& table_row : first->rows) {
    if (key >= table_row.size() || table_row[key].text == "mean") continue;
    const std::string& row = table_row[key].text;
    std::vector<double> here;
    for (const PublishedTable* p : order) {
      const std::string& column = c.column.empty() ? p->compare.front() : c.column;
      const Table* t = find_table(ours, p->ours);
      const auto v = t ? our_value(*t, *p, row, column) : std::nullopt;
      if (!v) {
        item.verdict = "not-comparable";
        item.detail = fmt::format("our table '{}' has no number at row '{}', column '{}'", p->ours, row, column);
        return item;
      }
      here.push_back(*v);
      unconverged.count(t, *p, row, column);
      item.values.emplace_back(fmt::format("{}: {}", row, p->label), *v);
    }
    ++rows;
    for (std::size_t a = 0; a < order.size(); ++a)
      for (std::size_t b = a + 1; b < order.size(); ++b)
        if (here[a] > here[b]) reversed[fmt::format("{} above {}", order[a]->label, order[b]->label)].push_back(row);
  }
  item.verdict = reversed.empty() ? "holds" : "reversed";
  std::vector<std::string> pairs;
  for (const auto& [pair, where] : reversed)
    pairs.push_back(fmt::format("{} on {} of {} rows ({})", pair, where.size(), rows, fmt::join(where, ", ")));
  item.detail = reversed.empty() ? fmt::format("the claim's ranking on every row of ours ({})", rows)
                                 : fmt::format("ranked the other way here: {}", fmt::join(pairs, "; "));
  item.detail += "; ranking only, at our conditions: " + reason + unconverged.note(rows);
  if (!c.note.empty()) item.detail += ". " + c.note;
  return item;
}

bool recovery_check(const Reproduction& r) { return r.data.data == "synthetic" && r.data.truth_is_compared_model; }

std::string data_sentence(const ReproductionSpec& d) {
  if (d.data == "real") return "real records";
  return fmt::format("synthetic records (truth: {}; {})", d.truth,
                     d.truth_is_compared_model ? "one of the compared models, so every verdict is a recovery check, "
                                                 "not evidence for the paper's claim"
                                               : "none of the compared models");
}

}  // namespace

Reproduction reproduce(const ReproductionSpec& spec, const std::vector<Table>& ours) {
  return reproduce_text(spec, spec_file::read_text(spec.published, "published numbers file"), ours);
}

Reproduction reproduce_text(const ReproductionSpec& spec, std::string_view text, const std::vector<Table>& ours) {
  const Reader r(spec.published);
  const toml::table root = spec_file::parse_toml(text, spec.published);
  r.only_keys(root, "", {"paper", "title", "source", "tolerance_rel", "tables", "claims"});
  Reproduction out;
  out.paper = r.required_string(root, "paper", "");
  out.title = r.required_string(root, "title", "");
  out.source = r.required_string(root, "source", "");
  out.tolerance_rel = r.number(root, "tolerance_rel", "").value_or(0.1);
  if (!(out.tolerance_rel >= 0)) r.fail(root.get("tolerance_rel"), "tolerance_rel", "expected a number >= 0");
  out.data = spec;
  auto tables = read_tables(r, root);
  for (auto& p : tables)
    if (p.not_comparable.empty()) p.not_comparable = spec.numbers_not_comparable;
  const auto claims = read_claims(r, root, tables);
  for (const auto& c : claims)
    out.items.push_back(spec.claims_on_our_rows ? claim_on_our_rows(c, ours, spec.numbers_not_comparable)
                                                : claim_item(r, c, ours, out.tolerance_rel));
  for (const auto& p : tables) {
    if (!spec.claims_on_our_rows) {
      out.items.push_back(table_item(p, ours, out.tolerance_rel));
      continue;
    }
    ReproductionItem item{p.table, fmt::format("{} ({})", p.label, fmt::join(p.compare, ", ")), {}, {},
                          "not-comparable", spec.numbers_not_comparable, p.table};
    out.items.push_back(std::move(item));
  }
  return out;
}

std::string reproduction_markdown(const Reproduction& r) {
  std::string md = fmt::format("# Reproduction of {}: {}\n\nThe paper's numbers as printed ({}), ours from this run's "
                               "tables, on {}. Numbers hold within ±{:g} % of the paper's.\n\n",
                               r.paper, r.title, r.source, data_sentence(r.data), 100 * r.tolerance_rel);
  md += "| item | claim | verdict | detail |\n|---|---|---|---|\n";
  for (const auto& i : r.items)
    md += fmt::format("| {} | {} | **{}**{} | {} |\n", i.id, i.claim, i.verdict, recovery_check(r) ? " (recovery check)" : "",
                      i.detail);
  for (const auto& i : r.items) {
    if (i.values.empty()) continue;
    if (i.paper_values.size() != i.values.size()) {  // a claim judged on our rows: no paper number beside ours
      md += fmt::format("\n**{}: {}** ({}; {})\n\n| | ours |\n|---|---:|\n", i.id, i.claim, i.table, i.verdict);
      for (const auto& [label, v] : i.values) md += fmt::format("| {} | {} |\n", label, format_number(v));
      continue;
    }
    md += fmt::format("\n**{}: {}** ({}; {})\n\n| | paper | ours | difference |\n|---|---:|---:|---:|\n", i.id, i.claim,
                      i.table, i.verdict);
    for (std::size_t k = 0; k < i.values.size(); ++k)
      md += fmt::format("| {} | {} | {}{} | {:+.1f} % |\n", i.values[k].first, format_number(i.paper_values[k].second),
                        format_number(i.values[k].second), is_not_determined(i, i.values[k].first) ? "‡" : "",
                        100 * relative(i.values[k].second, i.paper_values[k].second));
  }
  return md;
}

std::string reproduction_json(const Reproduction& r, const std::vector<std::string>& records) {
  nlohmann::ordered_json j;
  j["paper"] = r.paper;
  j["title"] = r.title;
  j["source"] = r.source;
  j["tolerance_rel"] = r.tolerance_rel;
  j["data"] = {{"kind", r.data.data},
               {"truth", r.data.truth},
               {"truth_is_compared_model", r.data.truth_is_compared_model},
               {"records", records}};
  j["items"] = nlohmann::ordered_json::array();
  for (const auto& i : r.items) {
    nlohmann::ordered_json paper = nlohmann::ordered_json::object(), ours = nlohmann::ordered_json::object();
    for (const auto& [label, v] : i.paper_values) paper[label] = v;
    for (const auto& [label, v] : i.values) ours[label] = v;
    j["items"].push_back({{"id", i.id},
                          {"table", i.table},
                          {"claim", i.claim},
                          {"paper_values", paper},
                          {"values", ours},
                          {"verdict", i.verdict},
                          {"detail", i.detail},
                          {"recovery_check", recovery_check(r)},
                          {"not_determined", i.not_determined}});
  }
  return j.dump(2) + "\n";
}

}  // namespace dampbench::sweep
