#pragma once
// The model interface (docs/design.md, "Data flow"): a model names its parameters with SI units and default
// bounds, cites its paper and equation, and evaluates a block of candidates at once.
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "engine/model/batch.hpp"
#include "engine/model/metrics.hpp"
#include "engine/model/stepper.hpp"
#include "engine/record/signals.hpp"

namespace dampbench {

struct ParameterInfo {
  std::string name;        ///< ASCII name as docs/models.md writes it (the command-line contract)
  std::string unit;        ///< SI unit of the value the engine uses
  double lower = 0;        ///< default bounds in SI
  double upper = 0;
  std::string paper_unit;  ///< unit of the paper's tables (see Model::to_paper_units)
};

/// A default bound that scales with the record, so the box fits any damper size: parameter
/// `name` in [lower, upper] × F^force · V^velocity · X^amplitude, where F = max |F| [N], V = max |v| [m/s] and
/// X = half the peak-to-peak stroke [m] of a fitted record; over several records, the smallest box holding each
/// record's own, or for a `stiffening` rule the largest box inside each record's own.
struct RecordBoundsRule {
  std::string name;
  double lower = 0, upper = 0;
  double force = 0, velocity = 0, amplitude = 0;  ///< exponents of F, V, X
  /// The parameter sets how fast an internal state moves (the gauged β, γ of Bouc–Wen: z saturates over
  /// 1/(β + γ) metres), so a value one record's box allows can make another record's ODE far stiffer than its own
  /// box would: tried on a 10 mm stroke, the 2 mm stroke's ±2000/X takes 6× the sub-steps per sample of the 10 mm
  /// box's own worst candidate. Over several records such a rule takes the intersection of their boxes.
  bool stiffening = false;

  /// "0 … 2·F/V"-style text for `dampbench models`.
  [[nodiscard]] std::string describe() const;
};

/// A gauge that removes an exact scale symmetry of a model's internal states: parameter `tied` is set to the
/// sum of the parameters `sum_of`. In Bouc–Wen and Spencer, z → s·z with A → s·A, α → α/s and
/// β, γ → β·s^(1−n), γ·s^(1−n) leaves the force unchanged, so α, β, γ and A trade off exactly; A = β + γ fixes s
/// so that |z| saturates at 1 ((A/(β+γ))^(1/n) = 1) and α becomes the hysteretic force in N.
struct StateGauge {
  std::string tied;
  std::vector<std::string> sum_of;
  std::string meaning;  ///< what the gauge makes of the states, for the tables
  /// Record-scaled bounds that replace the model's own under the gauge (the scale of z changes theirs).
  std::vector<RecordBoundsRule> bounds_rules;
  /// SI units that change with the scale of the states: (parameter, unit).
  std::vector<std::pair<std::string, std::string>> units;
};

class Model {
 public:
  virtual ~Model() = default;

  [[nodiscard]] virtual std::string_view id() const = 0;
  /// Paper key and equation, e.g. "fvd eq. 5".
  [[nodiscard]] virtual std::string_view citation() const = 0;
  /// The force law in one line of plain text.
  [[nodiscard]] virtual std::string_view law() const = 0;
  [[nodiscard]] virtual std::span<const ParameterInfo> parameters() const = 0;

  /// Metric sums of candidates [first, first + count) of `batch` (count ≤ max_block_lanes()) against data.F_N: those of
  /// `wanted`, the others NaN. Never throws; a candidate whose force is NaN or Inf ends with non-finite sums
  /// (→ +inf metric).
  virtual void evaluate_block(const CandidateBatch& batch, int first, int count, const Signals& data,
                              SumSet wanted, MetricSums* out) const = 0;

  /// Most candidates one evaluate_block takes: kLanes, or kWidestLanes for a model that also runs wider blocks
  /// (count ≤ kLanes runs a block of kLanes lanes, ≤ kWideLanes one of kWideLanes, else one of kWidestLanes); a
  /// lane gets the same bits in any.
  [[nodiscard]] virtual int max_block_lanes() const { return kLanes; }
  /// An estimate of each candidate's cost on `data`, proportional to the time its lane takes, into out[i] for
  /// candidates [0, batch.count()) (the ODE kernels: the lane's mean RK4 sub-steps per sample interval);
  /// false, and `out` untouched, where every candidate costs the same. A block costs what its dearest lane
  /// costs, so BatchEvaluator puts candidates of similar cost into the same lane blocks and chooses the blocks'
  /// widths by these costs: a lane's bits do not depend on its neighbours, so both change the time only.
  virtual bool lane_costs(const CandidateBatch& /*batch*/, const Signals& /*data*/, std::span<double> /*out*/) const {
    return false;
  }

