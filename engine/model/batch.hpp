#pragma once
// A batch of candidate parameter sets, stored structure-of-arrays: parameter j of candidate i is
// values[j * stride + i]. Kernels read a parameter for many candidates at once (candidate lanes).
#include <cassert>
#include <span>
#include <vector>

namespace dampbench {

/// Candidates per lane block: kernels always run on full blocks (short blocks are padded with a copy of
/// their first candidate), so every candidate goes through the same vector instructions wherever it
/// sits in a batch. That is what makes results independent of batch composition and thread count.
inline constexpr int kLanes = 16;
/// Lanes of the wider blocks models with internal states also run (Model::max_block_lanes): their RK4 stages are
/// chains of dependent operations, and a wider block gives the CPU more independent chains. A lane gets the same
/// bits in a block of any width (tests/unit/kernels/test_isa.cpp).
inline constexpr int kWideLanes = 32, kWidestLanes = 64;
/// Blocks of single-precision lanes (Model::evaluate_block_float32) hold this many times the candidates of the
/// float64 blocks: a float vector holds twice the lanes, so a block keeps its number of vectors.
inline constexpr int kFloat32LaneScale = 2;

class CandidateBatch {
 public:
  CandidateBatch() = default;
  CandidateBatch(int dim, int count) { resize(dim, count); }

  void resize(int dim, int count) {
    dim_ = dim;
    count_ = count;
    stride_ = (count + kLanes - 1) / kLanes * kLanes;
    values_.assign(static_cast<std::size_t>(dim_) * stride_, 0.0);
  }

  [[nodiscard]] int dim() const { return dim_; }
  [[nodiscard]] int count() const { return count_; }
  [[nodiscard]] int stride() const { return stride_; }

  double& at(int candidate, int param) {
    assert(candidate < count_ && param < dim_);
    return values_[static_cast<std::size_t>(param) * stride_ + candidate];
  }
  [[nodiscard]] double at(int candidate, int param) const {
    assert(candidate < count_ && param < dim_);
    return values_[static_cast<std::size_t>(param) * stride_ + candidate];
  }
  /// All candidates' values of one parameter (count() of them, then padding).
  [[nodiscard]] const double* param_row(int param) const {
    return values_.data() + static_cast<std::size_t>(param) * stride_;
  }

  void set_candidate(int candidate, std::span<const double> params) {
    assert(static_cast<int>(params.size()) == dim_);
    for (int j = 0; j < dim_; ++j) at(candidate, j) = params[j];
  }
  [[nodiscard]] std::vector<double> candidate(int candidate) const {
    std::vector<double> p(dim_);
    for (int j = 0; j < dim_; ++j) p[j] = at(candidate, j);
    return p;
  }

 private:
  int dim_ = 0;
  int count_ = 0;
  int stride_ = 0;
  std::vector<double> values_;
};

}  // namespace dampbench
