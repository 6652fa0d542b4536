#include "optimizers/registry.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <type_traits>
#include <variant>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "engine/common/error.hpp"
#include "engine/common/key_values.hpp"

namespace dampbench {
namespace {

/// An unknown setting, with the names the optimizer knows (what optimizer_settings lists).
class UnknownSetting : public InputError {
 public:
  UnknownSetting(const std::string& message, std::vector<std::string> known_names)
      : InputError(message), known(std::move(known_names)) {}
  std::vector<std::string> known;
};

// The settings that pick a name, as read and as listed.
const ChoiceSetting kPsoVariant{"variant",
                                {"inertia", "constriction", "linear_inertia"},
                                "inertia",
                                "inertia: constant w (Shi & Eberhart 1998); constriction: Clerc & Kennedy's χ with c1 = c2 = "
                                "2.05; linear_inertia: w from 0.9 to 0.4 with c1 = c2 = 2 (Shi & Eberhart 1999)"};
const ChoiceSetting kGaPreset{"preset", {"lssvm"}, "none",
                              "lssvm: the lssvm paper's GA (pc 0.6, pm 0.03, 50 × 500, η_c 15, one elite)"};
const ChoiceSetting kDeStrategy{"strategy", {"rand1bin", "best1bin", "currenttobest1bin"}, "rand1bin",
                                "mutation base and crossover (Storn & Price 1997)"};
const ChoiceSetting kCmaesRestarts{"restarts", {"none", "ipop", "bipop"}, "ipop",
                                   "ipop: each restart doubles the population; bipop: large and small runs alternate; "
                                   "none: one run, which may end before the budget"};
const ChoiceSetting kHybridGlobal{"global", {"ga", "cmaes"}, "ga",
                                  "the population phase: ga (its settings apply) or cmaes (cmaes's apply)"};

/// Reads one optimizer's settings map: `apply` sets fields from the optimizer's table (setting_table.hpp),
/// `choice` and `text` read the rest; `finish` rejects any key no call asked for, listing the known ones.
class SettingsReader {
 public:
  SettingsReader(std::string_view optimizer, const std::map<std::string, std::string>& settings)
      : optimizer_(optimizer), settings_(settings) {}

  /// The raw value of `key`, or nullptr.
  [[nodiscard]] const std::string* text(std::string_view key) {
    if (std::ranges::find(known_, key) == known_.end()) known_.push_back(key);
    const auto it = settings_.find(std::string(key));
    return it == settings_.end() ? nullptr : &it->second;
  }

  /// The number `key` gives (nullopt when absent); InputError for text that is not one, or not a whole number
  /// when `whole`. Its range is the optimizer's validate()'s to check.
  [[nodiscard]] std::optional<double> number(std::string_view key, bool whole) {
    const std::string* t = text(key);
    if (!t) return std::nullopt;
    const double v = parse_number(trim(*t), what(key));
    if (whole && (v != std::floor(v) || std::abs(v) > std::numeric_limits<int>::max()))
      throw InputError(fmt::format("{}: expected a whole number, got '{}'", what(key), *t));
    return v;
  }

  /// Sets each field of `s` whose key is given, in the table's order.
  template <class S>
  void apply(const SettingTable<S>& table, S& s) {
    for (const auto& row : table) {
      const std::optional<double> v = number(row.key, row.range.whole);
      if (!v) continue;
      std::visit(
          [&](auto field) {
            auto& target = s.*field;
            if constexpr (requires { target.has_value(); })
              target = static_cast<typename std::remove_cvref_t<decltype(target)>::value_type>(*v);
            else
              target = static_cast<std::remove_cvref_t<decltype(target)>>(*v);
          },
          row.field);
    }
  }

  /// The name `c.key` gives if it is one of `c.names` (empty when absent); otherwise InputError.
  [[nodiscard]] std::string choice(const ChoiceSetting& c) {
    const std::string* t = text(c.key);
    if (!t) return {};
    const std::string_view v = trim(*t);
    if (std::ranges::find(c.names, v) == c.names.end())
      throw InputError(fmt::format("{}: unknown {} '{}' (known: {})", optimizer_, c.key, v, fmt::join(c.names, ", ")));
    return std::string(v);
  }

