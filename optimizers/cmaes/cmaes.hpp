#pragma once
// `cmaes`: the covariance matrix adaptation evolution strategy (Hansen 2016, "The CMA Evolution Strategy: A
// Tutorial", arXiv:1604.00772; one run: optimizers/cmaes/strategy.hpp) with restarts:
//   none   one run; the optimizer finishes at its first stopping test, which may be before the budget is spent;
//   ipop   (the default) each stopping test starts a new run from a uniform mean with the population doubled,
//          λ_k = 2^k λ₀ (Auger & Hansen 2005, "A restart CMA evolution strategy with increasing population
//          size", CEC 2005), until the budget is spent. The default because it is monotone and predictable: a
//          larger population each time makes CMA-ES more global on multimodal landscapes; BIPOP's small regime
//          is meant for populations near the default λ, and fit's own populations (50) are already large;
//   bipop  Hansen 2009 ("Benchmarking a BI-population CMA-ES on the BBOB-2009 function testbed", GECCO
//          workshops): after a first run with λ₀, the regime with the fewer evaluations so far runs next (the
//          first run counts for neither; large on ties): the large regime with λ_l = 2^k λ₀ (k its runs so
//          far, the first included) and σ₀; the small regime with λ_s = ⌊λ₀ (λ_l/(2 λ₀))^{U₁²}⌋, σ₀·10^{−2 U₂}
//          and at most half the evaluations of the last large run (U₁, U₂ uniform in [0, 1)).
// Coordinates: each run works on the free parameters mapped to [0, 1] (optimizers/unit_box.hpp), with σ₀ =
// sigma0 (0.3 of every range by default) and C₀ = I. Bounds: pycma's boundary transformation
// (optimizers/cmaes/bound_transform.hpp): samples are unbounded genotypes, the candidates asked their images in
// the box, and the update uses the genotypes. The first run's mean is Bounds::start when given (an earlier
// stage's point); else the first ask is λ₀ uniform points in the box and the first run starts from the best
// of them (as pagmo2's cmaes starts from its initial population's best: on wide damper boxes a uniform mean
// often lies where every nearby candidate fails or the landscape is flat). Every restart's mean is a uniform
// draw.
//
// Batches and budget: every ask is `population` candidates (λ₀; 0 = Hansen's default λ₀ = 4 + ⌊3 ln n⌋ for n
// free parameters), so the identification's lockstep batch keeps its size across restarts. A generation of
// λ = 2^k λ₀ samples is asked in 2^k consecutive asks, and updated when the last of them is told; BIPOP's
// small λ_s is rounded up to a whole number of asks. The run costs exactly population × iterations
// evaluations (restarts included; the last generation may be cut short by the budget, and is then evaluated
// but not updated), except with restarts = none (fewer when it stops first).
// Failed candidates (+inf, NaN, −inf) rank behind every finite value and are never the best.
// Random numbers: the first ask's uniform points from stream (run_key, 2⁶⁴ − 1); run r's draws (r = 0 first)
// from stream (run_key, r, 0): the mean's n uniforms, then for a small BIPOP run U₁ and U₂; sample k of run r's
// generation g ≥ 1 from (run_key, r, g, k), n normals.
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include <Eigen/Dense>

#include "engine/common/random.hpp"
#include "engine/identification/optimizer.hpp"
#include "optimizers/cmaes/strategy.hpp"
#include "optimizers/setting_table.hpp"
#include "optimizers/unit_box.hpp"

