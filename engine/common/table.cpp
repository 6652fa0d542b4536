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

std::vector<std::string> texts(const std::vector<Cell>& row) {
  std::vector<std::string> out;
  out.reserve(row.size());
  for (const Cell& c : row) out.push_back(c.text);
  return out;
}

std::string join_row(const std::vector<std::string>& cells, bool csv) {
  std::string line = csv ? "" : "|";
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (csv) line += (i ? "," : "") + csv_cell(cells[i]);
    else line += " " + cells[i] + " |";
  }
  return line + "\n";
}

std::string latex_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': case '%': case '$': case '#': case '_': case '{': case '}': out += '\\'; out += c; break;
      case '~': out += "\\textasciitilde{}"; break;
      case '^': out += "\\textasciicircum{}"; break;
      case '\\': out += "\\textbackslash{}"; break;
      default: out += c;
    }
  }
  return out;
}

std::string latex_row(const std::vector<std::string>& cells) {
  std::string s;
  for (std::size_t i = 0; i < cells.size(); ++i) s += (i ? " & " : "") + latex_escape(cells[i]);
  return s + " \\\\\n";
}

}  // namespace

std::string Table::to_markdown() const {
  std::string out = title.empty() ? "" : "**" + title + "**\n\n";
  out += join_row(columns, false);
  out += "|";
  for (std::size_t i = 0; i < columns.size(); ++i) out += i == 0 ? "---|" : "---:|";
  out += "\n";
  for (const auto& r : rows) out += join_row(texts(r), false);
  if (!note.empty()) out += "\n" + note + "\n";
  return out;
}

std::string Table::to_csv() const {
  std::string out = join_row(columns, true);
  for (const auto& r : rows) out += join_row(texts(r), true);
  return out;
}

std::string Table::to_latex() const {
  std::string out = "\\begin{table}[htbp]\n\\centering\n";
  out += "\\caption{" + latex_escape(title) + "}\n\\label{tab:" + latex_escape(id) + "}\n";
  out += "\\begin{tabular}{l" + std::string(columns.empty() ? 0 : columns.size() - 1, 'r') + "}\n\\hline\n";
  out += latex_row(columns) + "\\hline\n";
  for (const auto& row : rows) out += latex_row(texts(row));
  out += "\\hline\n\\end{tabular}\n";
  if (!note.empty()) out += "\\par\\footnotesize " + latex_escape(note) + "\n";
  out += "\\end{table}\n";
  return out;
}

Cell number_cell(double v) { return {format_number(v), v}; }

std::string format_number(double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  if (std::isnan(v)) return "nan";
  const double a = std::fabs(v);
  if (a != 0 && (a < 1e-3 || a >= 1e6)) return fmt::format("{:.5e}", v);
  return fmt::format("{:.6g}", v);
}

}  // namespace dampbench
