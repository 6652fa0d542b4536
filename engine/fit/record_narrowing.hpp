#pragma once
// A law model's box by the mfm paper's bound narrowing (mfm §5.1, the identification behind its Table 3): the base
// model is fitted to each record alone within a box, the box is reset to the [min, max] of those fits over the
// records, and so on for `rounds` rounds (optimizers/narrowing/narrowing.hpp). The law model then searches the box
// those per-record ranges give its coefficients, starting from the laws fitted to the last round's per-record fits.
//
// From a parameter's narrowed range [lo, hi] (width w = hi − lo) over records whose law variable spans [v0, v1]:
//   - a shared parameter (no law) searches [lo, hi];
//   - poly(VAR,1), p = a + b·v: |b| ≤ w / (v1 − v0), the steepest line that stays inside the range between v0 and
//     v1, and a = p(vr) − b·vr ∈ [lo − |b|max·|vr|, hi + |b|max·|vr|] at vr, the end nearer to v = 0 (with the
//     currents from 0 A, as the mfm paper's, a ∈ [lo, hi]). The box holds every such line that stays in the range;
//     it also holds lines that leave it between the records, which the search may find worse, not better;
//   - poly(VAR,0) as a shared parameter; a fixed parameter has no coefficient. Other laws have no box from a range
//     and are refused (InputError naming the parameter and its law) before anything is fitted.
// The starting box is the base model's box for these records ("default"), or the paper's [−1e8, 1e8] ("wide").
#include <string>
#include <vector>

#include "engine/fit/record_fit_cache.hpp"
#include "engine/fit/resolve_model.hpp"
#include "optimizers/narrowing/narrowing.hpp"

namespace dampbench {

struct NarrowingSpec {
  int rounds = 3;
  std::string from = "default";  ///< "default" (the base model's box for the records) or "wide" ([−1e8, 1e8])
};

struct NarrowedStart {
  Bounds box;                  ///< the law model's box, in its coefficient order
  std::vector<double> start;   ///< the laws fitted to the last round's per-record fits (empty: every record failed)
  NarrowingResult narrowing;   ///< the rounds (the base model's parameters, as per_record_model orders them)
  PreFitEffort effort;         ///< the per-record fits of every round
  std::string summary;         ///< one line: rounds, failed records, the final ranges' widths
};

/// Checks that every law of `choice` has a box from a range (see above); InputError naming the first that has not.
void check_narrowable_laws(const ModelChoice& choice);

/// The narrowing over `records` (each fitted alone by `inner`, `settings.runs` runs, keyed from settings.task_key)
/// and the law model's box and start from it. InputError: a law without a box, spec.rounds < 1, an unknown
/// spec.from, a law variable that takes one value over the records (no slope to bound).
NarrowedStart narrowed_start(const ModelChoice& choice, const Model& law_model, const std::vector<const Signals*>& records,
                             const OptimizerSpec& inner, const IdentificationSettings& settings, const NarrowingSpec& spec);

}  // namespace dampbench
