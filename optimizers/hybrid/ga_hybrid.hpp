#pragma once
// What the two hybrids (`ga-sqp`, optimizers/hybrid/ga_sqp.hpp; `ga-lm`, optimizers/hybrid/ga_lm.hpp) share:
//   - the population (global) phase is the `ga` optimizer itself (optimizers/ga/ga.hpp), or with the setting
//     global = cmaes the `cmaes` optimizer (optimizers/cmaes/cmaes.hpp) with the hybrid's population and
//     iterations: ask, tell, finished and the random streams are those of that optimizer's run with the same
//     settings and run key, so a hybrid's population phase is bit for bit the global optimizer's;
//   - the local phase (refine) works on the free parameters mapped to the unit cube (optimizers/unit_box.hpp);
//   - after refine, best_position()/best_value() are the lowest metric value seen (GA best or any point
//     the local phase evaluated), so a hybrid is never worse than its global phase.
// Local phases draw no random numbers: the whole run is a pure function of (settings, bounds, run key) and
// the problem's values, which the engine computes bit-identically for any thread count and batch split.
#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/identification/optimizer.hpp"
#include "optimizers/cmaes/cmaes.hpp"
#include "optimizers/ga/ga.hpp"
#include "optimizers/unit_box.hpp"

namespace dampbench {

enum class GlobalStage { ga, cmaes };

/// What both hybrids' settings share: the GA's (the population phase by default) and the global stage.
struct HybridSettings : GaSettings {
  GlobalStage global = GlobalStage::ga;
  /// The cmaes settings when global == cmaes; its population and generations are the hybrid's (the GA fields
  /// above), whatever these two hold.
  CmaesSettings cmaes;

  /// What both hybrids check alike, in `hybrid`'s name: the GA's budget and operators, pc and pm (ga's table), and
  /// with global == cmaes the cmaes settings' validate() with the hybrid's population and generations.
  void validate_shared(std::string_view hybrid) const;
};

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

/// A global population phase (ga or cmaes) followed by a local refinement (subclasses implement refine()).
class GaHybrid : public Optimizer {
 public:
  [[nodiscard]] int batch_size() const override { return global_->batch_size(); }
  void ask(CandidateBatch& batch, int first) override { global_->ask(batch, first); }
  void tell(std::span<const double> values) override { global_->tell(values); }
  [[nodiscard]] bool finished() const override { return global_->finished(); }
  [[nodiscard]] std::span<const double> best_position() const override {
    return refined_ ? std::span<const double>(position_) : global_->best_position();
  }
  [[nodiscard]] double best_value() const override { return refined_ ? value_ : global_->best_value(); }

 protected:
  GaHybrid(const HybridSettings& settings, const Bounds& bounds, std::uint64_t run_key);
  /// Ends refine(): the better of the global phase's best and `seen` (the global best on ties).
  void finish_refine(const BestSeen& seen);
  /// The population phase's optimizer.
  [[nodiscard]] const Optimizer& global() const { return *global_; }

  Bounds bounds_;

 private:
  std::unique_ptr<Optimizer> global_;
  bool refined_ = false;
  std::vector<double> position_;
  double value_ = std::numeric_limits<double>::infinity();
};

}  // namespace dampbench
