#pragma once
// The ask/tell interface every population optimizer implements (optimizers/ has one folder per
// algorithm). One Optimizer object is one independent run; R runs advance in lockstep so that each
// generation of all of them is evaluated as one batch (engine/identification/identification.hpp).
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "engine/model/batch.hpp"
#include "engine/model/bounds.hpp"

namespace dampbench {

/// What a local refinement (the SQP or least-squares stage of a hybrid) may ask of the problem; the
/// identification loop provides one per run and counts its evaluations.
class LocalProblem {
 public:
  virtual ~LocalProblem() = default;
  /// The optimized metric of every candidate of the batch (one batch across cores; +inf for failures).
  virtual void evaluate(const CandidateBatch& batch, std::span<double> values) const = 0;
  /// Residuals F_model − F_measured of one candidate at every sample of every dataset, each dataset's
  /// residuals divided by sqrt(N_d)·max|F_d| so that ‖r‖² = Σ_d nrmse_d² (least-squares stages).
  [[nodiscard]] virtual std::vector<double> residuals(std::span<const double> params) const = 0;
  /// Residuals of many candidates at once (finite-difference Jacobians): the same values as one call each.
  /// Default: one call each; the identification's problem simulates them a lane block at a time.
  [[nodiscard]] virtual std::vector<std::vector<double>> residuals_batch(std::span<const std::vector<double>> candidates) const {
    std::vector<std::vector<double>> out;
    for (const auto& c : candidates) out.push_back(residuals(std::span<const double>(c)));
    return out;
  }
  /// Residuals of points[0] (a trial point) and, in the same batch, of points[1...] (what the caller needs next if it
  /// keeps the trial: Levenberg–Marquardt's Jacobian there), when the problem's batch has idle lanes for them: its
  /// lane blocks take the time of their dearest lane, so the points beside a single trial cost no extra time. The
  /// same values as one call each. Counts only points[0] as an evaluation; count_evaluations() adds the others when
  /// the caller uses them, so a run's evaluations are the algorithm's whatever it computed ahead. Default: {} (no
  /// idle lanes: the caller evaluates its trial alone).
  [[nodiscard]] virtual std::vector<std::vector<double>> residuals_ahead(std::span<const std::vector<double>> /*points*/) const {
    return {};
  }
  /// Counts `n` evaluations computed earlier by residuals_ahead.
  virtual void count_evaluations(long long /*n*/) const {}
  [[nodiscard]] virtual const Bounds& bounds() const = 0;
};

/// One run of an optimizer. identify() calls the ask and tell of different runs at the same time on different
/// cores: a run keeps its state to itself (no statics, nothing mutable shared with other runs), and ask writes
/// only its own rows.
class Optimizer {
 public:
  virtual ~Optimizer() = default;
  /// Candidates per ask (the population size of a generational algorithm).
  [[nodiscard]] virtual int batch_size() const = 0;
  /// Writes the next batch_size() candidates into rows [first, first + batch_size()) of `batch`.
  virtual void ask(CandidateBatch& batch, int first) = 0;
  /// Takes the metric of each asked candidate, in the order asked (+inf for failed candidates).
  virtual void tell(std::span<const double> values) = 0;
  [[nodiscard]] virtual bool finished() const = 0;
  [[nodiscard]] virtual std::span<const double> best_position() const = 0;
  [[nodiscard]] virtual double best_value() const = 0;
  /// Local refinement after the population phase has finished (hybrids: GA → SQP, GA → least squares).
  /// It may evaluate through `problem` and must leave best_position()/best_value() updated (best_value in
  /// the metric's terms). Default: nothing.
  virtual void refine(const LocalProblem& /*problem*/) {}
  /// After refine(): the local stage stopped on its own convergence test (a gradient method at a local
  /// optimum: LM's gradient, ftol, xtol; SLSQP's ftol, xtol, success), not on a failure, nor on an iteration
  /// cap while still gaining (LM at its cap counts if its last fifth gained ≤ 0.01 %, ga_lm.hpp).
  /// The convergence evidence then does not ask the run to have stopped improving (engine/identification/
  /// convergence.hpp): the refinement's late gain is by design. Default: false (no local stage).
  [[nodiscard]] virtual bool at_local_optimum() const { return false; }
};

/// `settings` after `settings.validate()` (which throws InputError), so that a constructor checks its settings
/// before it builds its bases and members from them.
template <class Settings>
const Settings& validated(const Settings& settings) {
  settings.validate();
  return settings;
}

/// Makes the optimizer of one run. `run_key` keys every random number the run draws
/// (engine/common/random.hpp), so a run's history depends only on it, never on threads or batch layout.
using OptimizerFactory = std::function<std::unique_ptr<Optimizer>(const Bounds& bounds, std::uint64_t run_key)>;

}  // namespace dampbench
