#include "engine/sweep/spec.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <toml++/toml.h>

#include "engine/record/csv_loader.hpp"
#include "engine/common/error.hpp"
#include "engine/common/key_values.hpp"
#include "engine/model/law_model.hpp"
#include "engine/model/parameter_law.hpp"
#include "engine/common/random.hpp"
#include "engine/sweep/fingerprint.hpp"
#include "engine/sweep/tables.hpp"
#include "datasets/synthetic/grids.hpp"
#include "models/fixtures.hpp"
#include "models/registry.hpp"

#ifndef DAMPBENCH_SHARED_DATA_DIR
#define DAMPBENCH_SHARED_DATA_DIR "../shared/data"
#endif

namespace dampbench::sweep {

namespace fs = std::filesystem;

bool Selection::matches(const std::string& name, const std::map<std::string, double>& variables) const {
  if (any.empty()) return true;
  for (const Condition& c : any) {
    bool ok = c.names.empty() || std::find(c.names.begin(), c.names.end(), name) != c.names.end();
    for (const auto& [var, values] : c.variables) {
      if (!ok) break;
      const auto it = variables.find(var);
      ok = it != variables.end() && std::any_of(values.begin(), values.end(), [&](double v) {
             return std::fabs(it->second - v) <= 1e-9 * std::max(std::fabs(v), std::fabs(it->second)) ||
                    it->second == v;
           });
    }
    if (ok) return true;
  }
  return false;
}

int PartSpec::model_index(std::string_view n) const {
  for (std::size_t i = 0; i < models.size(); ++i)
    if (models[i].name == n) return static_cast<int>(i);
  return -1;
}
int PartSpec::optimizer_index(std::string_view n) const {
  for (std::size_t i = 0; i < optimizers.size(); ++i)
    if (optimizers[i].label == n) return static_cast<int>(i);
  return -1;
}
int PartSpec::split_index(std::string_view n) const {
  for (std::size_t i = 0; i < splits.size(); ++i)
    if (splits[i].name == n) return static_cast<int>(i);
  return -1;
}

std::string generated_dir() {
  if (const char* env = std::getenv("DAMPBENCH_GENERATED_DIR"); env && *env) return env;
  fs::path cache;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) cache = xdg;
  else if (const char* home = std::getenv("HOME"); home && *home) cache = fs::path(home) / ".cache";
  else cache = fs::temp_directory_path();
  // One folder per build identity, so that two builds sharing a cache never regenerate each other's grids.
  return (cache / "dampbench" / fmt::format("generated-{:016x}", hash_name(generator_identity()))).string();
}

std::string generator_identity() { return fmt::format("dampbench {} ({})", dampbench_version(), build_flags()); }

void ensure_generated(std::string_view text, std::vector<std::string>& notes) {
  constexpr std::string_view prefix = "@generated/";
  if (!text.starts_with(prefix)) return;
  const std::string_view rest = text.substr(prefix.size());
  const std::string grid(rest.substr(0, rest.find('/')));
  const auto& known = synthetic::grid_names();
  if (std::find(known.begin(), known.end(), grid) == known.end())
    throw InputError(fmt::format("'{}' names no synthetic grid (known: {})", text, fmt::join(known, ", ")));
  const std::string root = generated_dir();
  if (synthetic::ensure_grid(root, grid, generator_identity()) != synthetic::GridState::kPresent)
    notes.push_back(fmt::format("generated the synthetic grid '{}' into {}", grid, (fs::path(root) / grid).string()));
}

std::string shared_data_dir() {
  if (const char* env = std::getenv("DAMPBENCH_SHARED_DATA_DIR"); env && *env) return env;
  return DAMPBENCH_SHARED_DATA_DIR;
}

std::string resolve_path(std::string_view text, const std::string& folder) {
  auto under = [&](std::string_view prefix, const std::string& dir) -> std::optional<std::string> {
    if (!text.starts_with(prefix)) return std::nullopt;
    return (fs::path(dir) / fs::path(std::string(text.substr(prefix.size())))).lexically_normal().string();
  };
  if (auto p = under("@generated/", generated_dir())) return *p;
  if (auto p = under("@shared/", shared_data_dir())) return *p;
  const fs::path p{std::string(text)};
  if (p.is_absolute()) return p.lexically_normal().string();
  return (fs::path(folder) / p).lexically_normal().string();
}

