#pragma once
// The model file (model_file.hpp) of a finished fit, for `fit --save-model`: apart from the file's format, which
// the fit itself reads for a start (prepared_fit.cpp), so that neither unit includes the other.
#include <string>

#include "engine/fit/model_file.hpp"
#include "engine/fit/prepared_fit.hpp"

namespace dampbench {

/// The model file of a finished fit: its best run's coefficients, each record's metric there (evaluated on that
/// record alone) and operating variables; the vector level is the one the kernels run at.
ModelFile model_file_of_fit(const FitSpec& spec, const PreparedFit& prepared, const FitOutcome& fit,
                            const std::string& dampbench_version);

}  // namespace dampbench
