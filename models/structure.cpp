// System models: a structure driven by a force, its displacement out (docs/models.md "System models").
//   sys.bouc_wen   Noël & Schoukens, hysteretic benchmark eqs. 1–3: m·ÿ + c·ẏ + k·y + z = u with Bouc–Wen z
// The structure is stepped by the benchmark's Newmark scheme (engine/kernels/newmark.hpp) on the input
// reconstructed at kSubsteps× the record's rate: band-limited (FFT) for a periodic input, a cubic spline otherwise.
// The output is the displacement at the record's instants, not passed through the benchmark's decimation filter: on
// the tool's own generated data the filter changes y by less than the Newmark scheme's own error (docs/models.md).
#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/kernels/cvode_integrator.hpp"
#include "engine/kernels/lane_kernel.hpp"
#include "engine/kernels/newmark.hpp"
#include "engine/record/bandlimited.hpp"
#include "models/registry.hpp"

namespace dampbench::sys {
namespace {

/// Newmark steps per record sample: the benchmark integrates at 15 kHz, 20× its 750 Hz rate.
constexpr int kSubsteps = 20;
/// A periodic input is simulated from rest over this many periods and scored on the last, by when the free
/// response of a lightly damped structure (the benchmark: ζ = 1.1 %, f₀ = 35.6 Hz, so e^(−ζω₀t) = 1e−24 after one
/// 10.9 s period) has died out.
constexpr int kPeriodicPeriods = 3;
/// Candidates per lane block.
constexpr int kBlock = kLanes;

const ModelInfo& bouc_wen_info() {
  static const ModelInfo i{
      "sys.bouc_wen",
      "Noel & Schoukens hysteretic benchmark eqs. 1-3",
      "m*y'' + c*y' + k*y + z = u;  z' = alpha*y' - beta_gamma*|y'|*|z|^(nu-1)*z - beta_delta*y'*|z|^nu",
      {{"m", "kg", 0.4, 10, "kg"},
       {"c", "N*s/m", 2, 50, "N*s/m"},
       {"k", "N/m", 1e4, 2.5e5, "N/m"},
       {"alpha", "N/m", 1e4, 2.5e5, "N/m"},
       {"beta_gamma", "N^(1-nu)/m", 160, 4000, "N^(1-nu)/m"},
       {"beta_delta", "N^(1-nu)/m", -5500, -220, "N^(1-nu)/m"},
       {"nu", "-", 0.2, 5, "-"}}};
  return i;
}

HystereticStructure structure_of(std::span<const double> p) { return {p[0], p[1], p[2], p[3], p[4], p[5], p[6]}; }

/// The input at the integrator's rate, and which integrator steps give the record's samples.
struct FineInput {
  std::vector<double> u_N;     ///< kSubsteps samples per record interval
  double h_s = 0;              ///< integrator step
  std::size_t steps = 0;       ///< integrator steps after the initial state
  std::size_t first_output = 0;///< integrator step of the record's sample 0
  bool periodic = false;       ///< u_N is one period, repeated

