#pragma once
// Candidate-lane kernels (docs/design.md, "Performance principles"): the time loop is outside, the loop over
// kLanes candidates inside and vectorized (`#pragma omp simd`); quantities shared by all lanes at a
// sample are prepared once; metric sums live in lane arrays; no force matrix is stored.
//
// A model is a Law (its equations) run by a Kernel (how time advances):
//   AlgebraicKernel<Law>  F = f(params; x, v, a) at each sample            (engine/kernels/algebraic_kernel.hpp)
//   OdeKernel<Law>        internal states integrated between samples      (engine/kernels/ode_kernel.hpp)
// KernelModel<Kernel> turns a kernel into a Model: evaluate_block (metric sums of up to kLanes
// candidates) and simulate (one candidate's force) both run the same kernel, so they see the same bits.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "engine/model/model.hpp"
#include "engine/common/vector_math.hpp"
#include "engine/kernels/isa.hpp"

namespace dampbench {

/// Static description of a law: id, citation, force law and parameters.
struct ModelInfo {
  std::string id;
  std::string citation;
  std::string law;
  std::vector<ParameterInfo> parameters;
};

/// Parameters of one block of W lanes: p[j][lane], in the lanes' real type R. Kernels run with W = kLanes; W = 1
/// gives the plain scalar loop of the same law, the reference `dampbench bench` compares against.
template <int D, int W = kLanes, class R = double>
struct LaneParams {
  using Real = R;
  alignas(64) R p[D][W];
};

/// A law run in single-precision lanes: twice the lanes per vector, for the global search of `--precision mixed`
/// (engine/evaluation/batch_evaluator.hpp; docs/performance.md, "Mixed precision"). The law's arithmetic follows
/// the lanes' real type (`typename P::Real`); a law opts in with `kFloat32Lanes`. The metric sums stay in double.
template <class Law>
struct Float32 : Law {
  using Real = float;
};
template <class Law>
struct LaneReal {
  using type = double;
};
template <class Law>
  requires requires { typename Law::Real; }
struct LaneReal<Law> {
  using type = typename Law::Real;
};
template <class Law>
using lane_real_t = typename LaneReal<Law>::type;
/// Whether a law's equations are written for any lane real type (KernelModel then has float32 blocks).
template <class Law>
inline constexpr bool kLawHasFloat32 = requires { requires Law::kFloat32Lanes; };

/// Rows of a law's lane block: its kParams parameters, then kLaneInvariants rows a law may add for
/// per-candidate constants (1/(c0 + c1), log k_r, ...) that `Law::lane_invariants(p)` fills once per
/// block, so the time loop does not redo a division or a log at every sample and RK4 stage.
template <class Law>
constexpr int lane_rows() {
  if constexpr (requires { Law::kLaneInvariants; }) return Law::kParams + Law::kLaneInvariants;
  else return Law::kParams;
}
template <class Law, int W>
using LawLanes = LaneParams<lane_rows<Law>(), W, lane_real_t<Law>>;

template <class Law, int W>
void fill_lane_invariants(LawLanes<Law, W>& lanes) {
  if constexpr (requires { Law::lane_invariants(lanes); }) Law::lane_invariants(lanes);
}

/// Copies candidates [first, first + count) into a lane block (rounded to the lanes' real type); lanes past count
/// repeat the first one.
template <class Law, int W = kLanes>
LawLanes<Law, W> gather_lanes(const CandidateBatch& batch, int first, int count) {
  using R = lane_real_t<Law>;
  LawLanes<Law, W> lanes;
  for (int j = 0; j < Law::kParams; ++j) {
    const double* row = batch.param_row(j);
    for (int l = 0; l < W; ++l) lanes.p[j][l] = static_cast<R>(row[first + (l < count ? l : 0)]);
  }
  fill_lane_invariants<Law, W>(lanes);
  return lanes;
}

/// One candidate in every lane (simulate).
template <class Law, int W = kLanes>
LawLanes<Law, W> broadcast_lanes(std::span<const double> params) {
  using R = lane_real_t<Law>;
  LawLanes<Law, W> lanes;
  for (int j = 0; j < Law::kParams; ++j)
    for (int l = 0; l < W; ++l) lanes.p[j][l] = static_cast<R>(params[j]);
  fill_lane_invariants<Law, W>(lanes);
  return lanes;
}

/// The metric sums of a block of W lanes (those of a SumSet), accumulated sample by sample.
template <int W = kLanes>
struct LaneSums {
  alignas(64) double abs_w[W] = {}, sq_w[W] = {}, abs_e[W] = {}, sq_e[W] = {}, abs_mag[W] = {};

