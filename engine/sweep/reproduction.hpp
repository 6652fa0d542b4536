#pragma once
// The reproduction report of a preset (`reproduction.md`, `reproduction.json` beside its tables): each published
// table or claim of a paper beside the same numbers from our tables, the difference, and a verdict.
//
// The paper's numbers live in a file of their own (datasets/papers/<paper>.toml, as printed, each table cited; read by
// engine/sweep/paper_file.hpp):
//   paper, title, source, tolerance_rel (numbers within it "hold")
//   [[tables]]  table ("Table 3"), ours (the id of our table with the same rows and columns), label (what the
//               table is of, e.g. the model), columns, rows = [["Test 1", 0.32, ...], ...], compare (the columns
//               compared; default all), scale (printed value × scale = ours, e.g. 0.01 for a paper's %; default 1),
//               numbers_not_comparable (the reason, when only rankings can be judged: another metric or unit)
//   [[claims]]  id (short, for the report's rows), text, note (what a verdict can mean), and one of
//               - order = the tables best (lowest) first as the paper's numbers rank them, column (the one they are
//                 ranked by; optional when each table compares one);
//               - table (a [[tables]] entry), column, largest = the row the paper says holds the largest value of
//                 that column (its own numbers must agree): judged on ours, `reversed` naming our largest;
//               - ours = the id of our table, for a statement the paper prints no number for, judged on our rows
//                 alone: sign = "positive"/"negative" of `column` on every row, or order = our table's columns that
//                 rise on every row, lowest first (magnitude = true: their absolute values); margin (in the column's
//                 unit, default 0): a row within it is neither way, and a verdict with such rows and none the other
//                 way is `differs`
//   [[laws]]    table ("eq. 10"), ours (our regression table: Parameter, Law, Coefficient, Value), parameter, law
//               (as --laws writes it), scale, coefficients = [["A_I0", 6.578], ...] in the law's order, at = the
//               conditions [{ I = 0, amp = 0.01, freq = 1 }, ...]: both laws' values there are compared, since a
//               product's factors share a free scale (our parameter determined at no condition: shown, not judged)
// Verdicts (fixed vocabulary):
//   holds           same ranking (a claim) and every number within tolerance_rel of the paper's (or the same
//                   ranking alone, said so, when the numbers are not comparable)
//   differs         same ranking, some number outside the tolerance
//   reversed        a pair the paper ranks one way (strictly) ranks the other way here
//   not-comparable  with the reason (our table is missing, a row or column the paper has and ours has not, or every
//                   number of ours is one the records do not determine)
// A number of ours marked ‡ (a parameter the records do not determine: identifiability, engine/fit) is shown beside
// the paper's but left out of the verdict, and the item names it (`not_determined`); one marked ⊥ (at a bound of the
// search box) is judged and named.
// A preset's `[reproduction] numbers_not_comparable` (records of another damper than the paper's) makes every table
// ranking-only; with `rows = "ours"` (records at other conditions than the paper's: its protocol on the real damper)
// each claim is judged on every row of our tables in the claim's order, without the paper's rows.
// A verdict on synthetic records whose truth is one of the compared models is a recovery check, never evidence
// for the paper's claim; the report says so on the item.
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "engine/common/table.hpp"
#include "engine/sweep/spec.hpp"

namespace dampbench::sweep {

struct ReproductionItem {
  std::string table;  ///< "Table 3", or the claim's tables
  std::string claim;  ///< the claim's text, or what the table holds
  std::vector<std::pair<std::string, double>> paper_values, values;  ///< same labels, in the same order
  std::string verdict;
  std::string detail;  ///< why: the largest difference, the reversed pairs, the missing table
  std::string id;      ///< a claim's id (its `id`, else "claim N"), or the table's name
  /// Labels of `values` our tables mark ‡ (a parameter the records do not determine): listed, never judged, since
  /// any value of it fits the records as well (a recovery check asks for the determined ones only).
  std::vector<std::string> not_determined = {};
};

struct Reproduction {
  std::string paper, title, source;
  double tolerance_rel = 0;
  ReproductionSpec data;
  std::vector<ReproductionItem> items;
};

/// The report of the paper file `spec.published` against `ours` (one part's tables). InputError naming the file,
/// line and key for a malformed paper file.
Reproduction reproduce(const ReproductionSpec& spec, const std::vector<Table>& ours);
/// The same from the paper file's text (spec.published names it in messages; fuzz_sweep_spec feeds it).
Reproduction reproduce_text(const ReproductionSpec& spec, std::string_view text, const std::vector<Table>& ours);

std::string reproduction_markdown(const Reproduction& r);
/// {"paper", "title", "source", "tolerance_rel", "data": {kind, truth, truth_is_compared_model, records},
///  "items": [{id, table, claim, paper_values, values, verdict, detail, recovery_check, not_determined}]}
std::string reproduction_json(const Reproduction& r, const std::vector<std::string>& records);

}  // namespace dampbench::sweep
