#pragma once
// Kernel for laws with internal states (Bouc–Wen, Spencer, generalized Maxwell, voltage filter): classical
// Runge–Kutta (RK4) with fixed sub-steps between samples, vectorized over candidate lanes. A fixed scheme runs
// the same instructions on every lane, so it vectorizes and a lane's bits depend on its own parameters and the
// record only. SUNDIALS CVODE (BDF, rtol 1e-10) on the same piecewise-linear inputs is the reference, so their
// difference is the integration error alone; states start at zero at the first sample. Sub-steps follow the
// motion, not the clock (ode_substeps); a stiff lane takes more of them (kStiffStep); |z|^n comes from a series
// chained along the lane (kSeriesTerms, kChainSteps), because a vector log and exp at every stage dominated the
// time; a lane that blows up is masked and reset so it never slows or poisons its neighbours.
// docs/performance.md has the design and its measurements ("How the kernels work") and the exact rules with
// their error bounds ("The ODE kernel's rules").
//
// A Law provides:
//   static constexpr int kParams, kStates; static constexpr double kSubstepsPerStroke;
//   optional: static constexpr bool kStrokeDriven (see ode_substeps; default false)
//   optional: static constexpr double kStiffStep (h·λ of a stiff lane's sub-step; default ::kStiffStep below)
//   static const ModelInfo& info();
//   struct Context; static Context context(const Signals&);          per-record constants (V, ω, ...)
//   template <class P, class Y, class DY>
//   static void rhs(const P&, int lane, const Context&, double x, double v, const Y& y, DY&& dydt);
//   template <class P, class Y> static double force(const P&, int lane, const Context&, double x, double v, const Y& y);
//   optional: kLaneInvariants and lane_invariants(p), per-candidate constants (engine/kernels/lane_kernel.hpp)
//   optional: template <class P> static double stiffness(const P&, int lane, const Context&, const RecordScales&)
//   optional: static constexpr int kPowerState, kPowerExponentRow (see kSeriesTerms below); rhs then
//             takes the power as an argument: rhs(p, lane, context, x, v, y, double y_power, dydt)
// where y[j] and dydt[j] index the states (a LaneState view in the kernel, a plain pointer in CVODE).
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "engine/kernels/lane_kernel.hpp"
#include "engine/kernels/cvode_integrator.hpp"
#include "engine/kernels/law_stepper.hpp"
#include "engine/kernels/substep_rule.hpp"

namespace dampbench {

/// State j of one lane inside a [states][W] block: y[j] is block[j][lane]. Indexing through it keeps
/// the lane loop free of private arrays, which GCC's vectorizer cannot handle in `omp simd` loops.
template <int W, class R = double>
struct LaneState {
  R* base;
  R& operator[](int j) const { return base[j * W]; }
};

template <class Law, int W>
class OdeKernel {
 public:
  static constexpr int S = Law::kStates;
  using R = lane_real_t<Law>;  // the lanes' real type: double, or float (Float32<Law>)
  using State = LaneState<W, R>;
  /// Also run as blocks of kWideLanes and kWidestLanes lanes (engine/model/batch.hpp, chosen per batch by
  /// engine/evaluation/lane_blocks.hpp): four dependent RK4 stages per sub-step leave the CPU waiting at kLanes
  /// lanes, and wider blocks give it independent work (docs/performance.md has the measurements).
  static constexpr bool kWideBlocks = true;
  /// The law stepped one sample at a time (Model::stepper).
  template <class L>
  using Stepper = OdeLawStepper<L>;
  static constexpr bool kStrokeDriven = law_stroke_driven<Law>();
  static constexpr bool kPower = requires { Law::kPowerState; };
  static constexpr double kLawStiffStep = law_stiff_step<Law>();
  /// Powers of a state: a law that names a state (`kPowerState`) and the lane-block row of its exponent e
  /// (`kPowerExponentRow`) gets |s|^e as an argument of rhs, from the binomial series of (1 + ε)^e to
  /// ε^kSeriesTerms wherever s = s0·(1 + ε) with |ε| ≤ kSeriesRadius from a point s0 whose power is known, else
  /// exactly (log and exp). The truncation, below |C(e, 9)|·32^−9 < 4e-16 relative for 0 ≤ e ≤ 7, is less than
  /// the exact path's own rounding; the terms and radius are the fastest pair found (docs/performance.md). Float
  /// lanes need less: 6 terms within 1/16, |C(e, 7)|·16^−7 < 4e-9 relative for 0 ≤ e ≤ 7, below float's 6e-8.
  static constexpr bool kFloat = std::is_same_v<R, float>;
  static constexpr int kSeriesTerms = kFloat ? 6 : 8;
  static constexpr double kSeriesRadius = kFloat ? 1.0 / 16.0 : 1.0 / 32.0;
  /// Anchor spacing of the chained power: a sub-step's start takes its power from the previous start's series
  /// except at an anchor (anchored()), at a lane's first sub-step and after a reset, so a chain is at most
  /// K² − 1 series long (K = kChainSteps) and a stage's power stays within about 1e-14 relative of the exact one
  /// (tests/unit/kernels/test_ode_power_chain.cpp). A law may set its own (tests: 1, the exact power at every sub-step's
  /// start).
  static constexpr int kChainSteps = [] {
    if constexpr (requires { Law::kChainSteps; }) return Law::kChainSteps;
    else return 4;
  }();
  static_assert(kChainSteps >= 1);

