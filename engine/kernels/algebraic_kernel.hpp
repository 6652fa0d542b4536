#pragma once
// Kernel for algebraic force laws F = f(params; x, v, a, operating variables) (engine/kernels/lane_kernel.hpp).
// A Law provides:
//   static constexpr int kParams;  static const ModelInfo& info();
//   struct Sample; static Sample prepare(const Signals&, std::size_t k);   per-sample shared quantities
//   template <class P> static double force(const P& p, int lane, const Sample& s);
#include <stdexcept>

#include "engine/kernels/lane_kernel.hpp"

namespace dampbench {

template <class Law, int W>
class AlgebraicKernel {
 public:
  AlgebraicKernel(const LawLanes<Law, W>& p, const Signals& data) : p_(p), data_(data) {
    if (data.sgn_v.size() != data.size())  // laws read the invariant columns of prepare_signals
      throw std::logic_error("signals '" + data.name + "' were not built by prepare_signals");
  }

  void forces(std::size_t k, double* f) const {
    const auto s = Law::prepare(data_, k);
#pragma omp simd
    for (int l = 0; l < W; ++l) f[l] = Law::force(p_, l, s);
  }
  [[nodiscard]] const bool* failed() const { return nullptr; }

 private:
  LawLanes<Law, W> p_;
  const Signals& data_;
};

template <class Law>
using AlgebraicModel = KernelModel<Law, AlgebraicKernel>;

}  // namespace dampbench
