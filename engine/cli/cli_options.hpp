#pragma once
// What several commands share: the loader options of their records, the output formats they accept, and numbers
// in JSON output.
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/fit/model_file.hpp"
#include "engine/fit/resolve_model.hpp"
#include "engine/model/model.hpp"
#include "engine/record/record_options.hpp"

namespace CLI {
class App;
}

namespace dampbench::cli {

/// Declares the loader options (--units, --columns, --transform, --average-cycles, --conditions, --set) on a
/// subcommand.
void add_data_options(CLI::App* cmd, RecordOptions& data);

/// A model named by the options --model (or --fixture), --laws and --bounds: messages name the options.
ModelChoice command_line_model(const std::string& model, const std::string& laws = "", const std::string& bounds = "",
                               const std::string& fixture = "");

/// Every parameter of the model from "name=value,..." (SI); all required unless `defaults` gives them.
std::vector<double> parse_params(const Model& model, const std::string& text, const std::vector<double>& defaults = {});

/// A model with its parameters as `simulate` and `structure` take it: --model-file, or --model (or --fixture) with
/// --laws and --params. InputError "<command>: ..." for both or neither.
struct ModelByName {
  std::string model_file, model, fixture, laws, params;
};
LoadedModel load_named_model(const ModelByName& names, const std::string& command);
/// Declares --model-file, --model, --fixture, --laws and --params into `names` (inverse, structure, export).
void add_model_by_name_options(CLI::App* cmd, ModelByName& names);

/// A commanded variable and its range, from "I=0:1" (inverse --range, structure --command). InputError naming
/// `option` for another form; the order of LOW and HIGH is checked by whoever uses them.
struct CommandRange {
  std::string variable;
  double low = 0, high = 0;
};
CommandRange parse_command_range(const std::string& text, std::string_view option);

/// InputError unless `format` is md or json.
void check_format(const std::string& format);

/// Before the work that ends in writing `path`: InputError "OPTION: the folder of 'PATH' does not exist" when it
/// does not (nothing when `path` is empty), so that no finished result is lost to a mistyped folder.
void check_output_folder(std::string_view option, const std::string& path);

/// A JSON number that stays valid JSON: non-finite values become null.
nlohmann::ordered_json json_number(double v);

}  // namespace dampbench::cli
