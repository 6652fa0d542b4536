#pragma once
// Particle swarm optimization, global-best topology (Kennedy & Eberhart 1995), inertia form
// (Shi & Eberhart 1998), used by the fvd paper (N = 50 particles, L = 100 iterations).
//
//   v ← w·v + c1·r1·(pbest − x) + c2·r2·(gbest − x),   x ← x + v,   r1, r2 ~ U[0, 1) per dimension.
//
// Defaults: w = 0.7298, c1 = c2 = 1.49618, the constriction coefficients of Clerc & Kennedy (2002)
// written in inertia form (Eberhart & Shi 2000) — the fvd paper gives none. With inertia_end ≠ inertia
// the inertia decreases linearly over the iterations (Shi & Eberhart 1999).
//
// Variants (the registry's setting `variant`):
//   inertia         the update above with the defaults (the default);
//   constriction    Clerc & Kennedy (2002), type 1'' constriction with κ = 1:
//                     v ← χ·(v + c1·r1·(pbest − x) + c2·r2·(gbest − x)),
//                     χ = 2 / |2 − φ − √(φ² − 4φ)|,  φ = c1 + c2 > 4;
//                   PsoSettings::constriction() takes c1 = c2 = 2.05 (φ = 4.1, χ ≈ 0.72984), their
//                   recommended values; the inertia fields are unused;
//   linear_inertia  Shi & Eberhart (1999): w decreasing linearly from 0.9 to 0.4, c1 = c2 = 2
//                   (PsoSettings::linear_inertia()).
// Iterations count swarm evaluations: iteration 0 evaluates the initial swarm, so a run costs exactly
// population × iterations evaluations (5 000 for the paper's N = 50, L = 100).
// Initial positions uniform in the bounds, initial velocities zero (Engelbrecht 2012).
// Bounds: a velocity component is clamped to ±vmax_fraction·(upper − lower); a particle leaving the box
// is put back on the violated bound and that velocity component is zeroed (absorbing walls).
// Random numbers: stream (run_key, iteration, particle) — a particle's draws never depend on others.
// Failed candidates (+inf, NaN or −inf; all read as +inf) never become a personal or global best over a
// finite value.
#include <cstdint>
#include <vector>

#include "optimizers/population.hpp"
#include "optimizers/setting_table.hpp"

namespace dampbench {

/// Velocity update form (see the header comment).
enum class PsoVariant { inertia, constriction };

struct PsoSettings {
  PsoVariant variant = PsoVariant::inertia;  ///< inertia weight form (Shi & Eberhart 1998)
  int population = 50;          ///< particles N (fvd paper)
  int iterations = 100;         ///< swarm evaluations L, including the initial one (fvd paper)
  double inertia = 0.7298;      ///< w at the first iteration
  double inertia_end = 0.7298;  ///< w at the last iteration (linear decrease when different)
  double cognitive = 1.49618;   ///< c1
  double social = 1.49618;      ///< c2
  double vmax_fraction = 0.5;   ///< velocity clamp as a fraction of each parameter's range
                                ///< (Vmax = Xmax on a symmetric box, Shi & Eberhart 1999)

  /// Clerc & Kennedy (2002) constriction: variant constriction, c1 = c2 = 2.05.
  static PsoSettings constriction();
  /// Shi & Eberhart (1999): inertia 0.9 → 0.4 linearly, c1 = c2 = 2.
  static PsoSettings linear_inertia();
  /// χ of the constriction variant from φ = cognitive + social (needs φ > 4).
  [[nodiscard]] double constriction_factor() const;

  /// Throws InputError for population < 2, iterations < 1, negative coefficients, vmax_fraction ≤ 0, and
  /// for the constriction variant cognitive + social ≤ 4.
  void validate() const;
};

/// pso's number settings (setting_table.hpp); `variant` is a choice the registry reads.
const SettingTable<PsoSettings>& pso_setting_table();

class Pso final : public PopulationOptimizer {
 public:
  Pso(const PsoSettings& settings, const Bounds& bounds, std::uint64_t run_key);

  void ask(CandidateBatch& batch, int first) override;
  void tell(std::span<const double> values) override;

 private:
  void move_swarm();
  double& v(int i, int j) { return v_[static_cast<std::size_t>(i) * dim_ + j]; }
  double& pbest(int i, int j) { return pbest_[static_cast<std::size_t>(i) * dim_ + j]; }

  PsoSettings settings_;
  std::vector<double> v_, pbest_, pbest_value_;  ///< velocities and personal bests (row-major N × dim)
};

}  // namespace dampbench
