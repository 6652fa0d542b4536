#pragma once
// A paper's file of published numbers (datasets/papers/<paper>.toml; its keys: engine/sweep/reproduction.hpp), read
// and checked against itself: a claim's ranking or largest row must be the one the paper's own numbers give.
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "engine/model/parameter_law.hpp"

namespace dampbench::sweep {

/// One [[tables]] entry of a paper file.
struct PublishedTable {
  std::string table, ours, label;
  std::vector<std::string> columns, compare;
  std::vector<std::pair<std::string, std::vector<double>>> rows;  ///< row label, a value per column (in our unit)
  double scale = 1;  ///< printed value × scale = the value in our table's unit (0.01: the paper prints %)
  std::string not_comparable;  ///< why its numbers cannot be set against ours (then only rankings are judged)
  std::string row_key;         ///< our table's column whose text names a row ("": its first column)
  /// The paper's numbers are levels of error its claim of accuracy rests on ("the maximum error is within 10 N"): on
  /// other records than the paper's, ours hold at or below them (within the tolerance above) and differ above.
  bool at_most = false;
};

/// One [[claims]] entry. Three forms:
///   ranking  `order` names [[tables]] entries, best (lowest) first, ranked by `column` on the paper's rows
///   largest  `table` names a [[tables]] entry whose row `largest` holds the largest value of `column` (paper and ours)
///   ours     a statement the paper makes without numbers, judged on our table `ours` alone: every row's `column`
///            has the `sign` ("positive" or "negative"), or on every row the columns `order` names rise (lowest
///            first; by magnitude with `magnitude = true`)
struct PublishedClaim {
  std::string id, text, column;
  std::vector<std::string> order;  ///< tables best (lowest) first; with `ours`: our table's columns, lowest first
  std::string note;                ///< what a verdict on it can mean (e.g. nested models)
  std::vector<const PublishedTable*> tables;  ///< the [[tables]] entries `order` names, in its order (ranking)
  const PublishedTable* table = nullptr;      ///< largest: the [[tables]] entry
  std::string largest;                        ///< largest: the row
  std::string ours;                           ///< ours: our table's id
  int sign = 0;                               ///< ours: +1 every value above 0, −1 below, 0 (the order form)
  bool magnitude = false;                     ///< ours, order form: compare |values|
  double margin = 0;                          ///< ours: differences within it (in the column's unit) are ties
};

/// One [[laws]] entry: a law the paper prints with its coefficients (mfm eqs. 10-11), set beside our regression of
/// the same parameter by the values both give at the conditions `at`, since a product's factors share a free scale
/// and their coefficients alone cannot be compared.
struct PublishedLaw {
  std::string table, ours, parameter, law, label;
  ParameterLaw parsed;  ///< `law` parsed
  double scale = 1;  ///< the printed law × scale = the parameter in our unit (eq. 10's × 10⁻³)
  std::vector<std::pair<std::string, double>> coefficients;  ///< by our coefficient names, as printed
  std::vector<std::map<std::string, double>> at;             ///< operating variables of each condition compared
};

struct PaperFile {
  std::string paper, title, source;
  double tolerance_rel = 0.1;  ///< numbers within it of the paper's hold
  std::vector<PublishedTable> tables;
  std::vector<PublishedClaim> claims;  ///< point into `tables` (move the file whole, never copy it)
  std::vector<PublishedLaw> laws;
};

/// The file's text parsed; InputError naming `path`, the line and the key for anything malformed.
PaperFile parse_paper_file(std::string_view text, const std::string& path);

}  // namespace dampbench::sweep