  static constexpr bool kStiff = requires(const LawLanes<Law, W>& p, const typename Law::Context& c) {
    Law::stiffness(p, 0, c, RecordScales{});
  };

  OdeKernel(const LawLanes<Law, W>& p, const Signals& data)
      : p_(p), data_(data), ctx_(Law::context(data)) {
    if constexpr (kStiff) stiffness_of_lanes(p_, ctx_, data, W, lambda_);
    if constexpr (kPower) {
      for (int l = 0; l < W; ++l) {  // C(e, i) = C(e, i − 1)·(e − i + 1)/i
        const double e = p_.p[Law::kPowerExponentRow][l];
        double c = 1.0;
        for (int i = 1; i <= kSeriesTerms; ++i) series_[i - 1][l] = static_cast<R>(c *= (e - (i - 1)) / i);
      }
    }
  }

  /// Each of the first `count` lanes' stiffness estimate λ [1/s] (≥ 0; +inf where it is not finite).
  static void stiffness_of_lanes(const LawLanes<Law, W>& p, const typename Law::Context& ctx, const Signals& data,
                                 int count, double* lambda)
    requires kStiff
  {
    const RecordScales scales{data.velocity_max_abs, data.displacement_ptp};
    for (int l = 0; l < count; ++l) {
      const double estimate = Law::stiffness(p, l, ctx, scales);
      lambda[l] = std::isfinite(estimate) ? std::max(estimate, 0.0) : std::numeric_limits<double>::infinity();
    }
  }

  /// What the lane costs of a record need: the record's sub-step counts n_k, sorted, with suffix sums, and the
  /// longest interval.
  struct SubstepProfile {
    std::vector<double> counts;  // n_k of every interval, ascending
    std::vector<double> above;   // above[i] = counts[i] + counts[i + 1] + ...
    double dt_max = 0;
  };
  static SubstepProfile substep_profile(const Signals& data)
    requires kStiff
  {
    SubstepProfile r;
    for (std::size_t k = 1; k < data.size(); ++k) {
      r.counts.push_back(ode_substeps(data, k, Law::kSubstepsPerStroke, kStrokeDriven));
      r.dt_max = std::max(r.dt_max, data.t_s[k] - data.t_s[k - 1]);
    }
    std::ranges::sort(r.counts);
    r.above.assign(r.counts.size() + 1, 0.0);
    for (std::size_t i = r.counts.size(); i-- > 0;) r.above[i] = r.above[i + 1] + r.counts[i];
    return r;
  }

  /// Model::lane_costs of the first `count` lanes: the mean sub-steps per interval each takes, the mean of
  /// max(n_k, its stiff count) (stiff_substeps; a lane that will be masked takes the record's n_k).
  static void lane_costs(const LawLanes<Law, W>& p, const Signals& data, const SubstepProfile& profile, int count,
                         double* out)
    requires kStiff
  {
    double lambda[W];
    stiffness_of_lanes(p, Law::context(data), data, count, lambda);
    const double intervals = static_cast<double>(profile.counts.size());
    for (int l = 0; l < count; ++l) {
      double stiff = std::ceil(profile.dt_max * lambda[l] / kLawStiffStep);
      if (!(stiff <= kMaxSubsteps)) stiff = 0.0;
      const auto below = std::ranges::lower_bound(profile.counts, stiff) - profile.counts.begin();
      out[l] = intervals > 0 ? (stiff * static_cast<double>(below) + profile.above[static_cast<std::size_t>(below)]) / intervals
                             : 1.0;
    }
  }

