#pragma once
// Reading a model file and the keys of its JSON with messages that name the file and the key: the model files' readers
// (model_file.cpp, lssvm_model_file.cpp).
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "engine/common/error.hpp"

namespace dampbench {

/// Reads keys of one JSON object, naming the file and the key's full path in every message.
struct Keys {
  const std::string& source;
  const nlohmann::ordered_json& object;
  std::string where;  ///< "model", "records[0]", ... ("" at the top)

  [[nodiscard]] std::string key_path(const std::string& key) const { return where.empty() ? key : where + "." + key; }
  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw InputError(fmt::format("{}: key '{}': {}", source, key_path(key), what));
  }
  [[nodiscard]] const nlohmann::ordered_json* find(const std::string& key, bool required) const {
    const auto it = object.find(key);
    if (it == object.end()) {
      if (required) fail(key, "missing");
      return nullptr;
    }
    return &*it;
  }
  [[nodiscard]] std::string string(const std::string& key, bool required = true) const {
    const nlohmann::ordered_json* v = find(key, required);
    if (!v) return "";
    if (!v->is_string()) fail(key, fmt::format("expected a string, got {}", v->dump()));
    return v->get<std::string>();
  }
  /// A number; null reads as NaN (a non-finite metric is written as null).
  [[nodiscard]] double number(const std::string& key) const {
    const nlohmann::ordered_json* v = find(key, true);
    if (v->is_null()) return std::numeric_limits<double>::quiet_NaN();
    if (!v->is_number()) fail(key, fmt::format("expected a number, got {}", v->dump()));
    return v->get<double>();
  }
  [[nodiscard]] Keys object_at(const std::string& key) const {
    const nlohmann::ordered_json* v = find(key, true);
    if (!v->is_object()) fail(key, fmt::format("expected an object, got {}", v->dump()));
    return {source, *v, key_path(key)};
  }
};

/// A model file's text; InputError "--model-file: cannot open '<path>'".
inline std::string read_model_file_text(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(fmt::format("--model-file: cannot open '{}'", path));
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// The JSON object of a file's text; InputError "<source>: not JSON (...)" or "...: expected a JSON object at the top".
inline nlohmann::ordered_json parse_json_object(const std::string& text, const std::string& source) {
  nlohmann::ordered_json j;
  try {
    j = nlohmann::ordered_json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(fmt::format("{}: not JSON ({})", source, e.what()));
  }
  if (!j.is_object()) throw InputError(fmt::format("{}: expected a JSON object at the top", source));
  return j;
}

/// Checks the file's "format" and "format_version" keys.
inline void check_format(const Keys& top, const std::string& format, int version) {
  if (const std::string given = top.string("format"); given != format)
    top.fail("format", fmt::format("expected \"{}\", got \"{}\"", format, given));
  const nlohmann::ordered_json* v = top.find("format_version", true);
  if (!v->is_number_integer() || v->get<int>() != version)
    top.fail("format_version", fmt::format("expected {}, got {}", version, v->dump()));
}

}  // namespace dampbench
