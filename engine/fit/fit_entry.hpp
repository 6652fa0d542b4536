#pragma once
// A fit from its spec to its result, and the one place that chooses how: with `laws = auto` the law choice and the
// joint fit of the chosen laws (law_selection.hpp), otherwise the fit itself, started from each record's own fit when
// the spec asks (`--start per-file`, record_start.hpp); then the held-out predictions the spec asks for
// (held_out.hpp). The command line, the Python module and the system benchmark call it and only print or write what
// it returns.
#include <functional>
#include <optional>
#include <string>

#include "engine/fit/held_out.hpp"
#include "engine/fit/law_selection.hpp"
#include "engine/fit/prepared_fit.hpp"

namespace dampbench {

/// A finished fit, before anything prints it.
struct FitResult {
  FitSpec spec;                     ///< as asked; with laws = auto, the laws chosen
  PreparedFit prepared;             ///< the model (with laws = auto: the chosen one), plan and records
  FitOutcome outcome;
  LawSelection selection;           ///< with laws = auto
  HeldOutPlan plan;                 ///< the held-out spec checked and its records loaded: held_out points into them
  std::optional<HeldOut> held_out;  ///< with predictions or folds asked for
};

/// Prepares the fit, checks the held-out spec (bad input before any fit runs), fits and predicts. `progress` is told
/// one line per step of a law choice, a per-file start or a fold. InputError or DataError for bad input.
FitResult fit_and_predict(const FitSpec& spec, const HeldOutSpec& held_out,
                          const std::function<void(const std::string&)>& progress);

}  // namespace dampbench
