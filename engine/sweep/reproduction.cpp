#include "engine/sweep/reproduction.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdio>
#include <map>
#include <optional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "engine/model/parameter_law.hpp"
#include "engine/sweep/paper_file.hpp"
#include "engine/sweep/spec/reader.hpp"

namespace dampbench::sweep {
namespace {

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
/// determine are left out (all of them: not-comparable). With `at_most` (the paper's numbers are levels of error) a
/// number of ours holds at any distance below the paper's, and only an excess above it counts.
void judge_numbers(ReproductionItem& item, double tolerance, bool at_most = false) {
  double worst = 0;
  std::size_t at = 0, judged = 0, above = 0;
  for (std::size_t i = 0; i < item.values.size(); ++i) {
    if (is_not_determined(item, item.values[i].first)) continue;
    ++judged;
    const double signed_d = relative(item.values[i].second, item.paper_values[i].second);
    const double d = at_most ? signed_d : std::fabs(signed_d);
    above += at_most && signed_d > tolerance;
    if (!(d <= worst) || judged == 1) worst = d, at = i;
  }
  if (!item.values.empty() && judged == 0) {
    if (item.verdict.empty()) item.verdict = "not-comparable";
    item.detail = "the records determine none of these numbers of ours (‡)";
    return;
  }
  if (item.verdict.empty()) item.verdict = worst <= tolerance ? "holds" : "differs";
  if (at_most && judged > 0)
    item.detail += fmt::format("{}{} of {} numbers of ours above the paper's level by more than {:g} %",
                               item.detail.empty() ? "" : "; ", above, judged, 100 * tolerance);
  if (judged > 0) {
    const std::string words = fmt::format("{} {}: ours {:.6g}, paper {:.6g} ({:+.1f} %)",
                                          at_most ? "highest against the paper's level" : "largest difference", item.values[at].first,
                                          item.values[at].second, item.paper_values[at].second,
                                          100 * relative(item.values[at].second, item.paper_values[at].second));
    item.detail = item.detail.empty() ? words : item.detail + "; " + words;
  }
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
  judge_numbers(item, tolerance, p.at_most);
  if (!item.not_determined.empty())
    item.detail += "; not determined by the records (‡, not judged) " + marked(item, item.not_determined);
  if (!at_bound.empty()) item.detail += "; at a bound of the search box (⊥) " + marked(item, at_bound);
  return item;
}

ReproductionItem claim_item(const PublishedClaim& c, const std::vector<Table>& ours, double tolerance) {
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
      for (std::size_t b = a + 1; b < order.size(); ++b)
        if (paper[a] < paper[b] && here[a] > here[b])
          reversed[fmt::format("{} above {}", order[a]->label, order[b]->label)].push_back(row);
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

/// The rows of our table `t` (its first column names them; "mean" rows left out) with a number in `column`.
std::vector<std::pair<std::string, double>> our_column(const Table& t, const std::string& column) {
  std::vector<std::pair<std::string, double>> out;
  const std::size_t j = column_index(t, column);
  for (const auto& row : t.rows)
    if (j < row.size() && row[j].value && row[0].text != "mean") out.emplace_back(row[0].text, *row[j].value);
  return out;
}

/// A `largest` claim: the paper's row holds the largest value of the column; does ours?
ReproductionItem largest_item(const PublishedClaim& c, const std::vector<Table>& ours) {
  const PublishedTable& p = *c.table;
  ReproductionItem item{p.table, c.text, {}, {}, "", "", c.id};
  const Table* t = find_table(ours, p.ours);
  const auto j = static_cast<std::size_t>(std::find(p.columns.begin(), p.columns.end(), c.column) - p.columns.begin());
  for (const auto& [row, values] : p.rows) {
    const auto v = t ? our_value(*t, p, row, c.column) : std::nullopt;
    if (!v) {
      item.verdict = "not-comparable";
      item.detail = fmt::format("our table '{}' has no number at row '{}', column '{}'", p.ours, row, c.column);
      return item;
    }
    const std::string label = fmt::format("{} {}", row, c.column);
    item.paper_values.emplace_back(label, values[j]);
    item.values.emplace_back(label, *v);
  }
  const auto top = std::max_element(item.values.begin(), item.values.end(),
                                    [](const auto& a, const auto& b) { return a.second < b.second; }) - item.values.begin();
  const std::string& row = p.rows[static_cast<std::size_t>(top)].first;  // values follow the paper's rows
  const double value = item.values[static_cast<std::size_t>(top)].second;
  item.verdict = row == c.largest ? "holds" : "reversed";
  item.detail = item.verdict == "holds"
                    ? fmt::format("the largest {} is {}'s here too ({:.6g})", c.column, c.largest, value)
                    : fmt::format("the largest {} here is {}'s ({:.6g}), not {}'s", c.column, row, value, c.largest);
  if (!c.note.empty()) item.detail += ". " + c.note;
  return item;
}

/// An `ours` claim: a sign of one column on every row, or columns that rise on every row.
ReproductionItem ours_claim_item(const PublishedClaim& c, const std::vector<Table>& ours) {
  ReproductionItem item{c.ours, c.text, {}, {}, "", "", c.id};
  const Table* t = find_table(ours, c.ours);
  if (!t) {
    item.verdict = "not-comparable";
    item.detail = fmt::format("this run wrote no table '{}'", c.ours);
    return item;
  }
  const std::vector<std::string> columns = c.sign != 0 ? std::vector<std::string>{c.column} : c.order;
  std::vector<std::vector<std::pair<std::string, double>>> values;
  for (const auto& column : columns) {
    values.push_back(our_column(*t, column));
    if (values.back().empty() || values.back().size() != values.front().size()) {
      item.verdict = "not-comparable";
      item.detail = fmt::format("our table '{}' has no number in column '{}' on some row", c.ours, column);
      return item;
    }
  }
  // Per row, how far it lies in the claim's direction: the value times the sign, or each next column's lead over the
  // one before (the smallest lead); beyond the margin it confirms, below −margin it contradicts, else a tie.
  std::vector<std::string> against, ties;
  for (std::size_t i = 0; i < values.front().size(); ++i) {
    const std::string& row = values.front()[i].first;
    for (std::size_t k = 0; k < columns.size(); ++k)
      item.values.emplace_back(fmt::format("{}: {}", row, columns[k]), values[k][i].second);
    double lead = std::numeric_limits<double>::infinity();
    if (c.sign != 0) lead = c.sign * values.front()[i].second;
    for (std::size_t k = 0; c.sign == 0 && k + 1 < columns.size(); ++k) {
      const double a = values[k][i].second, b = values[k + 1][i].second;
      lead = std::min(lead, c.magnitude ? std::fabs(b) - std::fabs(a) : b - a);
    }
    if (lead < -c.margin) against.push_back(row);
    else if (!(lead > c.margin)) ties.push_back(row);
  }
  const std::size_t rows = values.front().size();
  const std::string what = c.sign != 0 ? fmt::format("{} {} 0", c.column, c.sign > 0 ? ">" : "<")
                                       : fmt::format("{}{} rising", c.magnitude ? "|values| of " : "", fmt::join(columns, ", "));
  const std::string margin = c.margin > 0 ? fmt::format(" by more than {:g}", c.margin) : "";
  item.verdict = !against.empty() ? "reversed" : !ties.empty() ? "differs" : "holds";
  if (item.verdict == "holds") item.detail = fmt::format("{}{} on every row of ours ({})", what, margin, rows);
  if (!against.empty())
    item.detail = fmt::format("the other way{} on {} of {} rows ({})", margin, against.size(), rows, fmt::join(against, ", "));
  if (!ties.empty())
    item.detail += fmt::format("{}neither way{} on {} of {} rows ({})", item.detail.empty() ? "" : "; ",
                               c.margin > 0 ? fmt::format(" beyond ±{:g}", c.margin) : "", ties.size(), rows, fmt::join(ties, ", "));
  item.detail = fmt::format("claim: {}; ", what) + item.detail;
  item.detail += "; the paper prints no number for it, so ours alone are judged";
  if (!c.note.empty()) item.detail += ". " + c.note;
  return item;
}

/// Our regression of `parameter` in table `t` (columns Parameter, Law, Coefficient, Value, "Not identifiable at"):
/// its law, its coefficients by name and whether the records determined it at none of the conditions.
struct OurLaw {
  std::string law;
  std::map<std::string, double> coefficients;
  bool determined_nowhere = false;
};
std::optional<OurLaw> our_law(const Table& t, const std::string& parameter) {
  const std::size_t name = column_index(t, "Parameter"), law = column_index(t, "Law"),
                    coefficient = column_index(t, "Coefficient"), value = column_index(t, "Value"),
                    undetermined = column_index(t, "Not identifiable at");
  const std::size_t columns = t.columns.size();
  if (name >= columns || law >= columns || coefficient >= columns || value >= columns) return std::nullopt;
  std::optional<OurLaw> out;
  bool in = false;
  for (const auto& row : t.rows) {
    if (row.size() < columns) continue;
    if (!row[name].text.empty()) in = row[name].text == parameter;
    if (!in) continue;
    if (!out) {
      out = OurLaw{row[law].text, {}, false};
      int a = -1, b = -2;  // "‡ 112 of 112": not determined at every condition
      if (undetermined < columns && std::sscanf(row[undetermined].text.c_str(), "‡ %d of %d", &a, &b) == 2) out->determined_nowhere = a == b;
    }
    if (row[value].value) out->coefficients[row[coefficient].text] = *row[value].value;
  }
  return out;
}

/// A [[laws]] entry: the paper's law and our regression of the same parameter evaluated at each condition.
ReproductionItem law_item(const PublishedLaw& p, const std::vector<Table>& ours, double tolerance,
                          const std::string& not_comparable) {
  ReproductionItem item{p.table, fmt::format("{}: {} = {}", p.label, p.parameter, p.law), {}, {}, "", "", p.table};
  const Table* t = find_table(ours, p.ours);
  const std::optional<OurLaw> mine = t ? our_law(*t, p.parameter) : std::nullopt;
  if (!mine) {
    item.verdict = "not-comparable";
    item.detail = fmt::format("this run wrote no regression of {} in a table '{}'", p.parameter, p.ours);
    return item;
  }
  const ParameterLaw mine_law = parse_law(mine->law, p.ours);
  std::vector<double> mine_coefficients, paper_coefficients;
  for (const std::string& c : mine_law.coefficient_names(p.parameter)) {
    const auto it = mine->coefficients.find(c);
    if (it == mine->coefficients.end()) {
      item.verdict = "not-comparable";
      item.detail = fmt::format("table '{}' has no coefficient {}", p.ours, c);
      return item;
    }
    mine_coefficients.push_back(it->second);
  }
  const ParameterLaw& paper_law = p.parsed;
  for (const auto& c : p.coefficients) paper_coefficients.push_back(c.second);
  for (const auto& at : p.at) {
    std::vector<std::string> where;
    for (const std::string& v : paper_law.variables()) where.push_back(fmt::format("{}={:g}", v, at.at(v)));
    const std::string label = fmt::format("{} at {}", p.parameter, fmt::join(where, ", "));
    item.paper_values.emplace_back(label, p.scale * paper_law.evaluate(paper_coefficients.data(), at));
    item.values.emplace_back(label, mine_law.evaluate(mine_coefficients.data(), at));
    if (mine->determined_nowhere) item.not_determined.push_back(label);
  }
  if (!not_comparable.empty()) {
    item.verdict = "not-comparable";
    item.detail = not_comparable;
    return item;
  }
  item.detail = fmt::format("the two laws' values at {} conditions (a product's factors share a free scale, so its "
                            "coefficients alone are not compared)", p.at.size());
  judge_numbers(item, tolerance);  // not-comparable when the records determine our parameter nowhere
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
  PaperFile paper = parse_paper_file(text, spec.published);
  Reproduction out;
  out.paper = paper.paper;
  out.title = paper.title;
  out.source = paper.source;
  out.tolerance_rel = paper.tolerance_rel;
  out.data = spec;
  for (auto& p : paper.tables) {
    const auto own = std::find_if(spec.tables_not_comparable.begin(), spec.tables_not_comparable.end(),
                                  [&](const auto& entry) { return entry.first == p.ours; });
    if (p.not_comparable.empty())
      p.not_comparable = own != spec.tables_not_comparable.end() ? own->second : spec.numbers_not_comparable;
  }
  for (const auto& c : paper.claims) {
    if (!c.ours.empty())
      out.items.push_back(ours_claim_item(c, ours));
    else if (c.table)
      out.items.push_back(largest_item(c, ours));
    else
      out.items.push_back(spec.claims_on_our_rows ? claim_on_our_rows(c, ours, spec.numbers_not_comparable)
                                                  : claim_item(c, ours, out.tolerance_rel));
  }
  for (const auto& p : paper.tables) {
    if (!spec.claims_on_our_rows) {
      out.items.push_back(table_item(p, ours, out.tolerance_rel));
      continue;
    }
    ReproductionItem item{p.table, fmt::format("{} ({})", p.label, fmt::join(p.compare, ", ")), {}, {},
                          "not-comparable", spec.numbers_not_comparable, p.table};
    out.items.push_back(std::move(item));
  }
  for (const auto& p : paper.laws)
    out.items.push_back(law_item(p, ours, out.tolerance_rel, spec.numbers_not_comparable));
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
