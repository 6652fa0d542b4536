#pragma once
// Reading sweep files (engine/sweep/spec.hpp): the TOML reader that names file, line and key in every message,
// the condition tables shared by several part kinds, and one reader per part kind (datasets, models,
// optimizers, metrics, splits, tables, regressions). read_part puts a part together from them.
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <toml++/toml.h>

#include "engine/common/error.hpp"
#include "engine/sweep/spec.hpp"

namespace dampbench::sweep::spec_file {

/// The operating variables a condition, a `by` or a `set` may name.
bool known_variable(std::string_view v);

/// Reading one TOML document with messages "file:line: key 'a.b[2]': what".
class Reader {
 public:
  explicit Reader(std::string path) : path_(std::move(path)) {}

  [[nodiscard]] const std::string& path() const { return path_; }

  [[nodiscard]] std::string where(const toml::node* n, std::string_view key) const {
    if (n && n->source().begin.line > 0) return fmt::format("{}:{}: key '{}'", path_, n->source().begin.line, key);
    return fmt::format("{}: key '{}'", path_, key);
  }
  [[noreturn]] void fail(const toml::node* n, std::string_view key, std::string_view what) const {
    throw InputError(where(n, key) + ": " + std::string(what));
  }
  /// Rethrows an InputError of a validator with this node's location.
  template <class Fn>
  auto check(const toml::node* n, std::string_view key, Fn&& fn) const {
    try {
      return fn();
    } catch (const InputError& e) {
      fail(n, key, e.what());
    }
  }

  /// Rejects keys that are not in `known`.
  void only_keys(const toml::table& t, std::string_view prefix, std::initializer_list<std::string_view> known) const {
    for (const auto& [k, v] : t) {
      if (std::find(known.begin(), known.end(), k.str()) != known.end()) continue;
      fail(&v, join(prefix, k.str()), fmt::format("unknown key (known here: {})", fmt::join(known, ", ")));
    }
  }

  static std::string join(std::string_view prefix, std::string_view key) {
    return prefix.empty() ? std::string(key) : fmt::format("{}.{}", prefix, key);
  }

  [[nodiscard]] std::optional<std::string> string(const toml::table& t, std::string_view key, std::string_view prefix) const {
    const toml::node* n = t.get(key);
    if (!n) return std::nullopt;
    if (!n->is_string()) fail(n, join(prefix, key), "expected a string");
    return std::string(*n->value<std::string>());
  }
  [[nodiscard]] std::string required_string(const toml::table& t, std::string_view key, std::string_view prefix) const {
    auto s = string(t, key, prefix);
    if (!s) {
      const int line = t.source().begin.line;
      if (line > 0 && !prefix.empty())
        throw InputError(fmt::format("{}:{}: missing key '{}' (expected a string)", path_, line, join(prefix, key)));
      throw InputError(fmt::format("{}: missing key '{}' (expected a string)", path_, join(prefix, key)));
    }
    return *s;
  }
  [[nodiscard]] std::int64_t integer(const toml::table& t, std::string_view key, std::string_view prefix,
                                     std::int64_t fallback, std::int64_t min) const {
    const toml::node* n = t.get(key);
    if (!n) return fallback;
    if (!n->is_integer()) fail(n, join(prefix, key), fmt::format("expected an integer >= {}", min));
    const auto v = *n->value<std::int64_t>();
    if (v < min) fail(n, join(prefix, key), fmt::format("expected an integer >= {}, got {}", min, v));
    return v;
  }
  [[nodiscard]] std::optional<double> number(const toml::table& t, std::string_view key, std::string_view prefix) const {
    const toml::node* n = t.get(key);
    if (!n) return std::nullopt;
    return number(*n, join(prefix, key));
  }
  [[nodiscard]] double number(const toml::node& n, std::string_view key) const {
    if (n.is_integer()) return static_cast<double>(*n.value<std::int64_t>());
    if (n.is_floating_point()) return *n.value<double>();
    fail(&n, key, "expected a number");
  }
  [[nodiscard]] bool boolean(const toml::table& t, std::string_view key, std::string_view prefix, bool fallback) const {
    const toml::node* n = t.get(key);
    if (!n) return fallback;
    if (!n->is_boolean()) fail(n, join(prefix, key), "expected true or false");
    return *n->value<bool>();
  }
  /// A string or an array of strings.
  [[nodiscard]] std::vector<std::string> strings(const toml::node& n, std::string_view key) const {
    std::vector<std::string> out;
    if (n.is_string()) return {std::string(*n.value<std::string>())};
    if (!n.is_array()) fail(&n, key, "expected a string or an array of strings");
    for (const toml::node& e : *n.as_array()) {
      if (!e.is_string()) fail(&e, key, "expected a string or an array of strings");
      out.emplace_back(*e.value<std::string>());
    }
    return out;
  }
  [[nodiscard]] std::vector<std::string> strings(const toml::table& t, std::string_view key, std::string_view prefix) const {
    const toml::node* n = t.get(key);
    return n ? strings(*n, join(prefix, key)) : std::vector<std::string>{};
  }
  /// A number or an array of numbers.
  [[nodiscard]] std::vector<double> numbers(const toml::node& n, std::string_view key) const {
    if (!n.is_array()) return {number(n, key)};
    std::vector<double> out;
    for (const toml::node& e : *n.as_array()) {
      if (!e.is_integer() && !e.is_floating_point()) fail(&e, key, "expected a number or an array of numbers");
      out.push_back(number(e, key));
    }
    if (out.empty()) fail(&n, key, "expected a number or a non-empty array of numbers");
    return out;
  }