  void forces(std::size_t k, R* f) {
    if (k > 0) advance(k);
    const R x = static_cast<R>(data_.x_m[k]), v = static_cast<R>(data_.v_m_s[k]);
#pragma omp simd
    for (int l = 0; l < W; ++l) f[l] = Law::force(p_, l, ctx_, x, v, State{&y_[0][l]});
  }
  [[nodiscard]] const bool* failed() const {
    for (int l = 0; l < W; ++l) failed_flags_[l] = failed_[l] > 0.0;
    return failed_flags_;
  }

  /// Force of one candidate by CVODE on the same piecewise-linear inputs (the reference).
  static std::vector<double> reference(std::span<const double> params, const Signals& data) {
    const auto P = broadcast_lanes<Law, 1>(params);
    const auto ctx = Law::context(data);
    std::size_t interval = 0;  // last interval used; times only move forward within one CVODE call
    auto input = [&](double t, double& x, double& v) {
      while (interval + 2 < data.size() && t > data.t_s[interval + 1]) ++interval;
      while (interval > 0 && t < data.t_s[interval]) --interval;
      const double t0 = data.t_s[interval], t1 = data.t_s[interval + 1];
      const double th = std::clamp((t - t0) / (t1 - t0), 0.0, 1.0);
      x = data.x_m[interval] + th * (data.x_m[interval + 1] - data.x_m[interval]);
      v = data.v_m_s[interval] + th * (data.v_m_s[interval + 1] - data.v_m_s[interval]);
    };
    const auto states = integrate_cvode(
        [&](double t, std::span<const double> y, std::span<double> dydt) {
          double x, v;
          input(t, x, v);
          if constexpr (kPower)
            Law::rhs(P, 0, ctx, x, v, y.data(), abs_pow(y[Law::kPowerState], P.p[Law::kPowerExponentRow][0]), dydt.data());
          else
            Law::rhs(P, 0, ctx, x, v, y.data(), dydt.data());
        },
        std::vector<double>(S, 0.0), data.t_s, {1e-10, 1e-12, 1000000});
    std::vector<double> force(data.size());
    for (std::size_t k = 0; k < data.size(); ++k)
      force[k] = Law::force(P, 0, ctx, data.x_m[k], data.v_m_s[k], states[k].data());
    return force;
  }

 private:
  /// Integrates every lane from sample k−1 to sample k.
  void advance(std::size_t k) {
    const int n = ode_substeps(data_, k, Law::kSubstepsPerStroke, kStrokeDriven);
    const double dt = data_.t_s[k] - data_.t_s[k - 1];
    const double x0 = data_.x_m[k - 1], dx = data_.x_m[k] - x0;
    const double v0 = data_.v_m_s[k - 1], dv = data_.v_m_s[k] - v0;
    if constexpr (kStiff) {
      if (!(dt <= stiff_dt_ && dt >= stiff_dt_ * (1.0 - 2 * kStiffDtSlack))) stiff_substeps(dt * (1.0 + kStiffDtSlack));
    }
    if (stiff_max_ <= n) {  // every lane takes the record's sub-steps: one set of inputs for all
      const R inv = R(1) / static_cast<R>(n), h = static_cast<R>(dt) * inv;  // LaneInputs: the same arithmetic lane by lane
      const R x0r = static_cast<R>(x0), dxr = static_cast<R>(dx), v0r = static_cast<R>(v0), dvr = static_cast<R>(dv);
      for (int i = 0; i < n; ++i) {
        const R a = static_cast<R>(i) * inv, m = (static_cast<R>(i) + R(0.5)) * inv, b = static_cast<R>(i + 1) * inv;
        step(SharedInputs{h, x0r + a * dxr, v0r + a * dvr, x0r + m * dxr, v0r + m * dvr, x0r + b * dxr, v0r + b * dvr},
             anchored(k, i));
      }
    } else {
      const R record = static_cast<R>(n);
      R n_max = record;
#pragma omp simd reduction(max : n_max)
      for (int l = 0; l < W; ++l) {
        n_[l] = std::max(record, stiff_[l]);
        inv_n_[l] = R(1) / n_[l];
        n_max = std::max(n_max, n_[l]);
      }
      for (int i = 0; i < static_cast<int>(n_max); ++i)
        step(LaneInputs(i, n_, inv_n_, dt, x0, dx, v0, dv), anchored(k, i));
    }
    constexpr R kBlowUp = R(1e30);
#pragma omp simd
    for (int l = 0; l < W; ++l) {
      R bad = 0;  // 1 if some state is not finite or huge; selects of reals keep the loop vectorized
      for (int j = 0; j < S; ++j) bad = std::fabs(y_[j][l]) < kBlowUp ? bad : R(1);
      failed_[l] += bad;
      for (int j = 0; j < S; ++j) y_[j][l] = bad > R(0) ? R(0) : y_[j][l];
      chain_near_[l] = bad > R(0) ? R(0) : chain_near_[l];
    }
  }