namespace dampbench {

enum class CmaesRestarts { none, ipop, bipop };

/// Parses "none", "ipop" or "bipop" (InputError naming the known ones otherwise).
CmaesRestarts parse_cmaes_restarts(std::string_view name);
std::string_view cmaes_restarts_name(CmaesRestarts restarts);

/// Hansen's default population λ₀ = 4 + ⌊3 ln n⌋ for n free parameters (Hansen 2016, Table 1).
int cmaes_default_population(int free_parameters);

struct CmaesSettings {
  int population = 0;     ///< λ₀ and the size of every ask; 0 = 4 + ⌊3 ln n⌋ (Hansen 2016, Table 1)
  int generations = 100;  ///< asks; the budget is population × generations evaluations, restarts included
  CmaesRestarts restarts = CmaesRestarts::ipop;
  double sigma0 = 0.3;    ///< initial step size as a fraction of each parameter's range, in (0, 1]
  double tolfun = 1e-12;  ///< stopping test "tolfun", in the metric's units (strategy.hpp)
  double tolx = 1e-12;    ///< stopping test "tolx", relative to the run's σ₀ (strategy.hpp)

  /// Throws InputError: population 1 or negative, generations < 1, sigma0 outside (0, 1], tolfun or tolx
  /// negative or not finite.
  void validate() const;
};

/// cmaes's number settings (setting_table.hpp); `restarts` is a choice the registry reads.
const SettingTable<CmaesSettings>& cmaes_setting_table();

/// One CMA-ES run of the restart sequence.
struct CmaesRun {
  int lambda = 0;
  double sigma0 = 0;
  bool large = true;              ///< BIPOP's regime (always true for none and ipop)
  long long evaluations = 0;      ///< of the generations told so far
  std::string_view stop;          ///< the stopping test that ended it, "" while it runs
};

class Cmaes final : public Optimizer {
 public:
  Cmaes(const CmaesSettings& settings, const Bounds& bounds, std::uint64_t run_key);

  [[nodiscard]] int batch_size() const override { return batch_; }
  void ask(CandidateBatch& batch, int first) override;
  void tell(std::span<const double> values) override;
  [[nodiscard]] bool finished() const override { return asks_ >= settings_.generations || ended_; }
  [[nodiscard]] std::span<const double> best_position() const override { return best_position_; }
  [[nodiscard]] double best_value() const override { return best_value_; }
  /// Every run started so far, the current one last.
  [[nodiscard]] const std::vector<CmaesRun>& runs() const { return runs_; }

 private:
  /// Starts the next run of the restart sequence; `mean` (genotype) replaces its drawn mean when given.
  void start_run(const Eigen::VectorXd* mean = nullptr);
  void end_generation();
  void draw_uniform_sample();  ///< the first ask's points, into sample_unit_
  /// Writes the candidates of unit-box points (row-major batch_ × n_) into asked_ and rows first… of `batch`.
  void write_asked(std::span<const double> unit, CandidateBatch& batch, int first);
  void start_from_sample(std::span<const double> values);
  [[nodiscard]] Eigen::VectorXd initial_mean(RandomStream& rng) const;

  CmaesSettings settings_;
  UnitBox box_;
  std::vector<double> start_;  ///< Bounds::start, or empty
  std::uint64_t run_key_;
  int dim_, n_, batch_;        ///< parameters, CMA-ES dimension (free parameters, at least 1), ask size
  int asks_ = 0;
  bool ended_ = false;
  bool sampling_ = false;      ///< the first ask is the uniform sample the first run starts from
  std::vector<double> sample_unit_;  ///< that sample's points in the unit box, row-major (batch_ × n_)
  std::optional<CmaStrategy> strategy_;
  Eigen::MatrixXd samples_;    ///< the current generation's genotypes (columns)
  std::vector<double> asked_unit_;  ///< ask()'s phenotypes in the unit box, kept to reuse its storage
  std::vector<double> values_, asked_;  ///< the generation's values; the last ask's candidates, row-major
  int told_ = 0;               ///< samples of the current generation told so far
  int large_runs_ = 0;
  long long large_evaluations_ = 0, small_evaluations_ = 0;
  std::vector<CmaesRun> runs_;
  std::vector<double> best_position_;
  double best_value_ = std::numeric_limits<double>::infinity();
};

}  // namespace dampbench
