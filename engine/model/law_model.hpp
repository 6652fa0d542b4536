#pragma once
// A model whose parameters are laws in the operating variables (engine/model/parameter_law.hpp): its own
// parameters are the laws' coefficients. Fitted on several datasets (conditions) at once, one set of
// coefficients serves every condition (crfd §5, mfm eqs. 4–11, fdsp eqs. 13–14).
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/model/model.hpp"
#include "engine/model/parameter_law.hpp"

namespace dampbench {

/// The driver's lag of a commanded variable (Spencer et al. 1997; fdsp eq. 7 with η = 1/τ): the laws see u with
/// u̇ = (c(t) − u)/τ instead of the command c, u(0) = c(0). Given in the laws as `tau_I=free` (τ a coefficient, in
/// seconds) or `tau_I=0.02` (fixed). Under a constant command u stays c, so the batch kernels, which take one value
/// per record, are exact without it; on a record whose command varies, the model is stepped sample by sample
/// (engine/model/stepper.hpp), which integrates it.
struct DriverLag {
  std::string variable;
  int coefficient = -1;   ///< τ's index among the coefficients, or −1 when fixed
  double fixed_tau_s = 0;
};

class LawModel final : public Model {
 public:
  /// `laws` maps base parameter names to laws; parameters without a law stay free constants.
  /// Throws InputError for a law on an unknown parameter.
  /// `id` and `citation` name a published model built this way (default: "BASE[laws]", the base's).
  LawModel(const Model& base, std::map<std::string, ParameterLaw> laws, std::string id = "", std::string citation = "");

  /// Replaces a coefficient's default bounds (InputError for an unknown name).
  void set_default_bounds(std::string_view name, double lower, double upper);

  [[nodiscard]] std::string_view id() const override { return id_; }
  [[nodiscard]] std::string_view citation() const override { return citation_; }
  [[nodiscard]] std::string_view law() const override { return law_text_; }
  [[nodiscard]] std::span<const ParameterInfo> parameters() const override { return coefficients_; }
  /// The base model's rules (those of the gauge replacing theirs); those of parameters replaced by a law do not
  /// apply.
  [[nodiscard]] std::span<const RecordBoundsRule> record_bounds_rules() const override { return bounds_rules_; }
  /// The base model's gauge when this law model applies it (its laws do not name the tied parameter).
  [[nodiscard]] const std::optional<StateGauge>& applied_gauge() const { return gauge_; }

  void evaluate_block(const CandidateBatch& batch, int first, int count, const Signals& data, SumSet wanted,
                      MetricSums* out) const override;
  [[nodiscard]] bool has_float32_lanes() const override { return base_.has_float32_lanes(); }
  void evaluate_block_float32(const CandidateBatch& batch, int first, int count, const Signals& data, SumSet wanted,
                              MetricSums* out) const override;
  [[nodiscard]] std::vector<double> simulate_float32(std::span<const double> coefficients,
                                                     const Signals& data) const override;
  [[nodiscard]] int max_block_lanes() const override { return base_.max_block_lanes(); }
  [[nodiscard]] bool has_internal_states() const override { return base_.has_internal_states(); }
  bool lane_costs(const CandidateBatch& batch, const Signals& data, std::span<double> out) const override;
  void evaluate_scalar(const CandidateBatch& batch, int first, int count, const Signals& data, SumSet wanted,
                       MetricSums* out) const override;
  [[nodiscard]] std::vector<double> simulate(std::span<const double> coefficients, const Signals& data) const override;
  void simulate_block(const CandidateBatch& batch, int first, int count, const Signals& data, double* out) const override;
  [[nodiscard]] std::optional<std::vector<double>> simulate_reference(std::span<const double> coefficients,
                                                                      const Signals& data) const override;