  /// Whether sub-step i of interval k takes the exact power of the state at its start: sub-steps K, 2K, ... of
  /// every interval and sub-step 0 of every K-th interval (K = kChainSteps). The anchors a lane meets depend on
  /// the record and its own sub-step counts, never on its neighbours.
  static bool anchored(std::size_t k, int i) {
    return i % kChainSteps == 0 && (i > 0 || k % kChainSteps == 0);
  }

  /// Each lane's stiff sub-step count on intervals up to dt long, ceil(dt·λ_l / kLawStiffStep), and their maximum;
  /// a lane that would need more than kMaxSubsteps is masked and takes the record's count (stiff 0). A record's
  /// intervals are mostly of one length up to rounding of its time stamps (relative 1e-12 or so): the counts
  /// are kept for every interval of [dt·(1 − 2·kStiffDtSlack), dt] (dt with the slack added) and recomputed
  /// only for one outside, about once per record instead of once per sample. Which counts a lane takes
  /// depends on its own λ and the record only.
  static constexpr double kStiffDtSlack = 1e-6;
  void stiff_substeps(double dt) {
    stiff_dt_ = dt;
    stiff_max_ = 0.0;
    for (int l = 0; l < W; ++l) {
      const double stiff = std::ceil(dt * lambda_[l] / kLawStiffStep);  // +inf for an unbounded estimate
      if (!(stiff <= kMaxSubsteps)) failed_[l] += R(1);             // too stiff: masked, integrated cheaply
      stiff_[l] = failed_[l] > R(0) ? R(0) : static_cast<R>(stiff);
      stiff_max_ = std::max(stiff_max_, static_cast<double>(stiff_[l]));
    }
  }

  /// Inputs of one sub-step, the same for every lane: step size h and (x, v) at the step's start (a),
  /// middle (m) and end (b).
  struct SharedInputs {
    R h_, xa_, va_, xm_, vm_, xb_, vb_;
    [[nodiscard]] R h(int) const { return h_; }
    [[nodiscard]] R xa(int) const { return xa_; }
    [[nodiscard]] R va(int) const { return va_; }
    [[nodiscard]] R xm(int) const { return xm_; }
    [[nodiscard]] R vm(int) const { return vm_; }
    [[nodiscard]] R xb(int) const { return xb_; }
    [[nodiscard]] R vb(int) const { return vb_; }
    static constexpr bool active(int) { return true; }
  };

