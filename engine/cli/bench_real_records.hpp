#pragma once
// `dampbench bench --workload real-records` (docs/performance.md, "Real records"): the hysteretic MR models on
// two measured UTFSM records, 10mm1Hz1A (11 654 samples at 1 kHz) and 2mm5Hz1A (449 at 200 Hz), with the
// candidates a fit draws: uniform in the whole box, not its central half, so the stiff candidates of a real
// fit's first generations are in the rate.
//   boxes      "own": the model's record-scaled default box on that record (per-file fit, ungauged);
//              "gauged, both": the gauged law model (A = β + γ) in the box of a fit of both records at once
//              "gauged, hull": the same in the hull of the two records' own boxes (the law choice's clamp; a joint
//              fit's box until the stiffening rule, RecordBoundsRule::stiffening)
//   candidates 256 per box, from the stream keyed by the bench seed, the model id and the box
//   rates      candidate-samples per second on 2 threads (a fit's), best of `trials`; masked: the share of
//              candidates that blow up or are too stiff for the kernel (+inf)
#include "engine/cli/bench_rate.hpp"

namespace dampbench::cli {

int bench_real_records(const BenchOptions& options);

}  // namespace dampbench::cli