  [[nodiscard]] double input(std::size_t step) const { return u_N[periodic ? step % u_N.size() : step]; }
};

FineInput fine_input(const Signals& d) {
  FineInput in;
  const std::size_t n = d.size();
  in.h_s = (d.t_s.back() - d.t_s.front()) / static_cast<double>(n - 1) / kSubsteps;
  in.periodic = d.periodic_input;
  if (in.periodic) {
    in.u_N = upsample_periodic(d.u_N, kSubsteps);
    in.first_output = (kPeriodicPeriods - 1) * in.u_N.size();
    in.steps = in.first_output + (n - 1) * kSubsteps;
  } else {
    in.u_N = upsample_spline(d.u_N, kSubsteps);
    in.steps = (n - 1) * kSubsteps;
  }
  return in;
}

/// Runs `count` candidates from rest through the whole input; out(k, l, y) receives lane l's displacement at the
/// record's sample k, k = 0, 1, ... in order. failed[l] is set for a lane whose state stops being finite (its
/// later outputs are NaN).
template <class Out>
void run_lanes(const HystereticStructure* lanes, int count, const FineInput& in, bool* failed, Out&& out) {
  std::vector<StructureState> state(static_cast<std::size_t>(count));
  for (int l = 0; l < count; ++l) {
    state[l] = structure_at_rest(lanes[l], in.input(0));
    failed[l] = false;
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (in.first_output == 0)
    for (int l = 0; l < count; ++l) out(0, l, state[l].y_m);
  for (std::size_t step = 1; step <= in.steps; ++step) {
    const double u = in.input(step);
    for (int l = 0; l < count; ++l)
      if (!failed[l]) {
        newmark_step(lanes[l], in.h_s, u, state[l]);
        failed[l] = !std::isfinite(state[l].y_m) || !std::isfinite(state[l].z_N);
      }
    if (step >= in.first_output && (step - in.first_output) % kSubsteps == 0) {
      const std::size_t k = (step - in.first_output) / kSubsteps;
      for (int l = 0; l < count; ++l) out(k, l, failed[l] ? nan : state[l].y_m);
    }
  }
}

class BoucWenSystem final : public Model {
 public:
  [[nodiscard]] std::string_view id() const override { return bouc_wen_info().id; }
  [[nodiscard]] std::string_view citation() const override { return bouc_wen_info().citation; }
  [[nodiscard]] std::string_view law() const override { return bouc_wen_info().law; }
  [[nodiscard]] std::span<const ParameterInfo> parameters() const override { return bouc_wen_info().parameters; }
  [[nodiscard]] bool has_internal_states() const override { return true; }
  [[nodiscard]] bool is_system() const override { return true; }

  void evaluate_block(const CandidateBatch& batch, int first, int count, const Signals& data, SumSet wanted,
                      MetricSums* out) const override {
    HystereticStructure lanes[kBlock];
    for (int l = 0; l < count; ++l) lanes[l] = structure_of(batch.candidate(first + l));
    const FineInput in = fine_input(data);
    constexpr std::size_t kChunk = 16;
    alignas(64) double chunk[kChunk][kBlock] = {};
    LaneSums<kBlock> sums;
    bool failed[kBlock] = {};
    std::size_t filled = 0, chunk_start = 0;
    const auto flush = [&] {
      sums.add(chunk, filled, data.y_m.data() + chunk_start, data.w_trapz_s.data() + chunk_start, wanted);
      chunk_start += filled;
      filled = 0;
    };
    run_lanes(lanes, count, in, failed, [&](std::size_t, int l, double y) {
      chunk[filled][l] = y;
      if (l == count - 1 && ++filled == kChunk) flush();
    });
    if (filled > 0) flush();
    sums.store(out, count, wanted, failed);
  }

  [[nodiscard]] std::vector<double> simulate(std::span<const double> params, const Signals& data) const override {
    const HystereticStructure lane = structure_of(params);
    std::vector<double> y(data.size());
    bool failed = false;
    run_lanes(&lane, 1, fine_input(data), &failed, [&](std::size_t k, int, double value) { y[k] = value; });
    return y;
  }

  /// CVODE on the states (y, ẏ, z) with the input interpolated linearly between the integrator's input samples.
  [[nodiscard]] std::optional<std::vector<double>> simulate_reference(std::span<const double> params,
                                                                      const Signals& data) const override {
    const HystereticStructure p = structure_of(params);
    const FineInput in = fine_input(data);
    const auto u_at = [&](double t) {
      const double position = std::clamp(t / in.h_s, 0.0, static_cast<double>(in.steps));
      const auto step = std::min(static_cast<std::size_t>(position), in.steps - 1);
      const double w = position - static_cast<double>(step);
      return (1 - w) * in.input(step) + w * in.input(step + 1);
    };
    const OdeRhs rhs = [&](double t, std::span<const double> s, std::span<double> ds) {
      const double u = u_at(t);
      ds[0] = s[1];
      ds[1] = (u - p.c_N_s_m * s[1] - p.k_N_m * s[0] - s[2]) / p.m_kg;
      ds[2] = hysteretic_rate(p, s[1], s[2]).zdot;
    };
    std::vector<double> times(data.size());
    for (std::size_t k = 0; k < times.size(); ++k)
      times[k] = static_cast<double>(in.first_output + k * kSubsteps) * in.h_s;
    if (in.first_output > 0) times.insert(times.begin(), 0.0);
    auto states = integrate_cvode(rhs, {0.0, 0.0, 0.0}, times);
    if (in.first_output > 0) states.erase(states.begin());
    std::vector<double> y(data.size());
    for (std::size_t k = 0; k < y.size(); ++k) y[k] = states[k][0];
    return y;
  }
};

}  // namespace
}  // namespace dampbench::sys

namespace dampbench {

std::vector<std::unique_ptr<Model>> make_system_models() {
  std::vector<std::unique_ptr<Model>> models;
  models.push_back(std::make_unique<sys::BoucWenSystem>());
  return models;
}

}  // namespace dampbench