  /// Adds m samples: lane l's force at sample i in force[i][l], measured force F[i], weight w[i]; only the sums
  /// of `wanted`, each with the same arithmetic whichever others are computed (so the same bits). Forces of
  /// single-precision lanes are widened to double first.
  template <class R>
  void add(const R (*force)[W], std::size_t m, const double* F, const double* w, SumSet wanted) {
    switch (wanted) {
      case SumSet::every: return add<true, true, true, true, true, R>(force, m, F, w);
      case SumSet::abs_weighted: return add<true, false, false, false, false, R>(force, m, F, w);
      case SumSet::sq_weighted: return add<false, true, false, false, false, R>(force, m, F, w);
      case SumSet::abs: return add<false, false, true, false, false, R>(force, m, F, w);
      case SumSet::sq: return add<false, false, false, true, false, R>(force, m, F, w);
      case SumSet::abs_magnitude: return add<false, false, false, false, true, R>(force, m, F, w);
    }
  }
  /// Writes the first `count` lanes: the sums of `wanted`, NaN for the others; lanes flagged in `failed` get
  /// +inf sums (masked candidates).
  void store(MetricSums* out, int count, SumSet wanted, const bool* failed = nullptr) const {
    const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
    const auto keep = [&](SumSet s, double v) { return wanted == SumSet::every || wanted == s ? v : nan; };
    for (int l = 0; l < count; ++l)
      out[l] = (failed && failed[l])
                   ? MetricSums{inf, inf, inf, inf, inf}
                   : MetricSums{keep(SumSet::abs_weighted, abs_w[l]), keep(SumSet::sq_weighted, sq_w[l]),
                                keep(SumSet::abs, abs_e[l]), keep(SumSet::sq, sq_e[l]),
                                keep(SumSet::abs_magnitude, abs_mag[l])};
  }

 private:
  template <bool kAbsW, bool kSqW, bool kAbs, bool kSq, bool kMag, class R>
  void add(const R (*force)[W], std::size_t m, const double* F, const double* w) {
    for (std::size_t i = 0; i < m; ++i) {
      const double measured = F[i], wi = w[i];
#pragma omp simd
      for (int l = 0; l < W; ++l) {
        const double fl = static_cast<double>(force[i][l]);
        const double e = measured - fl;
        const double ae = std::fabs(e);
        if constexpr (kAbsW) abs_w[l] += wi * ae;
        if constexpr (kSqW) sq_w[l] += wi * (e * e);
        if constexpr (kAbs) abs_e[l] += ae;
        if constexpr (kSq) sq_e[l] += e * e;
        if constexpr (kMag) abs_mag[l] += std::fabs(std::fabs(measured) - std::fabs(fl));
      }
    }
  }
};

/// A kernel template KernelT<Law, W> run over a whole record for one block of W lanes: with kSums, the metric
/// sums of the first `count` lanes into `out`; otherwise their forces (lane l's force at sample k in
/// out[l·n + k], n samples). A lane the kernel flags as failed gets +inf sums or NaN forces. Run through
/// IsaClones (engine/kernels/isa.hpp), so the whole time loop is compiled for each vector instruction set;
/// both variants run the same kernel, so simulate sees the bits evaluate sees.
template <class Law, template <class, int> class KernelT, int W, bool kSums>
struct LaneBlockRun {
  using Out = std::conditional_t<kSums, MetricSums, double>;
  /// Samples whose forces are computed before they are added to the sums. The vector calls (exp, log, ...) of
  /// the forces clobber every vector register, so a loop that did both at each sample saved and restored the
  /// 2·5 sum registers around every call; in chunks the force loop has nothing live across the calls and the
  /// sums loop keeps its accumulators in registers (fvd.gv_linear_elastic: see docs/performance.md). The
  /// order of every operation on a lane is unchanged, so are the bits.
  static constexpr std::size_t kChunk = 16;
  /// The kernel's choice of GCC's PRE pass in the clones (engine/kernels/isa.hpp).
  static constexpr bool kWithoutTreePre = clones_without_tree_pre<KernelT<Law, W>>;