  /// Inputs of sub-step i of a block whose lanes take n[l] sub-steps each, computed lane by lane with the
  /// arithmetic of SharedInputs; a lane past its own n[l] sub-steps is inactive and keeps its state.
  struct LaneInputs {
    LaneInputs(int i, const R* n, const R* inv_n, double dt, double x0, double dx, double v0, double dv)
        : i_(static_cast<R>(i)), n_(n) {
      const R ir = static_cast<R>(i), dtr = static_cast<R>(dt);
      const R x0r = static_cast<R>(x0), dxr = static_cast<R>(dx), v0r = static_cast<R>(v0), dvr = static_cast<R>(dv);
#pragma omp simd
      for (int l = 0; l < W; ++l) {  // multiplications by 1/n instead of four vector divisions per lane and
        const R inv = inv_n[l];       // sub-step: divisions are slow and sit on the stage loop's path
        const R a = ir * inv, m = (ir + R(0.5)) * inv, b = (ir + R(1)) * inv;
        h_[l] = dtr * inv;
        xa_[l] = x0r + a * dxr, va_[l] = v0r + a * dvr;
        xm_[l] = x0r + m * dxr, vm_[l] = v0r + m * dvr;
        xb_[l] = x0r + b * dxr, vb_[l] = v0r + b * dvr;
      }
    }
    [[nodiscard]] R h(int l) const { return h_[l]; }
    [[nodiscard]] R xa(int l) const { return xa_[l]; }
    [[nodiscard]] R va(int l) const { return va_[l]; }
    [[nodiscard]] R xm(int l) const { return xm_[l]; }
    [[nodiscard]] R vm(int l) const { return vm_[l]; }
    [[nodiscard]] R xb(int l) const { return xb_[l]; }
    [[nodiscard]] R vb(int l) const { return vb_[l]; }
    [[nodiscard]] bool active(int l) const { return i_ < n_[l]; }

    R i_;
    const R* n_;
    alignas(64) R h_[W], xa_[W], va_[W], xm_[W], vm_[W], xb_[W], vb_[W];
  };

  /// One RK4 sub-step of every (active) lane with inputs `in` (SharedInputs or LaneInputs).
  /// One lane loop per stage: the lanes of a stage are independent, so the vector calls of neighbouring
  /// lane groups (log, exp of |z|^n) overlap in the CPU instead of waiting on the previous stage's result.
  template <class Inputs>
  void step(const Inputs& in, bool anchor) {
    if constexpr (kPower) {
      start_power(in, anchor);
#pragma omp simd
      for (int l = 0; l < W; ++l) {
        // ±inf at s0 = 0: ε is then not finite and the next power exact (0 at s0 = ±inf: that lane fails anyway)
        inv0_[l] = R(1) / y_[Law::kPowerState][l];
        Law::rhs(p_, l, ctx_, in.xa(l), in.va(l), State{&y_[0][l]}, power0_[l], State{&k_[0][0][l]});
      }
    } else {
#pragma omp simd
      for (int l = 0; l < W; ++l) Law::rhs(p_, l, ctx_, in.xa(l), in.va(l), State{&y_[0][l]}, State{&k_[0][0][l]});
    }
    stage<false>(in, 0.5, 0, 1);
    stage<false>(in, 0.5, 1, 2);
    stage<true>(in, 1.0, 2, 3);
#pragma omp simd
    for (int l = 0; l < W; ++l) {
      const State y{&y_[0][l]}, k1{&k_[0][0][l]}, k2{&k_[1][0][l]}, k3{&k_[2][0][l]}, k4{&k_[3][0][l]};
      const bool active = in.active(l);
      for (int j = 0; j < S; ++j) {
        const R next = y[j] + (in.h(l) / R(6)) * (k1[j] + R(2) * k2[j] + R(2) * k3[j] + k4[j]);
        y[j] = active ? next : y[j];
      }
      if constexpr (kPower) {  // the power at the next sub-step's start, chained: s = s0·(1 + ε) there
        // (ε from the increment: (s − s0)/s0 of the state as stored would follow its rounding, e·2^−52 relative
        // per series, but is slower; docs/performance.md)
        constexpr int ps = Law::kPowerState;
        const R eps = (in.h(l) / R(6)) * (k1[ps] + R(2) * k2[ps] + R(2) * k3[ps] + k4[ps]) * inv0_[l];
        const R chained = power0_[l] * series(eps, l);
        const R near = static_cast<R>(std::fabs(eps) <= R(kSeriesRadius));
        power0_[l] = active ? chained : power0_[l];
        chain_near_[l] = active ? near : chain_near_[l];
      }
    }
  }

