#pragma once
// The throughput workload of `dampbench bench` (engine/cli/bench_command.cpp) and of the Google Benchmark
// suite (bench/bench_models.cpp); docs/performance.md describes it:
//   record      x = X·sin(2π f t) sampled at fs, exact v and a, X = 0.02 m (0.02 rad for the rotary crfd
//               models); measured force = the model's own force at the centre of its bench box plus 1 %,
//               so that the metric sums are non-trivial
//   candidates  uniform (keyed stream) in the central half of the model's bench box
//   bench box   the model's default bounds, except where most of that box is too stiff for the explicit
//               RK4 of the ODE kernels: in the central half of the default box every mrd.spencer candidate
//               and half of the mrd.bouc_wen candidates blow up and are masked (+inf), so a benchmark there
//               would time the masking and resets, not the model. Those models get ±20 % around a
//               representative point (bench_reference_point); the bench reports the masked share.
#include <cstdint>
#include <optional>
#include <string_view>

#include "engine/model/batch.hpp"
#include "engine/model/bounds.hpp"
#include "engine/model/model.hpp"
#include "engine/record/signals.hpp"

namespace dampbench {

/// "name=value,..." of the representative point of a model whose default box is mostly unstable for the
/// explicit integrator, or nullopt (the bench box is then the default box).
std::optional<std::string_view> bench_reference_point(const Model& model);

/// The box the bench candidates come from (see above).
Bounds bench_box(const Model& model);

/// `count` candidates uniform in the central half of bench_box(model), from the stream keyed by `seed`
/// and the model id (the same candidates on every run and machine).
CandidateBatch bench_candidates(const Model& model, int count, std::uint64_t seed);

/// The bench record: `samples` samples of X·sin(2π·freq_hz·t) at fs_hz, prepared for evaluation.
Signals bench_record(const Model& model, int samples, double freq_hz, double fs_hz);

}  // namespace dampbench
