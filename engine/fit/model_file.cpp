#include "engine/fit/model_file.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/common/text_file.hpp"
#include "engine/fit/json_keys.hpp"
#include "engine/evaluation/batch_evaluator.hpp"
#include "engine/kernels/isa.hpp"

namespace dampbench {

using Json = nlohmann::ordered_json;

nlohmann::ordered_json operating_json(const Signals& record) {
  Json j = Json::object();
  for (const auto& [name, value] : record.law_variables) {
    const auto source = record.law_variable_source.find(name);
    j[name] = {{"value", value}, {"source", source != record.law_variable_source.end() ? source->second : "dataset"}};
  }
  return j;
}

namespace {

/// JSON text with every floating-point number as %.17g (nlohmann writes the shortest form that reads back, which
/// is the same number, but the file promises 17 digits to readers in other languages too); non-finite as null.
void write_json(std::ostringstream& out, const Json& j, int indent) {
  const std::string pad(static_cast<std::size_t>(indent + 2), ' '), close(static_cast<std::size_t>(indent), ' ');
  if (j.is_number_float()) {
    const double v = j.get<double>();
    out << (std::isfinite(v) ? fmt::format("{:.17g}", v) : "null");
  } else if (j.is_object() && !j.empty()) {
    out << "{\n";
    bool first = true;
    for (const auto& [key, value] : j.items()) {
      out << (first ? "" : ",\n") << pad << Json(key).dump() << ": ";
      write_json(out, value, indent + 2);
      first = false;
    }
    out << "\n" << close << "}";
  } else if (j.is_array() && !j.empty()) {
    out << "[\n";
    for (std::size_t i = 0; i < j.size(); ++i) {
      out << (i ? ",\n" : "") << pad;
      write_json(out, j[i], indent + 2);
    }
    out << "\n" << close << "]";
  } else {
    out << j.dump();
  }
}

}  // namespace

std::string exact_json_text(const nlohmann::ordered_json& j) {
  std::ostringstream out;
  write_json(out, j, 0);
  out << "\n";
  return out.str();
}

std::string model_file_text(const ModelFile& f) {
  Json j;
  j["format"] = kModelFileFormat;
  j["format_version"] = kModelFileVersion;
  j["dampbench_version"] = f.dampbench_version;
  j["vector_level"] = f.vector_level;
  j["model"] = {{"id", f.model_id}, {"base", f.choice.model}, {"laws", f.choice.laws}, {"fixture", f.choice.fixture}};
  Json coefficients = Json::object();
  for (const auto& [name, value] : f.coefficients) coefficients[name] = value;
  j["coefficients"] = coefficients;
  j["metric"] = {{"name", f.metric}, {"fitted_value", f.fitted_value}};
  Json records = Json::array();
  for (const ModelFileRecord& r : f.records)
    records.push_back({{"name", r.name},
                       {"path", r.path},
                       {"metric_value", r.metric_value},
                       {"operating", r.operating},
                       {"motion", {{"displacement_ptp_m", r.displacement_ptp_m},
                                   {"velocity_max_abs_m_s", r.velocity_max_abs_m_s}}}});
  j["records"] = records;
  return exact_json_text(j);
}

void write_model_file(const std::string& path, const ModelFile& file) { write_text_file(path, model_file_text(file)); }

namespace {

std::vector<ModelFileRecord> parse_records(const Keys& top) {
  const Json* list = top.find("records", true);
  if (!list->is_array()) top.fail("records", fmt::format("expected an array, got {}", list->dump()));
  std::vector<ModelFileRecord> records;
  for (std::size_t i = 0; i < list->size(); ++i) {
    const std::string where = fmt::format("records[{}]", i);
    if (!(*list)[i].is_object()) top.fail(where, "expected an object");
    const Keys r{top.source, (*list)[i], where};
    ModelFileRecord rec{r.string("name"), r.string("path"), r.number("metric_value"), Json::object()};
    const Keys operating = r.object_at("operating");
    for (const auto& [name, entry] : operating.object.items()) {
      if (!entry.is_object()) operating.fail(name, "expected an object {\"value\": number, \"source\": string}");
      const Keys e{top.source, entry, operating.key_path(name)};
      rec.operating[name] = {{"value", e.number("value")}, {"source", e.string("source")}};
    }
    if (r.find("motion", false)) {  // optional: files written before it existed have none
      const Keys motion = r.object_at("motion");
      rec.displacement_ptp_m = motion.number("displacement_ptp_m");
      rec.velocity_max_abs_m_s = motion.number("velocity_max_abs_m_s");
    }
    records.push_back(std::move(rec));
  }
  return records;
}

}  // namespace

ModelFile parse_model_file(const std::string& text, const std::string& source) {
  const Json j = parse_json_object(text, source);
  const Keys top{source, j, ""};
  check_format(top, kModelFileFormat, kModelFileVersion);
  ModelFile f;
  f.dampbench_version = top.string("dampbench_version");
  f.vector_level = top.string("vector_level");
  const Keys model = top.object_at("model");
  f.model_id = model.string("id", false);
  f.choice.model = model.string("base", false);
  f.choice.laws = model.string("laws", false);
  f.choice.fixture = model.string("fixture", false);
  if (f.choice.model.empty() == f.choice.fixture.empty())
    model.fail("base", "give exactly one of model.base (a model id) and model.fixture (a law fixture)");
  const Keys coefficients = top.object_at("coefficients");
  for (const auto& [name, value] : coefficients.object.items()) {
    (void)value;
    f.coefficients.emplace_back(name, coefficients.number(name));
  }
  const Keys metric = top.object_at("metric");
  f.metric = metric.string("name");
  f.fitted_value = metric.number("fitted_value");
  f.records = parse_records(top);
  return f;
}

namespace {

/// The file's coefficients in the model's parameter order: each named once, every parameter given.
std::vector<double> coefficients_in_order(const ModelFile& f, const Model& model, const std::string& source) {
  const auto params = model.parameters();
  std::string expected;
  for (const auto& p : params) expected += (expected.empty() ? "" : ", ") + p.name;
  std::vector<double> values(static_cast<std::size_t>(model.dim()), std::numeric_limits<double>::quiet_NaN());
  std::vector<bool> given(values.size(), false);
  for (const auto& [name, value] : f.coefficients) {
    const std::string& wanted = name;  // clang before 16 cannot capture a structured binding in a lambda
    const auto it = std::find_if(params.begin(), params.end(), [&](const auto& p) { return p.name == wanted; });
    if (it == params.end())
      throw InputError(fmt::format("{}: key 'coefficients.{}': not a coefficient of {} (its {}: {})", source, name,
                                   model.id(), params.size(), expected));
    const auto i = static_cast<std::size_t>(it - params.begin());
    if (!std::isfinite(value))
      throw InputError(fmt::format("{}: key 'coefficients.{}': expected a finite number", source, name));
    values[i] = value;
    given[i] = true;
  }
  for (std::size_t i = 0; i < values.size(); ++i)
    if (!given[i])
      throw InputError(fmt::format("{}: key 'coefficients.{}': missing ({} has {} coefficients: {}; the file gives {})",
                                   source, params[i].name, model.id(), params.size(), expected, f.coefficients.size()));
  return values;
}

}  // namespace

LoadedModel load_model_file(const std::string& path) {
  LoadedModel m;
  m.file = parse_model_file(read_model_file_text(path), path);
  ModelChoice choice = m.file.choice;
  choice.option_prefix = "model.";  // messages name the file's key model.laws
  ModelChoice base = choice;
  base.laws.clear();
  try {
    (void)resolve_model(base);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: key 'model.{}': {}", path, choice.fixture.empty() ? "base" : "fixture", e.what()));
  }
  try {
    m.model = resolve_model(choice);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: key 'model.laws': {}", path, e.what()));
  }
  m.params = coefficients_in_order(m.file, *m.model.model, path);
  return m;
}

FittedRange fitted_range_of(const LoadedModel& loaded) {
  std::vector<std::map<std::string, double>> fitted;
  for (const ModelFileRecord& r : loaded.file.records) {
    std::map<std::string, double>& variables = fitted.emplace_back();
    for (const auto& [name, entry] : r.operating.items()) variables[name] = entry.at("value").get<double>();
  }
  return FittedRange(*loaded.model.model, fitted);
}

}  // namespace dampbench
