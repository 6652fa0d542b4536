#include "optimizers/registry.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <string_view>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "engine/common/error.hpp"
#include "engine/common/key_values.hpp"

namespace dampbench {
namespace {

/// Reads one optimizer's settings map: rejects unknown keys up front, then applies known ones on request.
class SettingsReader {
 public:
  SettingsReader(std::string_view optimizer, const std::map<std::string, std::string>& settings,
                 std::vector<std::string_view> known)
      : optimizer_(optimizer), settings_(settings) {
    for (const auto& [key, value] : settings_)
      if (std::ranges::find(known, key) == known.end())
        throw InputError(fmt::format("{}: unknown setting '{}' (known: {})", optimizer_, key, fmt::join(known, ", ")));
  }

  /// The raw value of `key`, or nullptr.
  [[nodiscard]] const std::string* text(std::string_view key) const {
    const auto it = settings_.find(std::string(key));
    return it == settings_.end() ? nullptr : &it->second;
  }

  void number(std::string_view key, double& field) const {
    if (const std::string* t = text(key)) field = parse_number(trim(*t), what(key));
  }

  void optional_number(std::string_view key, std::optional<double>& field) const {
    if (const std::string* t = text(key)) field = parse_number(trim(*t), what(key));
  }

  void whole(std::string_view key, int& field) const {
    const std::string* t = text(key);
    if (!t) return;
    const double v = parse_number(trim(*t), what(key));
    if (v != std::floor(v) || std::abs(v) > std::numeric_limits<int>::max())
      throw InputError(fmt::format("{}: expected a whole number, got '{}'", what(key), *t));
    field = static_cast<int>(v);
  }

  /// The value of `key` if it is one of `names` (or absent: nullopt-like empty string); otherwise InputError.
  [[nodiscard]] std::string choice(std::string_view key, std::vector<std::string_view> names) const {
    const std::string* t = text(key);
    if (!t) return {};
    const std::string_view v = trim(*t);
    if (std::ranges::find(names, v) == names.end())
      throw InputError(fmt::format("{}: unknown {} '{}' (known: {})", optimizer_, key, v, fmt::join(names, ", ")));
    return std::string(v);
  }