namespace {

const char* const kVariables[] = {"I", "V", "phi", "amp", "freq", "w"};
bool known_variable(std::string_view v) {
  return std::any_of(std::begin(kVariables), std::end(kVariables), [&](const char* k) { return v == k; });
}

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

std::string setting_text(const Reader& r, const toml::node& v, const std::string& key) {
  if (v.is_string()) return std::string(*v.value<std::string>());
  if (v.is_integer()) return std::to_string(*v.value<std::int64_t>());
  if (v.is_floating_point()) return fmt::format("{}", *v.value<double>());
  if (v.is_boolean()) return *v.value<bool>() ? "true" : "false";
  r.fail(&v, key, "expected a string, number or boolean");
}

OptimizerEntry read_optimizer(const Reader& r, const toml::table& t, const std::string& key) {
  r.only_keys(t, key, {"label", "name", "population", "iterations", "runs", "settings", "max_evaluations", "target",
                       "stall_iterations"});
  OptimizerEntry o;
  o.spec.name = r.string(t, "name", key).value_or("pso");
  o.label = r.string(t, "label", key).value_or(o.spec.name);
  o.spec.population = static_cast<int>(r.integer(t, "population", key, 50, 2));
  o.spec.iterations = static_cast<int>(r.integer(t, "iterations", key, 100, 1));
  o.runs = static_cast<int>(r.integer(t, "runs", key, 0, 1));
  o.budget.max_evaluations = r.integer(t, "max_evaluations", key, 0, 0);
  o.budget.stall_iterations = static_cast<int>(r.integer(t, "stall_iterations", key, 0, 0));
  if (auto target = r.number(t, "target", key)) o.budget.target = *target;
  if (const toml::node* s = t.get("settings")) {
    if (!s->is_table()) r.fail(s, Reader::join(key, "settings"), "expected a table of settings, e.g. { pc = 0.6 }");
    for (const auto& [k, v] : *s->as_table())
      o.spec.settings[std::string(k.str())] = setting_text(r, v, Reader::join(key, "settings." + std::string(k.str())));
  }
  r.check(&t, key, [&] { return make_optimizer_factory(o.spec); });
  return o;
}

ModelSpec read_model(const Reader& r, const toml::node& n, const std::string& key) {
  ModelSpec m;
  if (n.is_string()) {
    const std::string id(*n.value<std::string>());
    // A registered model, else a law fixture; the message lists the models.
    try {
      find_model(id);
      m.model = id;
    } catch (const InputError& e) {
      try {
        find_fixture(id);
        m.fixture = id;
      } catch (const InputError&) {
        r.fail(&n, key, e.what());
      }
    }
    m.name = id;
    return m;
  }
  if (!n.is_table()) r.fail(&n, key, "expected a model id or a table { name, model | fixture, laws, bounds, optimizers }");
  const toml::table& t = *n.as_table();
  r.only_keys(t, key, {"name", "model", "fixture", "laws", "bounds", "optimizers"});
  m.model = r.string(t, "model", key).value_or("");
  m.fixture = r.string(t, "fixture", key).value_or("");
  if (m.model.empty() == m.fixture.empty()) r.fail(&n, key, "expected exactly one of 'model' and 'fixture'");
  if (!m.model.empty()) r.check(t.get("model"), Reader::join(key, "model"), [&] { return &find_model(m.model); });
  if (!m.fixture.empty()) r.check(t.get("fixture"), Reader::join(key, "fixture"), [&] { return &find_fixture(m.fixture); });
  m.laws = r.string(t, "laws", key).value_or("");
  m.bounds = r.string(t, "bounds", key).value_or("");
  m.name = r.string(t, "name", key).value_or(m.model.empty() ? m.fixture : m.model);
  m.optimizers = r.strings(t, "optimizers", key);
  return m;
}

/// Expands a glob whose wildcards (*, ?) are in the file name only; sorted by name.
std::vector<std::string> expand_glob(const std::string& pattern) {
  const fs::path p(pattern);
  const std::string name = p.filename().string();
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");  // a bare pattern: the current folder
  auto match = [](std::string_view pat, std::string_view s, auto&& self) -> bool {
    if (pat.empty()) return s.empty();
    if (pat[0] == '*') return self(pat.substr(1), s, self) || (!s.empty() && self(pat, s.substr(1), self));
    if (s.empty()) return false;
    return (pat[0] == '?' || pat[0] == s[0]) && self(pat.substr(1), s.substr(1), self);
  };
  std::vector<std::string> out;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return out;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    if (!e.is_regular_file()) continue;
    const std::string f = e.path().filename().string();
    if (match(name, f, match)) out.push_back(p.has_parent_path() ? (dir / f).string() : f);
  }
  std::sort(out.begin(), out.end());
  return out;
}

