#pragma once
// A model whose parameters are laws in the operating variables (engine/model/parameter_law.hpp): its own
// parameters are the laws' coefficients. Fitted on several datasets (conditions) at once, one set of
// coefficients serves every condition (crfd §5, mfm eqs. 4–11, fdsp eqs. 13–14).
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "engine/model/model.hpp"
#include "engine/model/parameter_law.hpp"

namespace dampbench {

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
  /// The base model's rules; those of parameters replaced by a law do not apply.
  [[nodiscard]] std::span<const RecordBoundsRule> record_bounds_rules() const override {
    return base().record_bounds_rules();
  }

  void evaluate_block(const CandidateBatch& batch, int first, int count, const Signals& data, SumSet wanted,
                      MetricSums* out) const override;
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
  /// Throws InputError if the record lacks a variable some law needs.
  void check_variables(const Signals& data) const;

  [[nodiscard]] const Model& base() const { return base_; }

 private:
  /// The base parameters of candidates [first, first + count) under the record's variables (thread scratch).
  const CandidateBatch& base_block(const CandidateBatch& batch, int first, int count, const Signals& data) const;

  const Model& base_;
  std::vector<ParameterLaw> laws_;   ///< one per base parameter
  std::vector<int> offsets_;         ///< first coefficient of each base parameter
  std::vector<ParameterInfo> coefficients_;
  std::string id_, citation_, law_text_;
};

}  // namespace dampbench