  /// Whether the model runs single-precision lanes (float, twice the lanes per vector): evaluate_block_float32
  /// and simulate_float32, for the global search of `--precision mixed`. The metric sums are added in double.
  [[nodiscard]] virtual bool has_float32_lanes() const { return false; }
  /// evaluate_block in single-precision lanes where has_float32_lanes(), with count ≤ kFloat32LaneScale ·
  /// max_block_lanes() (blocks of kLanes and kFloat32LaneScale times evaluate_block's widths); else evaluate_block.
  /// A lane's bits depend on its own parameters only, as in evaluate_block.
  virtual void evaluate_block_float32(const CandidateBatch& batch, int first, int count, const Signals& data,
                                      SumSet wanted, MetricSums* out) const {
    evaluate_block(batch, first, count, data, wanted, out);
  }
  /// simulate by the single-precision lanes of evaluate_block_float32 (widened to double), else simulate.
  [[nodiscard]] virtual std::vector<double> simulate_float32(std::span<const double> params, const Signals& data) const {
    return simulate(params, data);
  }

  /// The same sums computed by a plain scalar loop, one candidate at a time (the reference `dampbench
  /// bench` measures the lane kernels against). Default: evaluate_block.
  virtual void evaluate_scalar(const CandidateBatch& batch, int first, int count, const Signals& data,
                               SumSet wanted, MetricSums* out) const {
    evaluate_block(batch, first, count, data, wanted, out);
  }

  /// Force of one candidate at every sample, computed by the same kernel as evaluate_block, so the
  /// bits are those the batch path sees.
  [[nodiscard]] virtual std::vector<double> simulate(std::span<const double> params, const Signals& data) const = 0;

  /// Forces of candidates [first, first + count) of `batch` (count ≤ kLanes) in one lane block: candidate i's
  /// force at sample k in out[i·N + k], N = data.size(). Bit-identical to simulate() of each candidate (a
  /// lane's result depends on its own parameters only); NaN throughout for a candidate that blew up. It
  /// costs one block, where `count` calls of simulate cost `count` (finite differences, identifiability).
  /// Default: simulate per candidate.
  virtual void simulate_block(const CandidateBatch& batch, int first, int count, const Signals& data, double* out) const;

  /// True for models with internal states integrated between samples (Bouc–Wen, Spencer, Maxwell, ...), false
  /// for algebraic ones. `fit` chooses its default optimizer and budget by it (engine/fit/fit_defaults.hpp).
  [[nodiscard]] virtual bool has_internal_states() const { return false; }

  /// True for a system model: a structure driven by the force u of a system record (t, y, u), computing its
  /// displacement y (the "force" of simulate and the metrics is then y [m]). False for rig models, which take the
  /// displacement x and compute the force F. A model is only evaluated on records of its own kind.
  [[nodiscard]] virtual bool is_system() const { return false; }

  /// The model stepped one sample at a time (engine/model/stepper.hpp), with the batch kernels' equations in
  /// fixed RK4 sub-steps; nullptr for a model that cannot be (structure models, LS-SVM).
  [[nodiscard]] virtual std::unique_ptr<ModelStepper> stepper() const { return nullptr; }

  /// The force computed by the reference integrator (SUNDIALS CVODE, BDF, tight tolerances) for models
  /// with internal states; nullopt for algebraic models, whose force is exact.
  [[nodiscard]] virtual std::optional<std::vector<double>> simulate_reference(std::span<const double> /*params*/,
                                                                              const Signals& /*data*/) const {
    return std::nullopt;
  }

  /// Values in the paper's table units (ParameterInfo::paper_unit); may depend on other parameters
  /// (fvd's C is in kN/(mm/s)^α). Default: unchanged.
  [[nodiscard]] virtual std::vector<double> to_paper_units(std::span<const double> params) const {
    return {params.begin(), params.end()};
  }

  /// The gauge a law model applies (engine/model/law_model.hpp) unless its laws name the tied parameter;
  /// nullopt for models without a scale symmetry.
  [[nodiscard]] virtual std::optional<StateGauge> state_gauge() const { return std::nullopt; }

  /// Rules that replace the fixed default bounds of some parameters when a record is known (fit, sweeps).
  [[nodiscard]] virtual std::span<const RecordBoundsRule> record_bounds_rules() const { return {}; }

  [[nodiscard]] int dim() const { return static_cast<int>(parameters().size()); }
  /// Index of a parameter; throws InputError naming the model and its parameters.
  [[nodiscard]] int parameter_index(std::string_view name) const;
};

}  // namespace dampbench