struct PartReader {
  const Reader& r;
  const SpecOptions& options;
  PartSpec part;
  std::vector<std::string> notes;

  std::string folder() const { return fs::path(r.path()).parent_path().string(); }

  void read_datasets(const toml::table& root) {
    const toml::node* datasets = root.get("datasets");
    if (!datasets || !datasets->is_array_of_tables() || datasets->as_array()->empty())
      r.fail(datasets, "datasets", "expected one or more [[datasets]] tables");
    std::map<std::string, std::string> seen;  // dataset name → where
    const auto& a = *datasets->as_array();
    for (std::size_t i = 0; i < a.size(); ++i) {
      const std::string key = fmt::format("datasets[{}]", i);
      const toml::table& t = *a.get(i)->as_table();
      r.only_keys(t, key, {"name", "label", "file", "files", "glob", "units", "columns", "transform", "average",
                           "conditions", "set", "required"});
      const std::string name = r.required_string(t, "name", key);
      if (std::find(part.collections.begin(), part.collections.end(), name) != part.collections.end())
        r.fail(t.get("name"), Reader::join(key, "name"), fmt::format("dataset entry name '{}' is used twice", name));
      part.collections.push_back(name);
      RecordOptions load;
      load.units = r.string(t, "units", key).value_or("");
      load.columns = r.string(t, "columns", key).value_or("");
      load.transform = r.string(t, "transform", key).value_or("");
      load.average = r.string(t, "average", key).value_or("");
      load.conditions = r.string(t, "conditions", key).value_or("");
      load.set = r.string(t, "set", key).value_or("");
      check_load_options(t, key, load);
      const bool required = r.boolean(t, "required", key, true) && !options.datasets_optional;
      const int sources = (t.get("file") != nullptr) + (t.get("files") != nullptr) + (t.get("glob") != nullptr);
      if (sources != 1) r.fail(&t, key, "expected exactly one of 'file', 'files' and 'glob'");

      std::vector<std::string> files;
      const bool single = t.get("file") != nullptr;
      const toml::node* source_node = t.get("file") ? t.get("file") : t.get("files") ? t.get("files") : t.get("glob");
      const std::string source_key = Reader::join(key, t.get("file") ? "file" : t.get("files") ? "files" : "glob");
      if (options.check_files)  // "@generated/" grids are generated on first use
        for (const auto& text : r.strings(*source_node, source_key))
          r.check(source_node, source_key, [&] { ensure_generated(text, notes); });
      if (t.get("glob")) {
        const std::string pattern = resolve_path(r.required_string(t, "glob", key), folder());
        if (options.check_files) {
          files = expand_glob(pattern);
          if (files.empty()) {
            if (!required) {
              notes.push_back(fmt::format("{}: skipped (optional): no file matches '{}'", r.where(source_node, source_key), pattern));
              continue;
            }
            r.fail(source_node, source_key, fmt::format("no file matches '{}'", pattern));
          }
        }
      } else {
        for (const auto& f : r.strings(*source_node, source_key)) files.push_back(resolve_path(f, folder()));
        if (files.empty()) r.fail(source_node, source_key, "expected at least one file");
      }
      if (options.check_files) {
        bool missing_optional = false;
        for (const auto& f : files) {
          std::error_code ec;
          if (fs::is_regular_file(f, ec)) continue;
          if (!required) {
            missing_optional = true;
            break;
          }
          r.fail(source_node, source_key, fmt::format("cannot open data file '{}'", f));
        }
        if (missing_optional) {
          notes.push_back(fmt::format("{}: skipped (optional): missing files", r.where(source_node, source_key)));
          continue;
        }
      }
      for (const auto& f : files) {
        DatasetSpec d;
        d.collection = name;
        d.name = single ? name : fs::path(f).stem().string();
        d.label = single ? r.string(t, "label", key).value_or(name) : d.name;
        d.load = load;
        d.load.path = f;
        if (auto [it, fresh] = seen.emplace(d.name, key); !fresh)
          r.fail(source_node, source_key, fmt::format("dataset name '{}' is already used by {}", d.name, it->second));
        part.datasets.push_back(std::move(d));
      }
    }
  }