  /// InputError for a key that no call above asked for.
  void finish() const {
    for (const auto& [key, value] : settings_)
      if (std::ranges::find(known_, key) == known_.end())
        throw UnknownSetting(fmt::format("{}: unknown setting '{}' (known: {})", optimizer_, key, fmt::join(known_, ", ")),
                             {known_.begin(), known_.end()});
  }

 private:
  [[nodiscard]] std::string what(std::string_view key) const {
    return fmt::format("{}: setting '{}'", optimizer_, key);
  }
  std::string_view optimizer_;
  const std::map<std::string, std::string>& settings_;
  std::vector<std::string_view> known_;
};

/// Checks the settings and makes the factory of the runs.
template <class Algorithm, class Settings>
OptimizerFactory factory_of(SettingsReader& read, const Settings& settings) {
  read.finish();
  settings.validate();
  return [settings](const Bounds& bounds, std::uint64_t run_key) -> std::unique_ptr<Optimizer> {
    return std::make_unique<Algorithm>(settings, bounds, run_key);
  };
}

OptimizerFactory make_pso(const OptimizerSpec& spec) {
  SettingsReader read("pso", spec.settings);
  PsoSettings s;
  const std::string variant = read.choice(kPsoVariant);
  if (variant == "constriction") s = PsoSettings::constriction();
  if (variant == "linear_inertia") s = PsoSettings::linear_inertia();
  s.population = spec.population;
  s.iterations = spec.iterations;
  read.apply(pso_setting_table(), s);
  return factory_of<Pso>(read, s);
}

/// Settings with the spec's budget (population × generations) and every other field at its default.
template <class Settings>
Settings with_budget(const OptimizerSpec& spec) {
  Settings s;
  s.population = spec.population;
  s.generations = spec.iterations;
  return s;
}


OptimizerFactory make_ga(const OptimizerSpec& spec) {
  SettingsReader read("ga", spec.settings);
  // The lssvm paper's preset fixes its own budget (50 × 500) as well.
  GaSettings s = read.choice(kGaPreset) == "lssvm" ? GaSettings::lssvm() : with_budget<GaSettings>(spec);
  read.apply(ga_setting_table(), s);
  return factory_of<Ga>(read, s);
}

OptimizerFactory make_aga(const OptimizerSpec& spec) {
  SettingsReader read("aga", spec.settings);
  auto s = with_budget<AgaSettings>(spec);
  read.apply(aga_setting_table(), s);
  return factory_of<Aga>(read, s);
}

OptimizerFactory make_de(const OptimizerSpec& spec) {
  SettingsReader read("de", spec.settings);
  auto s = with_budget<DeSettings>(spec);
  if (const std::string* t = read.text("strategy")) s.strategy = parse_de_strategy(trim(*t));
  read.apply(de_setting_table(), s);
  return factory_of<De>(read, s);
}

/// The cmaes settings other than the budget (also those of a hybrid's cmaes global stage).
void read_cmaes(SettingsReader& read, CmaesSettings& s) {
  if (const std::string* t = read.text("restarts")) s.restarts = parse_cmaes_restarts(trim(*t));
  read.apply(cmaes_setting_table(), s);
}

OptimizerFactory make_cmaes(const OptimizerSpec& spec) {
  SettingsReader read("cmaes", spec.settings);
  auto s = with_budget<CmaesSettings>(spec);
  read_cmaes(read, s);
  return factory_of<Cmaes>(read, s);
}

/// A hybrid's global stage: `global` (ga, the default, or cmaes), then that stage's settings.
void read_hybrid_global(SettingsReader& read, HybridSettings& s) {
  if (read.choice(kHybridGlobal) == "cmaes") {
    s.global = GlobalStage::cmaes;
    read_cmaes(read, s.cmaes);
  } else {
    read.apply(ga_setting_table(), static_cast<GaSettings&>(s));
  }
}

OptimizerFactory make_ga_sqp(const OptimizerSpec& spec) {
  SettingsReader read("ga-sqp", spec.settings);
  auto s = with_budget<GaSqpSettings>(spec);
  read_hybrid_global(read, s);
  if (const std::string* t = read.text("constraint"); t && (trim(*t) == "off" || trim(*t) == "none"))
    s.constraint = std::numeric_limits<double>::infinity();
  else if (const auto v = read.number("constraint", false))
    s.constraint = *v;
  read.apply(ga_sqp_setting_table(), s);
  return factory_of<GaSqp>(read, s);
}

OptimizerFactory make_ga_lm(const OptimizerSpec& spec) {
  SettingsReader read("ga-lm", spec.settings);
  auto s = with_budget<GaLmSettings>(spec);
  read_hybrid_global(read, s);
  read.apply(ga_lm_setting_table(), s);
  return factory_of<GaLm>(read, s);
}

struct Entry {
  std::string_view name;
  OptimizerFactory (*make)(const OptimizerSpec&);
};
constexpr Entry kOptimizers[] = {{"pso", make_pso},     {"ga", make_ga},         {"aga", make_aga},
                                 {"de", make_de},       {"cmaes", make_cmaes},   {"ga-sqp", make_ga_sqp},
                                 {"ga-lm", make_ga_lm}};

}  // namespace

std::vector<std::string> optimizer_names() {
  std::vector<std::string> names;
  for (const Entry& e : kOptimizers) names.emplace_back(e.name);
  return names;
}

bool has_local_stage(const std::string& name) { return name == "ga-sqp" || name == "ga-lm"; }

OptimizerFactory make_optimizer_factory(const OptimizerSpec& spec) {
  for (const Entry& e : kOptimizers)
    if (spec.name == e.name) return e.make(spec);
  throw InputError(fmt::format("unknown optimizer '{}' (known: {})", spec.name, fmt::join(optimizer_names(), ", ")));
}

namespace {

/// A hybrid's rows: its global stage's choice, ga's settings and cmaes's (each applying with that stage), then its own.
template <class S>
std::vector<SettingRow> hybrid_rows(const SettingTable<S>& own, std::vector<SettingRow> extra = {}) {
  std::vector<SettingRow> rows{listed(kHybridGlobal)};
  const S defaults{};
  for (SettingRow row : listed<GaSettings>(ga_setting_table(), defaults)) {
    row.meaning = "with global = ga: " + row.meaning;
    rows.push_back(std::move(row));
  }
  SettingRow restarts = listed(kCmaesRestarts);
  restarts.meaning = "with global = cmaes: " + restarts.meaning;
  rows.push_back(std::move(restarts));
  for (SettingRow row : listed(cmaes_setting_table(), CmaesSettings{})) {
    row.meaning = "with global = cmaes: " + row.meaning;
    rows.push_back(std::move(row));
  }
  rows.insert(rows.end(), extra.begin(), extra.end());
  for (SettingRow& row : listed(own, defaults)) rows.push_back(std::move(row));
  return rows;
}

template <class S>
std::vector<SettingRow> with_choice(const ChoiceSetting& c, const SettingTable<S>& table) {
  std::vector<SettingRow> rows{listed(c)};
  for (SettingRow& row : listed(table, S{})) rows.push_back(std::move(row));
  return rows;
}

}  // namespace

std::vector<SettingRow> optimizer_setting_rows(const std::string& name) {
  if (name == "pso") return with_choice(kPsoVariant, pso_setting_table());
  if (name == "ga") return with_choice(kGaPreset, ga_setting_table());
  if (name == "aga") return listed(aga_setting_table(), AgaSettings{});
  if (name == "de") return with_choice(kDeStrategy, de_setting_table());
  if (name == "cmaes") return with_choice(kCmaesRestarts, cmaes_setting_table());
  if (name == "ga-sqp")
    return hybrid_rows(ga_sqp_setting_table(),
                       {{"constraint", "number or off", fmt::format("{:g}", GaSqpSettings{}.constraint), "> 0, or off",
                         "fdsp eq. 11's threshold on the error, in the run metric's units"}});
  if (name == "ga-lm") return hybrid_rows(ga_lm_setting_table());
  throw InputError(fmt::format("unknown optimizer '{}' (known: {})", name, fmt::join(optimizer_names(), ", ")));
}

std::vector<std::string> optimizer_settings(const std::string& name) {
  // The reader collects the keys it asks for as it validates; a key no optimizer has makes it list them.
  try {
    (void)make_optimizer_factory(OptimizerSpec{name, 50, 100, {{"?", "0"}}});
  } catch (const UnknownSetting& e) {
    return e.known;
  }
  throw std::logic_error("optimizer " + name + " accepted an unknown setting");
}

}  // namespace dampbench
