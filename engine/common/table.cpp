#include "engine/common/table.hpp"

#include <cmath>

#include <fmt/format.h>

namespace dampbench {
namespace {

std::string csv_cell(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += (c == '"') ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string join_row(const std::vector<std::string>& cells, bool csv) {
  std::string line = csv ? "" : "|";
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (csv) line += (i ? "," : "") + csv_cell(cells[i]);
    else line += " " + cells[i] + " |";
  }
  return line + "\n";
}

}  // namespace

std::string Table::to_markdown() const {
  std::string out = title.empty() ? "" : "**" + title + "**\n\n";
  out += join_row(columns, false);
  out += "|";
  for (std::size_t i = 0; i < columns.size(); ++i) out += i == 0 ? "---|" : "---:|";
  out += "\n";
  for (const auto& r : rows) out += join_row(r, false);
  return out;
}

std::string Table::to_csv() const {
  std::string out = join_row(columns, true);
  for (const auto& r : rows) out += join_row(r, true);
  return out;
}

std::string format_number(double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  if (std::isnan(v)) return "nan";
  const double a = std::fabs(v);
  if (a != 0 && (a < 1e-3 || a >= 1e6)) return fmt::format("{:.5e}", v);
  return fmt::format("{:.6g}", v);
}

}  // namespace dampbench