  void check_load_options(const toml::table& t, const std::string& key, const RecordOptions& load) const {
    if (!load.units.empty()) r.check(t.get("units"), Reader::join(key, "units"), [&] { return parse_units_option(load.units); });
    if (!load.columns.empty()) r.check(t.get("columns"), Reader::join(key, "columns"), [&] { return split_list(load.columns, "columns"); });
    if (!load.transform.empty() && load.transform != "slider-crank" && load.transform != "slider-crank-printed")
      r.fail(t.get("transform"), Reader::join(key, "transform"),
             fmt::format("expected slider-crank or slider-crank-printed, got '{}'", load.transform));
    if (!load.conditions.empty() && load.conditions != "utfsm")
      r.fail(t.get("conditions"), Reader::join(key, "conditions"), fmt::format("expected utfsm, got '{}'", load.conditions));
    if (!load.average.empty()) {
      r.check(t.get("average"), Reader::join(key, "average"), [&] {
        for (const auto& [k, v] : parse_key_values(load.average, "average")) {
          const double n = parse_number(v, "average " + k);
          if (n != std::floor(n) || n < 0) throw InputError(fmt::format("average {}: expected a whole number, got '{}'", k, v));
          if (k != "cycles" && k != "drop") throw InputError(fmt::format("average: unknown key '{}' (expected cycles, drop)", k));
        }
        return 0;
      });
    }
    if (!load.set.empty()) {
      r.check(t.get("set"), Reader::join(key, "set"), [&] {
        for (const auto& [k, v] : parse_key_values(load.set, "set")) {
          if (k != "I" && k != "V" && k != "phi" && k != "amp" && k != "freq")
            throw InputError(fmt::format("set: unknown operating variable '{}' (known: I, V, phi, amp, freq)", k));
          parse_number(v, "set " + k);
        }
        return 0;
      });
    }
  }

  void read_models(const toml::table& root) {
    const toml::node* models = root.get("models");
    if (!models || !models->is_array() || models->as_array()->empty())
      r.fail(models, "models", "expected a non-empty array of model ids or model tables");
    const auto& a = *models->as_array();
    for (std::size_t i = 0; i < a.size(); ++i) {
      const toml::node& n = *a.get(i);
      const std::string key = n.is_string() ? "models" : fmt::format("models[{}]", i);
      ModelSpec m = read_model(r, n, key);
      if (part.model_index(m.name) >= 0) r.fail(&n, key, fmt::format("model name '{}' is used twice", m.name));
      part.models.push_back(std::move(m));
    }
    if (const toml::node* b = root.get("bounds")) {
      if (!b->is_table()) r.fail(b, "bounds", "expected a table [bounds] of model = \"name=lo:hi,...\"");
      for (const auto& [k, v] : *b->as_table()) {
        const std::string id(k.str());
        if (!v.is_string()) r.fail(&v, id, "expected a string \"name=lo:hi,...\"");
        const int m = part.model_index(id);
        if (m < 0) r.fail(&v, id, fmt::format("no model named '{}' in 'models'", id));
        auto& bounds = part.models[m].bounds;
        bounds += (bounds.empty() ? "" : ",") + std::string(*v.value<std::string>());
      }
    }
    // Build every model once: laws, bounds and names are checked here, before anything runs.
    for (std::size_t i = 0; i < part.models.size(); ++i) {
      const ModelSpec& m = part.models[i];
      const toml::node* n = a.get(i);
      std::string key = n->is_string() ? "models" : fmt::format("models[{}]", i);
      if (const toml::node* b = root.get("bounds"); b && b->as_table()->get(m.name)) {
        n = b->as_table()->get(m.name);
        key = m.name;
      }
      r.check(n, key, [&] { return resolve_model(m); });
    }
  }