  static void run(const LawLanes<Law, W>* lanes, const Signals* data, int count, Out* out,
                  SumSet wanted = SumSet::every) {
    KernelT<Law, W> kernel(*lanes, *data);
    LaneSums<W> sums;
    alignas(64) lane_real_t<Law> f[kChunk][W];
    const std::size_t n = data->size();
    for (std::size_t k0 = 0; k0 < n; k0 += kChunk) {
      const std::size_t m = std::min(kChunk, n - k0);
      if constexpr (requires { kernel.forces_chunk(k0, m, f); }) {  // a kernel that does a chunk at once
        static_assert(kChunk <= KernelT<Law, W>::kMaxChunk);
        kernel.forces_chunk(k0, m, f);
      } else {
        for (std::size_t i = 0; i < m; ++i) kernel.forces(k0 + i, f[i]);
      }
      if constexpr (kSums) {
        sums.add(f, m, data->F_N.data() + k0, data->w_trapz_s.data() + k0, wanted);
      } else {
        for (std::size_t i = 0; i < m; ++i)
          for (int l = 0; l < count; ++l) out[static_cast<std::size_t>(l) * n + k0 + i] = f[i][l];
      }
    }
    const bool* failed = kernel.failed();
    if constexpr (kSums) {
      sums.store(out, count, wanted, failed);
    } else if (failed) {
      for (int l = 0; l < count; ++l)
        if (failed[l]) std::fill(out + static_cast<std::size_t>(l) * n, out + static_cast<std::size_t>(l + 1) * n, std::nan(""));
    }
  }
};

/// A Model from a Law and a kernel template KernelT<Law, W>, which has:
///   KernelT(const LawLanes<Law, W>&, const Signals&);
///   void forces(std::size_t k, double* f);    force of every lane at sample k (called for k = 0, 1, ...),
///     or forces_chunk(k0, m, f) with kMaxChunk: samples k0 … k0 + m − 1 at once (AlgebraicKernel, one-exp laws)
///   const bool* failed() const;               lanes that blew up (or nullptr)
///   optional: static std::vector<double> reference(params, data)   (CVODE for ODE kernels)
///   optional: static constexpr bool kWithoutTreePre   its clones compiled without GCC's PRE (engine/kernels/isa.hpp)
/// Law provides kParams, info() and optionally to_paper_units, kLaneInvariants, lane_invariants and gauge().
/// evaluate_block, simulate and simulate_block run the same lane block at the active vector level, so they
/// see the same bits; evaluate_scalar runs one lane (W = 1) of plain scalar code, the reference of `bench`.
template <class Law, template <class, int> class KernelT>
class KernelModel final : public Model {
  using ForcesBlock = IsaClones<LaneBlockRun<Law, KernelT, kLanes, false>>;
  using Kernel = KernelT<Law, kLanes>;
  /// Kernels that also run blocks of kWideLanes and kWidestLanes (Kernel::kWideBlocks).
  static constexpr bool kWide = requires { requires Kernel::kWideBlocks; };
  /// Kernels with a reference integrator (CVODE) integrate internal states.
  static constexpr bool kStates = requires(std::span<const double> p, const Signals& d) { Kernel::reference(p, d); };

 public:
  [[nodiscard]] std::string_view id() const override { return Law::info().id; }
  [[nodiscard]] std::string_view citation() const override { return Law::info().citation; }
  [[nodiscard]] std::string_view law() const override { return Law::info().law; }
  [[nodiscard]] std::span<const ParameterInfo> parameters() const override { return Law::info().parameters; }
  [[nodiscard]] std::optional<StateGauge> state_gauge() const override {
    if constexpr (requires { Law::gauge(); }) return Law::gauge();
    return std::nullopt;
  }

  [[nodiscard]] int max_block_lanes() const override { return kWide ? kWidestLanes : kLanes; }
  [[nodiscard]] bool has_internal_states() const override { return kStates; }

  void evaluate_block(const CandidateBatch& batch, int first, int count, const Signals& data, SumSet wanted,
                      MetricSums* out) const override {
    if constexpr (kWide) {
      if (count > kWideLanes) return evaluate_lanes<kWidestLanes>(batch, first, count, data, wanted, out);
      if (count > kLanes) return evaluate_lanes<kWideLanes>(batch, first, count, data, wanted, out);
    }
    evaluate_lanes<kLanes>(batch, first, count, data, wanted, out);
  }

  [[nodiscard]] bool has_float32_lanes() const override { return kLawHasFloat32<Law>; }

