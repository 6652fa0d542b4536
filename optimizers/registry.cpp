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

/// The field a settings key sets: a number, an optional number (unset = the optimizer's rule) or a whole number.
using SettingField = std::variant<double*, std::optional<double>*, int*, std::optional<int>*>;

/// Reads one optimizer's settings map: `apply` sets fields from a table of keys, `choice` and `text` read the
/// rest; `finish` rejects any key no call asked for, listing the known ones.
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

  /// Sets each field whose key is given.
  void apply(std::initializer_list<std::pair<std::string_view, SettingField>> table) {
    for (const auto& entry : table) {
      const std::string_view key = entry.first;  // not a structured binding: clang 14 cannot capture one
      const SettingField& field = entry.second;
      const std::string* t = text(key);
      if (!t) continue;
      const double v = parse_number(trim(*t), what(key));
      std::visit(
          [&](auto* f) {
            if constexpr (std::is_same_v<decltype(f), int*> || std::is_same_v<decltype(f), std::optional<int>*>) {
              if (v != std::floor(v) || std::abs(v) > std::numeric_limits<int>::max())
                throw InputError(fmt::format("{}: expected a whole number, got '{}'", what(key), *t));
              *f = static_cast<int>(v);
            } else {
              *f = v;
            }
          },
          field);
    }
  }

  /// The value of `key` if it is one of `names` (empty when absent); otherwise InputError.
  [[nodiscard]] std::string choice(std::string_view key, std::vector<std::string_view> names) {
    const std::string* t = text(key);
    if (!t) return {};
    const std::string_view v = trim(*t);
    if (std::ranges::find(names, v) == names.end())
      throw InputError(fmt::format("{}: unknown {} '{}' (known: {})", optimizer_, key, v, fmt::join(names, ", ")));
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
  const std::string variant = read.choice("variant", {"inertia", "constriction", "linear_inertia"});
  if (variant == "constriction") s = PsoSettings::constriction();
  if (variant == "linear_inertia") s = PsoSettings::linear_inertia();
  s.population = spec.population;
  s.iterations = spec.iterations;
  read.apply({{"inertia", &s.inertia}, {"inertia_end", &s.inertia_end}, {"cognitive", &s.cognitive},
              {"social", &s.social}, {"vmax_fraction", &s.vmax_fraction}});
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

/// The operator settings every genetic algorithm shares.
void read_genetic(SettingsReader& read, GeneticSettings& s) {
  read.apply({{"eta_c", &s.eta_c}, {"eta_m", &s.eta_m}, {"tournament", &s.tournament}, {"elites", &s.elites}});
}

/// The fixed crossover and mutation probabilities of the GA and the hybrids built on it, then read_genetic.
void read_ga(SettingsReader& read, GaSettings& s) {
  read.apply({{"pc", &s.pc}, {"pm", &s.pm}});
  read_genetic(read, s);
}

OptimizerFactory make_ga(const OptimizerSpec& spec) {
  SettingsReader read("ga", spec.settings);
  // The lssvm paper's preset fixes its own budget (50 × 500) as well.
  GaSettings s = read.choice("preset", {"lssvm"}) == "lssvm" ? GaSettings::lssvm() : with_budget<GaSettings>(spec);
  read_ga(read, s);
  return factory_of<Ga>(read, s);
}

OptimizerFactory make_aga(const OptimizerSpec& spec) {
  SettingsReader read("aga", spec.settings);
  auto s = with_budget<AgaSettings>(spec);
  read.apply({{"k1", &s.k1}, {"k2", &s.k2}, {"k3", &s.k3}, {"k4", &s.k4}, {"pm_min", &s.pm_min}});
  read_genetic(read, s);
  return factory_of<Aga>(read, s);
}

OptimizerFactory make_de(const OptimizerSpec& spec) {
  SettingsReader read("de", spec.settings);
  auto s = with_budget<DeSettings>(spec);
  if (const std::string* t = read.text("strategy")) s.strategy = parse_de_strategy(trim(*t));
  read.apply({{"F", &s.F}, {"CR", &s.CR}});
  return factory_of<De>(read, s);
}

/// The cmaes settings other than the budget (also those of a hybrid's cmaes global stage).
void read_cmaes(SettingsReader& read, CmaesSettings& s) {
  if (const std::string* t = read.text("restarts")) s.restarts = parse_cmaes_restarts(trim(*t));
  read.apply({{"sigma0", &s.sigma0}, {"tolfun", &s.tolfun}, {"tolx", &s.tolx}});
}

OptimizerFactory make_cmaes(const OptimizerSpec& spec) {
  SettingsReader read("cmaes", spec.settings);
  auto s = with_budget<CmaesSettings>(spec);
  read_cmaes(read, s);
  return factory_of<Cmaes>(read, s);
}

/// A hybrid's global stage: `global` (ga, the default, or cmaes), then that stage's settings.
void read_hybrid_global(SettingsReader& read, HybridSettings& s) {
  if (read.choice("global", {"ga", "cmaes"}) == "cmaes") {
    s.global = GlobalStage::cmaes;
    read_cmaes(read, s.cmaes);
  } else {
    read_ga(read, s);
  }
}

OptimizerFactory make_ga_sqp(const OptimizerSpec& spec) {
  SettingsReader read("ga-sqp", spec.settings);
  auto s = with_budget<GaSqpSettings>(spec);
  read_hybrid_global(read, s);
  if (const std::string* t = read.text("constraint"); t && (trim(*t) == "off" || trim(*t) == "none"))
    s.constraint = std::numeric_limits<double>::infinity();
  else
    read.apply({{"constraint", &s.constraint}});
  read.apply({{"sqp_iterations", &s.sqp_iterations}, {"fd_step", &s.fd_step}, {"xtol", &s.xtol}, {"ftol", &s.ftol}});
  return factory_of<GaSqp>(read, s);
}

OptimizerFactory make_ga_lm(const OptimizerSpec& spec) {
  SettingsReader read("ga-lm", spec.settings);
  auto s = with_budget<GaLmSettings>(spec);
  read_hybrid_global(read, s);
  read.apply({{"lm_iterations", &s.lm_iterations}, {"fd_step", &s.fd_step}, {"ftol", &s.ftol}, {"xtol", &s.xtol},
              {"gtol", &s.gtol}, {"lambda0", &s.lambda0}, {"geodesic", &s.geodesic},
              {"geodesic_ratio", &s.geodesic_ratio}});
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