  void read_optimizers(const toml::table& root) {
    const toml::node* one = root.get("optimizer");
    const toml::node* many = root.get("optimizers");
    if (one && many) r.fail(many, "optimizers", "give either [optimizer] or [[optimizers]], not both");
    if (one) {
      if (!one->is_table()) r.fail(one, "optimizer", "expected a table [optimizer]");
      part.optimizers.push_back(read_optimizer(r, *one->as_table(), "optimizer"));
    } else if (many) {
      if (!many->is_array_of_tables() || many->as_array()->empty())
        r.fail(many, "optimizers", "expected one or more [[optimizers]] tables");
      const auto& a = *many->as_array();
      for (std::size_t i = 0; i < a.size(); ++i) {
        const std::string key = fmt::format("optimizers[{}]", i);
        OptimizerEntry o = read_optimizer(r, *a.get(i)->as_table(), key);
        if (part.optimizer_index(o.label) >= 0)
          r.fail(a.get(i), key, fmt::format("optimizer label '{}' is used twice (give each a 'label')", o.label));
        part.optimizers.push_back(std::move(o));
      }
    } else {
      part.optimizers.push_back(OptimizerEntry{"pso", OptimizerSpec{}, Budget{}, 0});
    }
    const toml::node* models = root.get("models");
    for (std::size_t i = 0; i < part.models.size(); ++i)
      for (const auto& label : part.models[i].optimizers)
        if (part.optimizer_index(label) < 0)
          r.fail(models->as_array()->get(i), fmt::format("models[{}].optimizers", i),
                 fmt::format("no optimizer labelled '{}'", label));
  }

  void read_metrics(const toml::table& root) {
    const toml::node* one = root.get("metric");
    const toml::node* many = root.get("metrics");
    if (one && many) r.fail(many, "metrics", "give either 'metric' or 'metrics', not both");
    const toml::node* n = one ? one : many;
    if (!n) return;
    const std::string key = one ? "metric" : "metrics";
    if (one && !one->is_string()) r.fail(one, key, "expected a metric name");
    part.metrics.clear();
    for (const auto& name : r.strings(*n, key)) {
      const Metric m = r.check(n, key, [&] { return parse_metric(name); });
      if (std::find(part.metrics.begin(), part.metrics.end(), m) != part.metrics.end())
        r.fail(n, key, fmt::format("metric '{}' is listed twice", name));
      part.metrics.push_back(m);
    }
    if (part.metrics.empty()) r.fail(n, key, "expected at least one metric");
  }

  void check_names(const toml::node* n, const std::string& key, const std::vector<std::string>& names,
                   const std::vector<std::string>& known, std::string_view what) const {
    for (const auto& name : names)
      if (std::find(known.begin(), known.end(), name) == known.end())
        r.fail(n, key, fmt::format("unknown {} '{}' (known: {})", what, name, fmt::join(known, ", ")));
  }
  std::vector<std::string> model_names() const {
    std::vector<std::string> v;
    for (const auto& m : part.models) v.push_back(m.name);
    return v;
  }
  std::vector<std::string> optimizer_labels() const {
    std::vector<std::string> v;
    for (const auto& o : part.optimizers) v.push_back(o.label);
    return v;
  }

  SensitivitySpec read_sensitivity(const toml::node& n, const std::string& key) const {
    SensitivitySpec s;
    if (n.is_boolean()) {
      s.enabled = *n.value<bool>();
      return s;
    }
    if (!n.is_table()) r.fail(&n, key, "expected true or a table { points, range, objective, normalized, where }");
    const toml::table& t = *n.as_table();
    r.only_keys(t, key, {"points", "range", "objective", "normalized", "where"});
    s.enabled = true;
    s.points = static_cast<int>(r.integer(t, "points", key, 21, 3));
    s.range = r.number(t, "range", key).value_or(0.5);
    if (!(s.range > 0 && s.range < 1)) r.fail(t.get("range"), Reader::join(key, "range"), "expected a number in (0, 1)");
    s.objective = r.string(t, "objective", key).value_or("rms");
    if (s.objective != "rms") r.check(t.get("objective"), Reader::join(key, "objective"), [&] { return parse_metric(s.objective); });
    s.normalized = r.boolean(t, "normalized", key, false);
    if (const toml::node* w = t.get("where")) s.where = read_selection(r, *w, Reader::join(key, "where"));
    return s;
  }

