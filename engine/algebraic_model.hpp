#pragma once
// Candidate-lane kernel for algebraic force laws F = f(params; x, v, a) (DESIGN.md, "Performance
// principles"): the time loop is outside, the loop over kLanes candidates inside and vectorized;
// quantities shared by all lanes at a sample (sgn v, log|v|, ...) are prepared once by the law; the
// four metric sums live in lane arrays and no force matrix is stored.
//
// A Law is a small struct:
//   static constexpr int kParams;                              number of parameters
//   static const ModelInfo& info();                            id, citation, law, parameters
//   struct Sample; static Sample prepare(const Signals&, k);   per-sample shared quantities
//   template <class P> static double force(const P& p, int lane, const Sample& s);
//   optional: static std::vector<double> to_paper_units(std::span<const double>);
#include <cmath>
#include <span>
#include <vector>

#include "engine/model.hpp"
#include "engine/vector_math.hpp"

namespace dampbench {

struct ModelInfo {
  std::string id;
  std::string citation;
  std::string law;
  std::vector<ParameterInfo> parameters;
};

/// Parameters of one lane block: p[j][lane].
template <int D>
struct LaneParams {
  alignas(64) double p[D][kLanes];
};

/// Copies candidates [first, first + count) into a lane block; lanes past count repeat the first one.
template <int D>
LaneParams<D> gather_lanes(const CandidateBatch& batch, int first, int count) {
  LaneParams<D> lanes;
  for (int j = 0; j < D; ++j) {
    const double* row = batch.param_row(j);
    for (int l = 0; l < kLanes; ++l) lanes.p[j][l] = row[first + (l < count ? l : 0)];
  }
  return lanes;
}

template <class Law>
class AlgebraicModel final : public Model {
 public:
  [[nodiscard]] std::string_view id() const override { return Law::info().id; }
  [[nodiscard]] std::string_view citation() const override { return Law::info().citation; }
  [[nodiscard]] std::string_view law() const override { return Law::info().law; }
  [[nodiscard]] std::span<const ParameterInfo> parameters() const override { return Law::info().parameters; }

  void evaluate_block(const CandidateBatch& batch, int first, int count, const Signals& data,
                      MetricSums* out) const override {
    const auto P = gather_lanes<Law::kParams>(batch, first, count);
    alignas(64) double abs_w[kLanes] = {}, sq_w[kLanes] = {}, abs_e[kLanes] = {}, sq_e[kLanes] = {};
    const std::size_t n = data.size();
    for (std::size_t k = 0; k < n; ++k) {
      const auto s = Law::prepare(data, k);
      const double measured = data.F_N[k];
      const double w = data.w_trapz_s[k];
#pragma omp simd
      for (int l = 0; l < kLanes; ++l) {
        const double e = measured - Law::force(P, l, s);
        const double ae = std::fabs(e);
        abs_w[l] += w * ae;
        sq_w[l] += w * (e * e);
        abs_e[l] += ae;
        sq_e[l] += e * e;
      }
    }
    for (int l = 0; l < count; ++l) out[l] = {abs_w[l], sq_w[l], abs_e[l], sq_e[l]};
  }

  [[nodiscard]] std::vector<double> simulate(std::span<const double> params, const Signals& data) const override {
    LaneParams<Law::kParams> P;
    for (int j = 0; j < Law::kParams; ++j)
      for (int l = 0; l < kLanes; ++l) P.p[j][l] = params[j];
    std::vector<double> force(data.size());
    for (std::size_t k = 0; k < data.size(); ++k) {
      const auto s = Law::prepare(data, k);
      alignas(64) double f[kLanes];
#pragma omp simd
      for (int l = 0; l < kLanes; ++l) f[l] = Law::force(P, l, s);
      force[k] = f[0];
    }
    return force;
  }

  [[nodiscard]] std::vector<double> to_paper_units(std::span<const double> params) const override {
    if constexpr (requires { Law::to_paper_units(params); }) return Law::to_paper_units(params);
    else return Model::to_paper_units(params);
  }
};

}  // namespace dampbench
