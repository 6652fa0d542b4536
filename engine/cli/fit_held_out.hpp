#pragma once
// `fit`'s held-out evaluation on the command line (--predict, --folds, --reference): its options, and its tables
// in Markdown and JSON. The evaluation itself is engine/fit/held_out's.
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/common/table.hpp"
#include "engine/fit/held_out.hpp"

namespace CLI {
class App;
}

namespace dampbench::cli {

void add_held_out_options(CLI::App* cmd, HeldOutSpec& spec);

/// The folds (when any fit predicts), each record's metric beside its per-file fit, and the means by role.
/// `rule` names the folds in the titles; `base_id` the model of the per-file fits.
std::vector<Table> held_out_tables(const HeldOut& held_out, std::string_view rule, std::string_view base_id);

/// {metric, reference, folds: [{name, fit, predict, fit_value, converged, verdict, best_params}], records: [{role,
/// fold, record, metric, per_file, per_file_verdict, ratio}], summary: {fitted, held_out}: {count, mean,
/// mean_per_file, ratio_of_means, worst_ratio, worst_record}}; absent numbers are null. `model` is the fitted one.
nlohmann::ordered_json held_out_json(const HeldOut& held_out, const Model& model);

}  // namespace dampbench::cli