  void read_splits(const toml::table& root) {
    const toml::node* splits = root.get("splits");
    if (!splits) {
      part.splits.push_back(SplitSpec{});
      return;
    }
    if (!splits->is_array_of_tables() || splits->as_array()->empty())
      r.fail(splits, "splits", "expected one or more [[splits]] tables");
    const auto& a = *splits->as_array();
    for (std::size_t i = 0; i < a.size(); ++i) {
      const std::string key = fmt::format("splits[{}]", i);
      const toml::table& t = *a.get(i)->as_table();
      r.only_keys(t, key, {"name", "datasets", "models", "optimizers", "fit", "predict", "by", "sensitivity"});
      SplitSpec s;
      s.name = r.string(t, "name", key).value_or(fmt::format("split{}", i + 1));
      if (part.split_index(s.name) >= 0) r.fail(t.get("name"), Reader::join(key, "name"), fmt::format("split name '{}' is used twice", s.name));
      s.collections = r.strings(t, "datasets", key);
      check_names(t.get("datasets"), Reader::join(key, "datasets"), s.collections, part.collections, "dataset entry");
      s.models = r.strings(t, "models", key);
      check_names(t.get("models"), Reader::join(key, "models"), s.models, model_names(), "model");
      s.optimizers = r.strings(t, "optimizers", key);
      check_names(t.get("optimizers"), Reader::join(key, "optimizers"), s.optimizers, optimizer_labels(), "optimizer");
      if (const toml::node* f = t.get("fit")) s.fit = read_selection(r, *f, Reader::join(key, "fit"));
      if (const toml::node* p = t.get("predict")) s.predict = read_selection(r, *p, Reader::join(key, "predict"));
      if (const toml::node* b = t.get("by")) {
        const std::string bkey = Reader::join(key, "by");
        if (b->is_string() && *b->value<std::string>() == "each") s.by = SplitSpec::By::each;
        else if (b->is_string() && *b->value<std::string>() == "all") s.by = SplitSpec::By::all;
        else if (b->is_array()) {
          s.by = SplitSpec::By::variables;
          s.by_variables = r.strings(*b, bkey);
          for (const auto& v : s.by_variables)
            if (!known_variable(v)) r.fail(b, bkey, fmt::format("unknown operating variable '{}' (known: I, V, phi, amp, freq, w)", v));
          if (s.by_variables.empty()) s.by = SplitSpec::By::all;
        } else {
          r.fail(b, bkey, "expected \"each\", \"all\" or an array of operating variables, e.g. [\"I\"]");
        }
      }
      if (const toml::node* n = t.get("sensitivity")) s.sensitivity = read_sensitivity(*n, Reader::join(key, "sensitivity"));
      part.splits.push_back(std::move(s));
    }
  }

  TableSpec read_table(const toml::node& n, const std::string& key) const {
    TableSpec ts;
    if (n.is_string()) {
      ts.kind = *n.value<std::string>();
    } else {
      if (!n.is_table()) r.fail(&n, key, "expected a table kind or a table { kind, paper, split, models, ... }");
      const toml::table& t = *n.as_table();
      r.only_keys(t, key, {"kind", "name", "title", "paper", "split", "models", "optimizers", "metric", "role", "where",
                           "target_rel"});
      ts.kind = r.required_string(t, "kind", key);
      ts.name = r.string(t, "name", key).value_or("");
      ts.title = r.string(t, "title", key).value_or("");
      ts.paper = r.string(t, "paper", key).value_or("");
      ts.splits = r.strings(t, "split", key);
      for (const auto& sp : ts.splits)
        if (part.split_index(sp) < 0) r.fail(t.get("split"), Reader::join(key, "split"), fmt::format("unknown split '{}'", sp));
      ts.models = r.strings(t, "models", key);
      check_names(t.get("models"), Reader::join(key, "models"), ts.models, model_names(), "model");
      ts.optimizers = r.strings(t, "optimizers", key);
      check_names(t.get("optimizers"), Reader::join(key, "optimizers"), ts.optimizers, optimizer_labels(), "optimizer");
      ts.metric = r.string(t, "metric", key).value_or("");
      if (!ts.metric.empty()) r.check(t.get("metric"), Reader::join(key, "metric"), [&] { return parse_metric(ts.metric); });
      ts.role = r.string(t, "role", key).value_or("");
      if (!ts.role.empty() && ts.role != "fit" && ts.role != "predict")
        r.fail(t.get("role"), Reader::join(key, "role"), fmt::format("expected fit or predict, got '{}'", ts.role));
      if (const toml::node* w = t.get("where")) ts.where = read_selection(r, *w, Reader::join(key, "where"));
      ts.target_rel = r.number(t, "target_rel", key).value_or(0.01);
      if (!(ts.target_rel >= 0)) r.fail(t.get("target_rel"), Reader::join(key, "target_rel"), "expected a number >= 0");
    }
    const auto kinds = table_kinds();
    if (std::find(kinds.begin(), kinds.end(), ts.kind) == kinds.end())
      r.fail(&n, key, fmt::format("unknown table kind '{}' (known: {})", ts.kind, fmt::join(kinds, ", ")));
    return ts;
  }

