#include "optimizers/pso/pso.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/common/random.hpp"

namespace dampbench {

void PsoSettings::validate() const {
  if (population < 2) throw InputError(fmt::format("pso: population must be at least 2, got {}", population));
  if (iterations < 1) throw InputError(fmt::format("pso: iterations must be at least 1, got {}", iterations));
  check_ranges("pso", pso_setting_table(), *this);
  if (variant == PsoVariant::constriction && !(cognitive + social > 4))
    throw InputError(fmt::format(
        "pso: the constriction variant needs phi = cognitive + social > 4 (Clerc & Kennedy 2002), got {}",
        cognitive + social));
}

const SettingTable<PsoSettings>& pso_setting_table() {
  static const SettingTable<PsoSettings> table{
      {"inertia", &PsoSettings::inertia, kNonNegative, "inertia weight w at the first iteration"},
      {"inertia_end", &PsoSettings::inertia_end, kNonNegative,
       "w at the last iteration (a linear decrease when it differs from inertia)"},
      {"cognitive", &PsoSettings::cognitive, kNonNegative, "c1, the pull toward each particle's own best"},
      {"social", &PsoSettings::social, kNonNegative, "c2, the pull toward the swarm's best"},
      {"vmax_fraction", &PsoSettings::vmax_fraction, kPositive, "velocity clamp as a fraction of each parameter's range"},
  };
  return table;
}

PsoSettings PsoSettings::constriction() {
  return {.variant = PsoVariant::constriction, .cognitive = 2.05, .social = 2.05};
}

PsoSettings PsoSettings::linear_inertia() { return {.inertia = 0.9, .inertia_end = 0.4, .cognitive = 2.0, .social = 2.0}; }

double PsoSettings::constriction_factor() const {
  const double phi = cognitive + social;
  return 2.0 / std::abs(2.0 - phi - std::sqrt(phi * phi - 4.0 * phi));
}

// Until the first tell, the best position is the first particle (PopulationOptimizer): inside the box even if
// a run is stopped (engine budgets) before any evaluation.
Pso::Pso(const PsoSettings& settings, const Bounds& bounds, std::uint64_t run_key)
    : PopulationOptimizer(validated(settings).population, settings.iterations, bounds, run_key),
      settings_(settings) {
  v_.assign(population_.size(), 0.0);
  pbest_.resize(population_.size());
  pbest_value_.assign(settings_.population, std::numeric_limits<double>::infinity());
}

void Pso::ask(CandidateBatch& batch, int first) {
  if (generation_ > 0) move_swarm();
  for (int i = 0; i < settings_.population; ++i)
    for (int j = 0; j < dim_; ++j) batch.at(first + i, j) = x(i, j);
}

void Pso::tell(std::span<const double> values) {
  for (int i = 0; i < settings_.population; ++i) {
    const double value = std::isfinite(values[i]) ? values[i] : std::numeric_limits<double>::infinity();
    // The first evaluation always sets pbest (even +inf), so every particle has an attractor.
    if (generation_ == 0 || value < pbest_value_[i]) {
      pbest_value_[i] = value;
      std::copy_n(population_.begin() + static_cast<std::ptrdiff_t>(i) * dim_, dim_,
                  pbest_.begin() + static_cast<std::ptrdiff_t>(i) * dim_);
    }
    if (value < best_value_ || (generation_ == 0 && i == 0)) {
      best_value_ = value;
      std::copy_n(population_.begin() + static_cast<std::ptrdiff_t>(i) * dim_, dim_, best_position_.begin());
    }
  }
  ++generation_;
}

void Pso::move_swarm() {
  const double progress =
      settings_.iterations > 1 ? static_cast<double>(generation_ - 1) / (settings_.iterations - 1) : 0.0;
  const double w = settings_.inertia + (settings_.inertia_end - settings_.inertia) * progress;
  const bool constricted = settings_.variant == PsoVariant::constriction;
  const double chi = constricted ? settings_.constriction_factor() : 1.0;
  const std::uint64_t generation_key = hash_key({run_key_, static_cast<std::uint64_t>(generation_)});
  for (int i = 0; i < settings_.population; ++i) {
    RandomStream rng(extend_key(generation_key, static_cast<std::uint64_t>(i)));  // (run, generation, i)
    for (int j = 0; j < dim_; ++j) {
      const double lo = bounds_.lower[j], hi = bounds_.upper[j];
      const double vmax = settings_.vmax_fraction * (hi - lo);
      const double r1 = rng.uniform(), r2 = rng.uniform();
      const double cognitive = settings_.cognitive * r1 * (pbest(i, j) - x(i, j));
      const double social = settings_.social * r2 * (best_position_[j] - x(i, j));
      double vel = constricted ? chi * (v(i, j) + cognitive + social) : w * v(i, j) + cognitive + social;
      vel = std::clamp(vel, -vmax, vmax);
      double pos = x(i, j) + vel;
      if (pos < lo || pos > hi) {
        pos = std::clamp(pos, lo, hi);
        vel = 0.0;
      }
      x(i, j) = pos;
      v(i, j) = vel;
    }
  }
}

}  // namespace dampbench
