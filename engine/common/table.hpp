#pragma once
// The one table type: what `fit`, `compare`, `evaluate` and the sweep's tables print, what the sweep writes as
// Markdown and CSV, and what the HTML report shows. A cell keeps its text and, when it holds a number, the number
// itself, so that JSON output and the report's figures read full precision while Markdown and CSV print the text.
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace dampbench {

struct Cell {
  std::string text;
  std::optional<double> value;  ///< the number behind the text, when there is one

  // Implicit from text, so that rows of plain strings read as they are written.
  Cell(std::string cell_text = {}, std::optional<double> cell_value = std::nullopt)
      : text(std::move(cell_text)), value(cell_value) {}
  Cell(const char* cell_text) : text(cell_text) {}
};

struct Table {
  std::string id;      ///< file stem, e.g. "table03_of_linear_viscous"
  std::string title;   ///< e.g. "Table 3. OF over 50 runs, fvd.linear_viscous"
  std::vector<std::string> columns;
  std::vector<std::vector<Cell>> rows;
  std::string paper = {};  ///< the paper's table it reproduces ("" when beyond the papers)
  std::string note = {};   ///< one line under the table

  /// The title in bold, the table, and the note under it.
  [[nodiscard]] std::string to_markdown() const;
  [[nodiscard]] std::string to_csv() const;  ///< RFC 4180 quoting where a cell needs it; no title, no note
  [[nodiscard]] std::string to_latex() const;
};

/// A cell holding a number, formatted by format_number.
Cell number_cell(double v);

/// Number formatting for tables: 6 significant digits, scientific outside [1e-3, 1e6).
std::string format_number(double v);

}  // namespace dampbench