 private:
  std::string path_;
};

/// A condition table { phi = [0, 30], amp = 0.001, name = "Test 1" }.
Condition read_condition(const Reader& r, const toml::node& n, const std::string& key);
/// A selection: one condition table, or an array of them (any of).
Selection read_selection(const Reader& r, const toml::node& n, const std::string& key);

/// Fails on the first of `names` that is not in `known` ("unknown model 'x' (known: a, b)").
void check_names(const Reader& r, const toml::node* n, const std::string& key, const std::vector<std::string>& names,
                 const std::vector<std::string>& known, std::string_view what);
std::vector<std::string> model_names(const PartSpec& part);
std::vector<std::string> optimizer_labels(const PartSpec& part);

// One reader per part kind, each filling its lists of `part`. Splits, tables and regressions name models,
// optimizers and dataset entries, so they are read after those (read_part keeps the order).
void read_metrics(const Reader& r, const toml::table& root, PartSpec& part);
void read_models(const Reader& r, const toml::table& root, PartSpec& part);
void read_optimizers(const Reader& r, const toml::table& root, PartSpec& part);
void read_splits(const Reader& r, const toml::table& root, PartSpec& part);
/// A model with laws = "auto" chooses its laws over the records of a group at a fixed budget, as `fit --laws auto`
/// does: every split it is in groups several records, and every optimizer it is identified with has a fixed budget.
void check_auto_laws(const Reader& r, const toml::table& root, const PartSpec& part);
/// A held model's source (`hold.from`, `hold.split`) names a model the split fits, which holds to nothing itself.
void check_holds(const Reader& r, const toml::table& root, const PartSpec& part);
void read_tables(const Reader& r, const toml::table& root, PartSpec& part);
void read_regressions(const Reader& r, const toml::table& root, PartSpec& part);
/// `[reproduction]` (published, data, truth, truth_is_compared_model); the published file must exist when
/// `check_files`.
void read_reproduction(const Reader& r, const toml::table& root, PartSpec& part, bool check_files);
/// Datasets, with their files checked and globs expanded when options.check_files; optional entries whose
/// files are missing are skipped with a line in `notes`.
void read_datasets(const Reader& r, const toml::table& root, const SpecOptions& options, PartSpec& part,
                   std::vector<std::string>& notes);

/// One part from the text of one sweep file; its notes are appended to `notes`.
PartSpec read_part(std::string_view text, const std::string& path, const SpecOptions& options,
                   std::vector<std::string>& notes);
toml::table parse_toml(std::string_view text, const std::string& path);
std::string read_text(const std::string& path, std::string_view what);


}  // namespace dampbench::sweep::spec_file