  void evaluate_block_float32(const CandidateBatch& batch, int first, int count, const Signals& data, SumSet wanted,
                              MetricSums* out) const override {
    if constexpr (kLawHasFloat32<Law>) {  // the widths of float32_block_shapes (engine/evaluation/lane_blocks.hpp)
      constexpr int k = kFloat32LaneScale;
      if constexpr (kWide) {
        if (count > k * kWideLanes) return evaluate_lanes<k * kWidestLanes, Float32<Law>>(batch, first, count, data, wanted, out);
        if (count > k * kLanes) return evaluate_lanes<k * kWideLanes, Float32<Law>>(batch, first, count, data, wanted, out);
      }
      if (count > kLanes) return evaluate_lanes<k * kLanes, Float32<Law>>(batch, first, count, data, wanted, out);
      evaluate_lanes<kLanes, Float32<Law>>(batch, first, count, data, wanted, out);
    } else {
      evaluate_block(batch, first, count, data, wanted, out);
    }
  }

  [[nodiscard]] std::vector<double> simulate_float32(std::span<const double> params, const Signals& data) const override {
    if constexpr (kLawHasFloat32<Law>) return simulate_lanes<kFloat32LaneScale * kLanes, Float32<Law>>(params, data);
    else return simulate(params, data);
  }

  /// One candidate's force, from a block of W lanes of the law L (Law, or Float32<Law>).
  template <int W, class L = Law>
  static std::vector<double> simulate_lanes(std::span<const double> params, const Signals& data) {
    const auto lanes = broadcast_lanes<L, W>(params);
    std::vector<double> force(data.size());
    IsaClones<LaneBlockRun<L, KernelT, W, false>>::call(&lanes, &data, 1, force.data());
    return force;
  }

  /// evaluate_block with a block of W lanes of the law L (Law, or Float32<Law>).
  template <int W, class L = Law>
  static void evaluate_lanes(const CandidateBatch& batch, int first, int count, const Signals& data, SumSet wanted,
                             MetricSums* out) {
    const auto lanes = gather_lanes<L, W>(batch, first, count);
    IsaClones<LaneBlockRun<L, KernelT, W, true>>::call(&lanes, &data, count, out, wanted);
  }

  bool lane_costs(const CandidateBatch& batch, const Signals& data, std::span<double> out) const override {
    if constexpr (requires { Kernel::substep_profile(data); }) {
      const auto profile = Kernel::substep_profile(data);
      for (int first = 0; first < batch.count(); first += kLanes) {
        const int n = std::min(kLanes, batch.count() - first);
        Kernel::lane_costs(gather_lanes<Law, kLanes>(batch, first, n), data, profile, n, out.data() + first);
      }
      return true;
    } else {
      return false;
    }
  }

  void evaluate_scalar(const CandidateBatch& batch, int first, int count, const Signals& data, SumSet wanted,
                       MetricSums* out) const override {
    for (int i = 0; i < count; ++i) {
      const auto lane = gather_lanes<Law, 1>(batch, first + i, 1);
      LaneBlockRun<Law, KernelT, 1, true>::run(&lane, &data, 1, out + i, wanted);
    }
  }

  [[nodiscard]] std::vector<double> simulate(std::span<const double> params, const Signals& data) const override {
    return simulate_lanes<kLanes>(params, data);
  }

  void simulate_block(const CandidateBatch& batch, int first, int count, const Signals& data, double* out) const override {
    const auto lanes = gather_lanes<Law, kLanes>(batch, first, count);
    ForcesBlock::call(&lanes, &data, count, out);
  }

  [[nodiscard]] std::span<const RecordBoundsRule> record_bounds_rules() const override {
    if constexpr (requires { Law::record_bounds_rules(); }) return Law::record_bounds_rules();
    else return {};
  }

  [[nodiscard]] std::vector<double> to_paper_units(std::span<const double> params) const override {
    if constexpr (requires { Law::to_paper_units(params); }) return Law::to_paper_units(params);
    else return Model::to_paper_units(params);
  }

  [[nodiscard]] std::optional<std::vector<double>> simulate_reference(std::span<const double> params,
                                                                      const Signals& data) const override {
    if constexpr (kStates) return Kernel::reference(params, data);
    else return std::nullopt;
  }

  /// The kernel's law stepped sample by sample (engine/kernels/law_stepper.hpp), where the kernel names one.
  [[nodiscard]] std::unique_ptr<ModelStepper> stepper() const override {
    if constexpr (requires { typename Kernel::template Stepper<Law>; })
      return std::make_unique<typename Kernel::template Stepper<Law>>();
    else return nullptr;
  }
};

}  // namespace dampbench