  void read_tables(const toml::table& root) {
    const toml::node* tables = root.get("tables");
    if (!tables) {
      // The fvd paper's set: run statistics, parameter statistics, variability and the ranking.
      TableSpec t;
      t.kind = "fvd";
      part.tables.push_back(std::move(t));
      return;
    }
    if (tables->is_string()) {
      part.tables.push_back(read_table(*tables, "tables"));
      return;
    }
    if (!tables->is_array()) r.fail(tables, "tables", "expected a table kind or an array of kinds and [[tables]]");
    const auto& a = *tables->as_array();
    for (std::size_t i = 0; i < a.size(); ++i) part.tables.push_back(read_table(*a.get(i), fmt::format("tables[{}]", i)));
  }

  void read_regressions(const toml::table& root) {
    const toml::node* regs = root.get("regressions");
    if (!regs) return;
    if (!regs->is_array_of_tables()) r.fail(regs, "regressions", "expected [[regressions]] tables");
    const auto& a = *regs->as_array();
    for (std::size_t i = 0; i < a.size(); ++i) {
      const std::string key = fmt::format("regressions[{}]", i);
      const toml::table& t = *a.get(i)->as_table();
      r.only_keys(t, key, {"name", "model", "split", "optimizer", "laws", "paper", "where"});
      RegressionSpec g;
      g.model = r.required_string(t, "model", key);
      const int m = part.model_index(g.model);
      if (m < 0) r.fail(t.get("model"), Reader::join(key, "model"), fmt::format("unknown model '{}' (known: {})", g.model, fmt::join(model_names(), ", ")));
      g.name = r.string(t, "name", key).value_or(fmt::format("regression{}", i + 1));
      g.split = r.string(t, "split", key).value_or("");
      if (!g.split.empty() && part.split_index(g.split) < 0)
        r.fail(t.get("split"), Reader::join(key, "split"), fmt::format("unknown split '{}'", g.split));
      g.optimizer = r.string(t, "optimizer", key).value_or("");
      if (!g.optimizer.empty() && part.optimizer_index(g.optimizer) < 0)
        r.fail(t.get("optimizer"), Reader::join(key, "optimizer"), fmt::format("unknown optimizer '{}'", g.optimizer));
      g.laws = r.required_string(t, "laws", key);
      g.paper = r.string(t, "paper", key).value_or("");
      r.check(t.get("laws"), Reader::join(key, "laws"), [&] {
        const ResolvedModel model = resolve_model(part.models[m]);
        for (const auto& [name, law] : parse_laws(g.laws, "laws")) {
          (void)model.model->parameter_index(name);
          if (law.kind == ParameterLaw::Kind::fixed)
            throw InputError(fmt::format("laws {}: a regression needs a law with coefficients, got a number", name));
        }
        return 0;
      });
      if (const toml::node* w = t.get("where")) g.where = read_selection(r, *w, Reader::join(key, "where"));
      part.regressions.push_back(std::move(g));
    }
  }

  /// Canonical JSON of the keys that decide results (not titles, labels, tables or regressions).
  std::string canonical(const toml::table& root) const {
    toml::table copy = root;
    for (const char* k : {"title", "tables", "regressions"}) copy.erase(k);
    if (auto* d = copy.get("datasets"); d && d->is_array()) {
      for (auto& e : *d->as_array())
        if (e.is_table()) e.as_table()->erase("label");
    }
    std::ostringstream out;
    out << toml::json_formatter{copy};
    return out.str();
  }