 private:
  [[nodiscard]] std::string what(std::string_view key) const {
    return fmt::format("{}: setting '{}'", optimizer_, key);
  }
  std::string_view optimizer_;
  const std::map<std::string, std::string>& settings_;
};

template <class Algorithm, class Settings>
OptimizerFactory factory_of(const Settings& settings) {
  settings.validate();
  return [settings](const Bounds& bounds, std::uint64_t run_key) -> std::unique_ptr<Optimizer> {
    return std::make_unique<Algorithm>(settings, bounds, run_key);
  };
}

OptimizerFactory make_pso(const OptimizerSpec& spec) {
  const SettingsReader read("pso", spec.settings,
                            {"variant", "inertia", "inertia_end", "cognitive", "social", "vmax_fraction"});
  PsoSettings s;
  const std::string variant = read.choice("variant", {"inertia", "constriction", "linear_inertia"});
  if (variant == "constriction") s = PsoSettings::constriction();
  if (variant == "linear_inertia") s = PsoSettings::linear_inertia();
  s.population = spec.population;
  s.iterations = spec.iterations;
  read.number("inertia", s.inertia);
  read.number("inertia_end", s.inertia_end);
  read.number("cognitive", s.cognitive);
  read.number("social", s.social);
  read.number("vmax_fraction", s.vmax_fraction);
  return factory_of<Pso>(s);
}

void read_genetic(const SettingsReader& read, GeneticSettings& s) {
  read.number("eta_c", s.eta_c);
  read.number("eta_m", s.eta_m);
  read.whole("tournament", s.tournament);
  read.whole("elites", s.elites);
}

OptimizerFactory make_ga(const OptimizerSpec& spec) {
  const SettingsReader read("ga", spec.settings, {"pc", "pm", "eta_c", "eta_m", "tournament", "elites", "preset"});
  GaSettings s;
  s.population = spec.population;
  s.generations = spec.iterations;
  if (read.choice("preset", {"lssvm"}) == "lssvm") s = GaSettings::lssvm();
  read.number("pc", s.pc);
  read.optional_number("pm", s.pm);
  read_genetic(read, s);
  return factory_of<Ga>(s);
}

OptimizerFactory make_aga(const OptimizerSpec& spec) {
  const SettingsReader read("aga", spec.settings,
                            {"k1", "k2", "k3", "k4", "pm_min", "eta_c", "eta_m", "tournament", "elites"});
  AgaSettings s;
  s.population = spec.population;
  s.generations = spec.iterations;
  read.number("k1", s.k1);
  read.number("k2", s.k2);
  read.number("k3", s.k3);
  read.number("k4", s.k4);
  read.optional_number("pm_min", s.pm_min);
  read_genetic(read, s);
  return factory_of<Aga>(s);
}

OptimizerFactory make_de(const OptimizerSpec& spec) {
  const SettingsReader read("de", spec.settings, {"strategy", "F", "CR"});
  DeSettings s;
  s.population = spec.population;
  s.generations = spec.iterations;
  if (const std::string* t = read.text("strategy")) s.strategy = parse_de_strategy(trim(*t));
  read.number("F", s.F);
  read.number("CR", s.CR);
  return factory_of<De>(s);
}

OptimizerFactory make_ga_sqp(const OptimizerSpec& spec) {
  const SettingsReader read("ga-sqp", spec.settings,
                            {"pc", "pm", "eta_c", "eta_m", "tournament", "elites", "constraint", "sqp_iterations",
                             "fd_step", "xtol", "ftol"});
  GaSqpSettings s;
  s.population = spec.population;
  s.generations = spec.iterations;
  read.number("pc", s.pc);
  read.optional_number("pm", s.pm);
  read_genetic(read, s);
  if (const std::string* t = read.text("constraint"); t && (trim(*t) == "off" || trim(*t) == "none"))
    s.constraint = std::numeric_limits<double>::infinity();
  else
    read.number("constraint", s.constraint);
  read.whole("sqp_iterations", s.sqp_iterations);
  read.number("fd_step", s.fd_step);
  read.number("xtol", s.xtol);
  read.number("ftol", s.ftol);
  return factory_of<GaSqp>(s);
}

OptimizerFactory make_ga_lm(const OptimizerSpec& spec) {
  const SettingsReader read("ga-lm", spec.settings,
                            {"pc", "pm", "eta_c", "eta_m", "tournament", "elites", "lm_iterations", "fd_step", "ftol",
                             "xtol", "gtol", "lambda0", "geodesic", "geodesic_ratio"});
  GaLmSettings s;
  s.population = spec.population;
  s.generations = spec.iterations;
  read.number("pc", s.pc);
  read.optional_number("pm", s.pm);
  read_genetic(read, s);
  read.whole("lm_iterations", s.lm_iterations);
  read.number("fd_step", s.fd_step);
  read.number("ftol", s.ftol);
  read.number("xtol", s.xtol);
  read.number("gtol", s.gtol);
  read.number("lambda0", s.lambda0);
  read.whole("geodesic", s.geodesic);
  read.number("geodesic_ratio", s.geodesic_ratio);
  return factory_of<GaLm>(s);
}

struct Entry {
  std::string_view name;
  OptimizerFactory (*make)(const OptimizerSpec&);
};
constexpr Entry kOptimizers[] = {{"pso", make_pso}, {"ga", make_ga},         {"aga", make_aga},
                                 {"de", make_de},   {"ga-sqp", make_ga_sqp}, {"ga-lm", make_ga_lm}};

}  // namespace

std::vector<std::string> optimizer_names() {
  std::vector<std::string> names;
  for (const Entry& e : kOptimizers) names.emplace_back(e.name);
  return names;
}

OptimizerFactory make_optimizer_factory(const OptimizerSpec& spec) {
  for (const Entry& e : kOptimizers)
    if (spec.name == e.name) return e.make(spec);
  throw InputError(fmt::format("unknown optimizer '{}' (known: {})", spec.name, fmt::join(optimizer_names(), ", ")));
}

}  // namespace dampbench
