#pragma once
// What the two hybrids (`ga-sqp`, optimizers/hybrid/ga_sqp.hpp; `ga-lm`, optimizers/hybrid/ga_lm.hpp) share:
//   - the population phase is the `ga` optimizer itself (optimizers/ga/ga.hpp): ask, tell, finished and the
//     random streams are those of a `ga` run with the same settings and run key, so a hybrid's population
//     phase is bit for bit the GA's;
//   - the local phase (refine) works on the free parameters mapped to the unit cube (optimizers/unit_box.hpp);
//   - after refine, best_position()/best_value() are the lowest metric value seen (GA best or any point
//     the local phase evaluated), so a hybrid is never worse than its GA phase.
// Local phases draw no random numbers: the whole run is a pure function of (settings, bounds, run key) and
// the problem's values, which the engine computes bit-identically for any thread count and batch split.
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "engine/identification/optimizer.hpp"
#include "optimizers/ga/ga.hpp"
#include "optimizers/unit_box.hpp"

namespace dampbench {

/// Lowest finite value seen and where (what a local phase hands back).
struct BestSeen {
  double value = std::numeric_limits<double>::infinity();
  std::vector<double> position;
  void offer(double v, std::span<const double> x) {
    if (v < value) {  // false for NaN and +inf
      value = v;
      position.assign(x.begin(), x.end());
    }
  }
};

/// A GA population phase followed by a local refinement (subclasses implement refine()).
class GaHybrid : public Optimizer {
 public:
  [[nodiscard]] int batch_size() const override { return ga_.batch_size(); }
  void ask(CandidateBatch& batch, int first) override { ga_.ask(batch, first); }
  void tell(std::span<const double> values) override { ga_.tell(values); }
  [[nodiscard]] bool finished() const override { return ga_.finished(); }
  [[nodiscard]] std::span<const double> best_position() const override {
    return refined_ ? std::span<const double>(position_) : ga_.best_position();
  }
  [[nodiscard]] double best_value() const override { return refined_ ? value_ : ga_.best_value(); }

 protected:
  GaHybrid(const GaSettings& ga, const Bounds& bounds, std::uint64_t run_key) : ga_(ga, bounds, run_key), bounds_(bounds) {}
  /// Ends refine(): the better of the GA best and `seen` (the GA best on ties).
  void finish_refine(const BestSeen& seen);

  Ga ga_;
  Bounds bounds_;

 private:
  bool refined_ = false;
  std::vector<double> position_;
  double value_ = std::numeric_limits<double>::infinity();
};

}  // namespace dampbench
