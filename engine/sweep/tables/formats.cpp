// The `table` command's output formats: Markdown, CSV and LaTeX from the table itself, JSON with full-precision
// numbers from the cells' values.
#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "engine/common/error.hpp"
#include "engine/sweep/tables.hpp"

namespace dampbench::sweep {

std::string tables_to_json(const std::vector<Table>& tables) {
  nlohmann::ordered_json all = nlohmann::ordered_json::array();
  for (const auto& r : tables) {
    nlohmann::ordered_json t;
    t["id"] = r.id;
    t["title"] = r.title;
    t["paper"] = r.paper;
    t["note"] = r.note;
    t["columns"] = r.columns;
    nlohmann::ordered_json rows = nlohmann::ordered_json::array();
    for (const auto& row : r.rows) {
      nlohmann::ordered_json cells = nlohmann::ordered_json::array();
      for (const auto& c : row) {
        if (c.value && std::isfinite(*c.value)) cells.push_back(*c.value);
        else if (c.value) cells.push_back(std::isnan(*c.value) ? "nan" : (*c.value > 0 ? "inf" : "-inf"));
        else cells.push_back(c.text);
      }
      rows.push_back(std::move(cells));
    }
    t["rows"] = std::move(rows);
    all.push_back(std::move(t));
  }
  return nlohmann::ordered_json{{"tables", all}}.dump(2) + "\n";
}

std::string format_tables(const std::vector<Table>& tables, const std::string& format) {
  if (format == "json") return tables_to_json(tables);
  std::string out;
  for (const auto& r : tables) {
    if (format == "md") out += r.to_markdown() + "\n";
    else if (format == "csv") out += (tables.size() > 1 ? "# " + r.id + ": " + r.title + "\n" : "") + r.to_csv() + (tables.size() > 1 ? "\n" : "");
    else if (format == "latex") out += r.to_latex() + "\n";
    else throw InputError(fmt::format("--format: expected md, csv, latex or json, got '{}'", format));
  }
  if (tables.empty() && format != "md" && format != "csv" && format != "latex")
    throw InputError(fmt::format("--format: expected md, csv, latex or json, got '{}'", format));
  return out;
}

}  // namespace dampbench::sweep