  /// power0_ at a sub-step's start: the chained power where the lane's last series was near and the sub-step is
  /// not an anchor (or the lane is past its own sub-steps, and keeps its state), else exact; the loop with the
  /// vector log and exp runs only if some lane needs it (kSeriesTerms).
  template <class Inputs>
  void start_power(const Inputs& in, bool anchor) {
    // (over every lane of a chunk: skipping inactive ones is slower; docs/performance.md)
    if (!exact_powers(y_[Law::kPowerState], anchor ? nullptr : chain_near_)) return;
#pragma omp simd
    for (int l = 0; l < W; ++l) {
      const bool exact = chain_near_[l] == R(0) || (anchor && in.active(l));
      power0_[l] = exact ? exact_[l] : power0_[l];
    }
  }

  /// Lanes per chunk of exact_powers(): the narrowest block (kLanes), so a chunk's loop is a whole block's loop
  /// of that width and gives its lanes the same bits (Float32Lanes.SameBitsForAnyThreadCountBatchSplitAndBlockWidth).
  static constexpr int kExactChunk = std::min(W, kLanes);
  static_assert(W % kExactChunk == 0);

  /// exact_[l] = |s[l]|^e (vector log and exp) for the lanes of every kExactChunk-lane chunk in which some lane that
  /// has not failed has near[l] == 0 (every chunk when near is null); false when no chunk needed them. A failed lane's
  /// forces are discarded (NaN), and its state, reset to 0 after each blow-up, leaves the series' radius at every
  /// step: computed for the whole block, exact powers for such lanes and for stiff ones (whose state moves fast
  /// relative to itself) were a quarter to half of a Spencer fit's time (docs/performance.md). When every chunk
  /// needs them, one loop over the block keeps the vector calls of its chunks overlapping.
  bool exact_powers(const R* s, const R* near) {
    constexpr int kChunks = W / kExactChunk;
    bool needed[kChunks];
    int count = kChunks;
    if (near) {
      // counted_near_: 1 where near or failed. One reduction over the block first, because most stages need no
      // exact power, then one per chunk (min over reals: an integer count was scalar in some clones).
      R all_near = 1;
#pragma omp simd reduction(min : all_near)
      for (int l = 0; l < W; ++l) {
        counted_near_[l] = failed_[l] > R(0) ? R(1) : near[l];
        all_near = std::min(all_near, counted_near_[l]);
      }
      if (all_near > R(0)) return false;
      count = 0;
      for (int c = 0; c < kChunks; ++c) {
        R chunk_near = 1;
        const int first = c * kExactChunk;
#pragma omp simd reduction(min : chunk_near)
        for (int l = first; l < first + kExactChunk; ++l) chunk_near = std::min(chunk_near, counted_near_[l]);
        needed[c] = !(chunk_near > R(0));
        count += needed[c];
      }
    }
    const R* e = p_.p[Law::kPowerExponentRow];
    if (count == kChunks) {  // (also when near is null; needed[] is then not read)
#pragma omp simd
      for (int l = 0; l < W; ++l) exact_[l] = abs_pow(s[l], e[l]);
      return true;
    }
    for (int c = 0; c < kChunks; ++c) {
      if (!needed[c]) continue;
      const int first = c * kExactChunk;
#pragma omp simd
      for (int l = first; l < first + kExactChunk; ++l) exact_[l] = abs_pow(s[l], e[l]);
    }
    return count > 0;
  }

  /// RK4 stage: slopes k[to] at y + fraction·h·k[from], inputs at the step's middle (or end: kEnd).
  template <bool kEnd, class Inputs>
  void stage(const Inputs& in, double fraction, int from, int to) {
    if constexpr (kPower) {
      power_stage<kEnd>(in, fraction, from, to);
    } else {
#pragma omp simd
      for (int l = 0; l < W; ++l) {
        const State y{&y_[0][l]}, t{&t_[0][l]}, kf{&k_[from][0][l]};
        const R a = static_cast<R>(fraction) * in.h(l);
        for (int j = 0; j < S; ++j) t[j] = y[j] + a * kf[j];
        Law::rhs(p_, l, ctx_, kEnd ? in.xb(l) : in.xm(l), kEnd ? in.vb(l) : in.vm(l), t, State{&k_[to][0][l]});
      }
    }
  }

