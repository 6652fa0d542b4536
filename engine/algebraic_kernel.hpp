#pragma once
// Kernel for algebraic force laws F = f(params; x, v, a, operating variables) (engine/lane_kernel.hpp).
// A Law provides:
//   static constexpr int kParams;  static const ModelInfo& info();
//   struct Sample; static Sample prepare(const Signals&, std::size_t k);   per-sample shared quantities
//   template <class P> static double force(const P& p, int lane, const Sample& s);
#include "engine/lane_kernel.hpp"

namespace dampbench {

template <class Law, int W>
class AlgebraicKernel {
 public:
  AlgebraicKernel(const LaneParams<Law::kParams, W>& p, const Signals& data) : p_(p), data_(data) {}

  void forces(std::size_t k, double* f) const {
    const auto s = Law::prepare(data_, k);
#pragma omp simd
    for (int l = 0; l < W; ++l) f[l] = Law::force(p_, l, s);
  }
  [[nodiscard]] const bool* failed() const { return nullptr; }

 private:
  LaneParams<Law::kParams, W> p_;
  const Signals& data_;
};

template <class Law>
using AlgebraicModel = KernelModel<Law, AlgebraicKernel>;

}  // namespace dampbench