  void read(const toml::table& root) {
    r.only_keys(root, "", {"name", "title", "seed", "runs", "metric", "metrics", "models", "bounds", "optimizer",
                           "optimizers", "datasets", "splits", "tables", "regressions"});
    part.path = r.path();
    part.name = r.required_string(root, "name", "");
    part.title = r.string(root, "title", "").value_or(part.name);
    part.seed = static_cast<std::uint64_t>(r.integer(root, "seed", "", 1, 0));
    part.runs = static_cast<int>(r.integer(root, "runs", "", 50, 1));
    read_metrics(root);
    read_models(root);
    read_optimizers(root);
    // Tables and splits name datasets entries: read entry names first, files last (a bad bound is
    // reported before a missing file).
    const toml::node* datasets = root.get("datasets");
    if (!datasets || !datasets->is_array_of_tables() || datasets->as_array()->empty())
      r.fail(datasets, "datasets", "expected one or more [[datasets]] tables");
    for (const toml::node& d : *datasets->as_array()) {
      const toml::node* n = d.as_table()->get("name");
      if (n && n->is_string()) part.collections.emplace_back(*n->value<std::string>());
    }
    read_splits(root);
    read_tables(root);
    read_regressions(root);
    part.collections.clear();
    read_datasets(root);
    part.canonical = canonical(root);
  }
};

toml::table parse_toml(std::string_view text, const std::string& path) {
  try {
    return toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    throw InputError(fmt::format("{}:{}:{}: {}", path, e.source().begin.line, e.source().begin.column, e.description()));
  }
}

std::string read_text(const std::string& path, std::string_view what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("cannot open {} '{}'", what, path));
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

PartSpec read_part(std::string_view text, const std::string& path, const SpecOptions& options, std::vector<std::string>& notes) {
  const toml::table root = parse_toml(text, path);
  const Reader r(path);
  PartReader pr{r, options, {}, {}};
  pr.read(root);
  pr.part.source = std::string(text);
  notes.insert(notes.end(), pr.notes.begin(), pr.notes.end());
  return std::move(pr.part);
}

std::string hex64(std::uint64_t v) { return fmt::format("{:016x}", v); }

}  // namespace

static SweepSpec parse_sweep_text(std::string_view text, const std::string& path, const SpecOptions& options);

SweepSpec parse_sweep(std::string_view text, const std::string& path, const SpecOptions& options) {
  return as_data_error([&] { return parse_sweep_text(text, path, options); });
}

static SweepSpec parse_sweep_text(std::string_view text, const std::string& path, const SpecOptions& options) {
  SweepSpec spec;
  spec.path = path;
  std::vector<std::string> notes;
  const toml::table root = parse_toml(text, path);
  if (const toml::node* inc = root.get("include")) {
    const Reader r(path);
    r.only_keys(root, "", {"name", "title", "include", "include_optional"});
    spec.name = r.required_string(root, "name", "");
    spec.title = r.string(root, "title", "").value_or(spec.name);
    auto files = r.strings(*inc, "include");
    const auto optional = r.strings(root, "include_optional", "");
    files.insert(files.end(), optional.begin(), optional.end());
    if (files.empty()) r.fail(inc, "include", "expected one or more sweep files");
    for (std::size_t i = 0; i < files.size(); ++i) {
      const std::string p = resolve_path(files[i], fs::path(path).parent_path().string());
      const std::string t = r.check(inc, "include", [&] { return read_text(p, "included sweep file"); });
      SpecOptions part_options = options;
      part_options.datasets_optional |= i + optional.size() >= files.size();
      spec.parts.push_back(read_part(t, p, part_options, notes));
      for (std::size_t k = 0; k + 1 < spec.parts.size(); ++k)
        if (spec.parts[k].name == spec.parts.back().name)
          r.fail(inc, "include", fmt::format("two included files are named '{}'", spec.parts.back().name));
    }
  } else {
    spec.parts.push_back(read_part(text, path, options, notes));
    spec.name = spec.parts[0].name;
    spec.title = spec.parts[0].title;
  }
  std::uint64_t h = hash_name("dampbench-sweep-1");
  for (const auto& p : spec.parts) h = hash_key({h, hash_name(p.name), hash_name(p.canonical)});
  spec.hash = hex64(h);
  spec.notes = std::move(notes);
  return spec;
}

SweepSpec load_sweep(const std::string& path, const SpecOptions& options) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw DataError(fmt::format("cannot open preset file '{}'", path));
  return parse_sweep(read_text(path, "preset file"), path, options);
}

}  // namespace dampbench::sweep
