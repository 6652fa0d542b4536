#include <algorithm>
#include <fstream>
#include <iterator>
#include <sstream>

#include "engine/sweep/spec/reader.hpp"

namespace dampbench::sweep::spec_file {

namespace {

const char* const kVariables[] = {"I", "V", "phi", "amp", "freq", "w", "vamp"};

}  // namespace

bool known_variable(std::string_view v) {
  return std::any_of(std::begin(kVariables), std::end(kVariables), [&](const char* k) { return v == k; });
}

/// A condition table { phi = [0, 30], amp = 0.001, name = "Test 1" }.
Condition read_condition(const Reader& r, const toml::node& n, const std::string& key) {
  if (!n.is_table()) r.fail(&n, key, "expected a table of conditions, e.g. { I = [0, 0.5], amp = 0.01 }");
  Condition c;
  for (const auto& [k, v] : *n.as_table()) {
    const std::string name(k.str());
    const std::string sub = Reader::join(key, name);
    if (name == "name") {
      c.names = r.strings(v, sub);
    } else if (known_variable(name)) {
      c.variables.emplace_back(name, r.numbers(v, sub));
    } else {
      r.fail(&v, sub, "unknown condition (known: name, I, V, phi, amp, freq, w)");
    }
  }
  return c;
}

/// A selection: one condition table, or an array of them (any of).
Selection read_selection(const Reader& r, const toml::node& n, const std::string& key) {
  Selection s;
  if (n.is_array()) {
    const auto& a = *n.as_array();
    if (a.empty()) r.fail(&n, key, "expected a condition table or a non-empty array of them");
    for (std::size_t i = 0; i < a.size(); ++i) s.any.push_back(read_condition(r, *a.get(i), fmt::format("{}[{}]", key, i)));
  } else {
    s.any.push_back(read_condition(r, n, key));
  }
  return s;
}

void check_names(const Reader& r, const toml::node* n, const std::string& key, const std::vector<std::string>& names,
                 const std::vector<std::string>& known, std::string_view what) {
  for (const auto& name : names)
    if (std::find(known.begin(), known.end(), name) == known.end())
      r.fail(n, key, fmt::format("unknown {} '{}' (known: {})", what, name, fmt::join(known, ", ")));
}

std::vector<std::string> model_names(const PartSpec& part) {
  std::vector<std::string> v;
  for (const auto& m : part.models) v.push_back(m.name);
  return v;
}

std::vector<std::string> optimizer_labels(const PartSpec& part) {
  std::vector<std::string> v;
  for (const auto& o : part.optimizers) v.push_back(o.label);
  return v;
}

toml::table parse_toml(std::string_view text, const std::string& path) {
  try {
    return toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    throw InputError(fmt::format("{}:{}:{}: {}", path, e.source().begin.line, e.source().begin.column, e.description()));
  }
}

}  // namespace dampbench::sweep::spec_file