  /// 1 + C(e, 1)·ε + … + C(e, m)·ε^m (m = kSeriesTerms, 8 or 6) of lane l by Estrin's scheme: pairs, then pairs
  /// of pairs, four dependent multiply-adds deep instead of Horner's eight, because the series sits on the stage
  /// loop's critical path.
  [[nodiscard]] R series(R eps, int l) const {
    static_assert(kSeriesTerms == 8 || kSeriesTerms == 6, "series() is written out for 8 and 6 terms");
    const auto c = [&](int i) { return series_[i][l]; };  // C(e, i + 1)
    const R e2 = eps * eps, e4 = e2 * e2;
    const R q01 = c(0) + c(1) * eps, q23 = c(2) + c(3) * eps, q45 = c(4) + c(5) * eps;
    const R q03 = q01 + q23 * e2;
    if constexpr (kSeriesTerms == 6) return R(1) + eps * (q03 + q45 * e4);
    const R q67 = c(6) + c(7) * eps;
    const R q47 = q45 + q67 * e2;
    return R(1) + eps * (q03 + q47 * e4);
  }

  /// stage() of a law with a power state: |t|^e from the series where |ε| ≤ kSeriesRadius, else exact; the loop
  /// with the vector log and exp runs only if some lane needs them (kSeriesTerms).
  template <bool kEnd, class Inputs>
  void power_stage(const Inputs& in, double fraction, int from, int to) {
    constexpr int ps = Law::kPowerState;
#pragma omp simd
    for (int l = 0; l < W; ++l) {
      const R a = static_cast<R>(fraction) * in.h(l);
      for (int j = 0; j < S; ++j) t_[j][l] = y_[j][l] + a * k_[from][j][l];
      const R eps = a * k_[from][ps][l] * inv0_[l];  // t[ps] = s0·(1 + ε)
      power_[l] = power0_[l] * series(eps, l);  // replaced below where the lane is not near (no select here: GCC sinks the
      near_[l] = static_cast<R>(std::fabs(eps) <= R(kSeriesRadius));  // product into its branch and stops)
    }
    if (exact_powers(t_[ps], near_)) {
      // Two loops: in one, GCC sinks the call into the select's branch and leaves the loop scalar.
#pragma omp simd
      for (int l = 0; l < W; ++l) power_[l] = near_[l] > R(0) ? power_[l] : exact_[l];
    }
#pragma omp simd
    for (int l = 0; l < W; ++l)
      Law::rhs(p_, l, ctx_, kEnd ? in.xb(l) : in.xm(l), kEnd ? in.vb(l) : in.vm(l), State{&t_[0][l]}, power_[l],
               State{&k_[to][0][l]});
  }

  LawLanes<Law, W> p_;
  const Signals& data_;
  typename Law::Context ctx_;
  alignas(64) R y_[S][W] = {};
  alignas(64) R t_[S][W] = {};      // RK4 stage input
  alignas(64) R k_[4][S][W] = {};   // RK4 stage slopes
  alignas(64) R failed_[W] = {};    // > 0 once a lane has blown up or was too stiff
  alignas(64) double lambda_[W] = {};    // Law::stiffness of each lane [1/s] (0: the record's rule alone)
  alignas(64) R stiff_[W] = {};          // stiff sub-steps of each lane on an interval of length stiff_dt_
  double stiff_dt_ = -1.0;
  double stiff_max_ = 0.0;               // max of stiff_
  alignas(64) R n_[W] = {};              // sub-steps of each lane on the current interval (a whole number)
  alignas(64) R inv_n_[W] = {};          // 1 / n_
  // Powers of a state (kPower only): |s0|^e and 1/s0 at the sub-step's start, the stage's |t|^e, C(e, i)
  alignas(64) R power0_[W] = {};      // after a sub-step: the chained power at the next one's start
  alignas(64) R chain_near_[W] = {};  // 1 where that chained power came from a series with |ε| ≤ kSeriesRadius
  alignas(64) R inv0_[W] = {};
  alignas(64) R power_[W] = {};
  alignas(64) R near_[W] = {};   // 1 where the stage's power came from the series
  alignas(64) R exact_[W] = {};  // exact powers (a sub-step's start or a stage)
  alignas(64) R counted_near_[W] = {};  // near, or 1 for a failed lane (exact_powers)
  alignas(64) R series_[kSeriesTerms][W] = {};
  mutable bool failed_flags_[W] = {};  // failed_ > 0, filled by failed()
};

template <class Law>
using OdeModel = KernelModel<Law, OdeKernel>;

}  // namespace dampbench