  /// The base model's parameters for these coefficients under the record's operating variables.
  [[nodiscard]] std::vector<double> base_parameters(std::span<const double> coefficients, const Signals& data) const;
  /// The same under operating variables by name; InputError naming a variable a law needs and `variables` lack.
  [[nodiscard]] std::vector<double> base_parameters(std::span<const double> coefficients,
                                                    const std::map<std::string, double>& variables) const;
  /// The base model's stepper with the laws evaluated at the variables each set_parameters gives (a command that
  /// changes between steps changes the base parameters there; the states carry on). In law_model_stepper.cpp.
  [[nodiscard]] std::unique_ptr<ModelStepper> stepper() const override;
  /// Whether a law reads a variable that varies over the record (a column in Dataset::operating_signals): such a
  /// record is evaluated candidate by candidate, stepped sample by sample (engine/model/stepped_simulation.hpp)
  /// with the batch kernels' sub-step rules, instead of in lanes at one value per record.
  [[nodiscard]] bool follows_columns(const Signals& data) const;
  /// Throws InputError if the record lacks a variable some law needs.
  void check_variables(const Signals& data) const;
  /// The operating variables its laws read, sorted, each once.
  [[nodiscard]] const std::vector<std::string>& law_variables() const { return law_variables_; }

  [[nodiscard]] const Model& base() const { return base_; }
  /// The law of each base parameter (in the base's order) and the index of its first coefficient (what the C export
  /// writes out); the gauge's tied base parameter (−1: none) and the base parameters it is the sum of.
  [[nodiscard]] const std::vector<ParameterLaw>& laws() const { return laws_; }
  [[nodiscard]] int coefficient_offset(int base_parameter) const { return offsets_[static_cast<std::size_t>(base_parameter)]; }
  [[nodiscard]] int gauge_tied() const { return gauge_tied_; }
  [[nodiscard]] const std::vector<int>& gauge_sum_of() const { return gauge_sum_of_; }
  /// The driver lags of its commanded variables (none for most law models).
  [[nodiscard]] const std::vector<DriverLag>& lags() const { return lags_; }
  /// τ [s] of a lag for these coefficients.
  [[nodiscard]] double lag_tau(const DriverLag& lag, std::span<const double> coefficients) const {
    return lag.coefficient >= 0 ? coefficients[static_cast<std::size_t>(lag.coefficient)] : lag.fixed_tau_s;
  }

 private:
  /// Applies the base model's gauge unless `laws` name its tied parameter (then the user has chosen the states'
  /// scale); the tied parameter gets a fixed law (no coefficient) whose value base_values overwrites.
  void apply_gauge(const Model& base, std::map<std::string, ParameterLaw>& laws);
  /// Takes the `tau_<variable>` entries out of `laws` (names the base does not have) and appends a free τ's
  /// coefficient; InputError for a lag of a variable no law uses or a τ that is not free or a number >= 0.
  void take_lags(std::map<std::string, ParameterLaw>& laws, std::string& law_list);
  void find_law_variables();
  /// The base parameter's info with the gauge's unit.
  [[nodiscard]] ParameterInfo gauged_info(const ParameterInfo& p) const;
  /// The base parameters of one candidate's coefficients `c` under operating variables `v`, into p[0, base dim).
  void base_values(const double* c, const std::map<std::string, double>& v, double* p) const;
  /// The force on such a record: stepped with the kernels' sub-step rules; NaN throughout for a candidate that
  /// blows up, is too stiff or has a driver lag's τ below 0.
  [[nodiscard]] std::vector<double> stepped_force(std::span<const double> coefficients, const Signals& data) const;
  /// evaluate_block on such a record: each candidate's stepped force and its metric sums (every sum; +inf for a
  /// candidate that blows up or is too stiff).
  void evaluate_stepped(const CandidateBatch& batch, int first, int count, const Signals& data, MetricSums* out) const;
  /// The base parameters of candidates [first, first + count) under the record's variables (thread scratch).
  const CandidateBatch& base_block(const CandidateBatch& batch, int first, int count, const Signals& data) const;

  const Model& base_;
  std::vector<ParameterLaw> laws_;   ///< one per base parameter
  std::vector<int> offsets_;         ///< first coefficient of each base parameter
  std::vector<ParameterInfo> coefficients_;
  std::vector<RecordBoundsRule> bounds_rules_;
  std::optional<StateGauge> gauge_;
  int gauge_tied_ = -1;                 ///< base index of the gauge's tied parameter (−1: no gauge)
  std::vector<int> gauge_sum_of_;       ///< base indices it is the sum of
  std::vector<DriverLag> lags_;
  std::vector<std::string> law_variables_;  ///< sorted, each once (find_law_variables)
  std::string id_, citation_, law_text_;
};

}  // namespace dampbench
