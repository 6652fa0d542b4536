#pragma once
// A titled table of text cells, written as Markdown or CSV (the papers' tables, DESIGN.md "Outputs").
#include <string>
#include <vector>

namespace dampbench {

struct Table {
  std::string id;      ///< file stem, e.g. "table03_of_linear_viscous"
  std::string title;   ///< e.g. "Table 3. OF over 50 runs, fvd.linear_viscous"
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;

  [[nodiscard]] std::string to_markdown() const;
  [[nodiscard]] std::string to_csv() const;  ///< RFC 4180 quoting where a cell needs it
};

/// Number formatting for tables: 6 significant digits, scientific outside [1e-3, 1e6).
std::string format_number(double v);

}  // namespace dampbench
