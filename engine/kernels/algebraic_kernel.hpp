#pragma once
// Kernel for algebraic force laws F = f(params; x, v, a, operating variables) (engine/kernels/lane_kernel.hpp).
// A Law provides:
//   static constexpr int kParams;  static const ModelInfo& info();
//   struct Sample; static Sample prepare(const Signals&, std::size_t k);   per-sample shared quantities
//   template <class P> static double force(const P& p, int lane, const Sample& s);
// or, for a law whose force makes one vector exp (the generalized viscous laws), instead of force:
//   template <class P> static double exp_argument(const P& p, int lane, const Sample& s);
//   template <class P> static double force_with_exp(const P& p, int lane, const Sample& s, double e);
// with force = force_with_exp(..., exp(exp_argument(...))). The kernel then computes a chunk of samples in three
// passes (arguments, exps, forces), so the libmvec calls run back to back: a call clobbers every vector
// register, and in one pass the registers live across it are saved and restored around each call
// (docs/performance.md has the gain). Same operations per lane, same bits.
// A law with single-precision lanes (kFloat32Lanes) gives its samples in the lanes' real type:
//   template <class R> static Sample<R> prepare(const Signals&, std::size_t k);
// and its float exps take arguments no lower than −80 (lane_exp, engine/common/vector_math.hpp).
#include <stdexcept>
#include <utility>

#include "engine/kernels/lane_kernel.hpp"
#include "engine/kernels/law_stepper.hpp"

namespace dampbench {

template <class Law, int W>
class AlgebraicKernel {
  using R = lane_real_t<Law>;
  static auto prepare(const Signals& data, std::size_t k) {
    if constexpr (kLawHasFloat32<Law>) return Law::template prepare<R>(data, k);
    else return Law::prepare(data, k);
  }
  using Sample = decltype(prepare(std::declval<const Signals&>(), 0));

 public:
  /// The law stepped one sample at a time (Model::stepper).
  template <class L>
  using Stepper = AlgebraicLawStepper<L>;

  AlgebraicKernel(const LawLanes<Law, W>& p, const Signals& data) : p_(p), data_(data) {
    if (data.sgn_v.size() != data.size())  // laws read the invariant columns of prepare_signals
      throw std::logic_error("signals '" + data.name + "' were not built by prepare_signals");
  }

  /// Clones compiled without GCC's PRE pass: faster for the algebraic laws (engine/kernels/isa.hpp).
  static constexpr bool kWithoutTreePre = true;

  static constexpr bool kOneExp = requires(const LawLanes<Law, W>& p, const Sample& s) {
    Law::exp_argument(p, 0, s);
    Law::force_with_exp(p, 0, s, R(1));
  };

  /// Force of every lane at sample k (a law with `force`).
  void forces(std::size_t k, R* f) const
    requires(!kOneExp)
  {
    const auto s = prepare(data_, k);
#pragma omp simd
    for (int l = 0; l < W; ++l) f[l] = Law::force(p_, l, s);
  }
  /// The forces of samples k0 … k0 + m − 1 (m ≤ kMaxChunk) of a one-exp law, in three passes (see the top of
  /// this file); lane l's force is force_with_exp(…, exp(exp_argument(…))), the same operations as one pass.
  static constexpr std::size_t kMaxChunk = 16;
  void forces_chunk(std::size_t k0, std::size_t m, R (*f)[W]) const
    requires kOneExp
  {
    alignas(64) R e[kMaxChunk][W];
    Sample s[kMaxChunk];
    for (std::size_t i = 0; i < m; ++i) {
      s[i] = prepare(data_, k0 + i);
#pragma omp simd
      for (int l = 0; l < W; ++l) e[i][l] = Law::exp_argument(p_, l, s[i]);
    }
    for (std::size_t i = 0; i < m; ++i) {
#pragma omp simd
      for (int l = 0; l < W; ++l) e[i][l] = lane_exp(e[i][l]);
    }
    for (std::size_t i = 0; i < m; ++i) {
#pragma omp simd
      for (int l = 0; l < W; ++l) f[i][l] = Law::force_with_exp(p_, l, s[i], e[i][l]);
    }
  }
  [[nodiscard]] const bool* failed() const { return nullptr; }

 private:
  LawLanes<Law, W> p_;
  const Signals& data_;
};

template <class Law>
using AlgebraicModel = KernelModel<Law, AlgebraicKernel>;

}  // namespace dampbench
