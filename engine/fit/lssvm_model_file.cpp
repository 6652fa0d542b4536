#include "engine/fit/lssvm_model_file.hpp"

#include <fstream>

#include "engine/common/text_file.hpp"
#include "engine/fit/json_keys.hpp"
#include "engine/fit/model_file.hpp"

namespace dampbench {
namespace {

using Json = nlohmann::ordered_json;

Json vector_json(const Eigen::VectorXd& v) {
  Json a = Json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) a.push_back(v[i]);
  return a;
}

/// The numbers of the array `v`, which messages name as `key` of `keys` (exactly `size` of them when size ≥ 0).
Eigen::VectorXd numbers_of(const Json* v, const Keys& keys, const std::string& key, Eigen::Index size) {
  if (!v->is_array()) keys.fail(key, fmt::format("expected an array of numbers, got {}", v->dump().substr(0, 80)));
  if (size >= 0 && static_cast<Eigen::Index>(v->size()) != size)
    keys.fail(key, fmt::format("expected {} numbers, got {}", size, v->size()));
  Eigen::VectorXd out(static_cast<Eigen::Index>(v->size()));
  for (std::size_t i = 0; i < v->size(); ++i) {
    if (!(*v)[i].is_number()) keys.fail(key, fmt::format("entry {} is not a number: {}", i, (*v)[i].dump()));
    out[static_cast<Eigen::Index>(i)] = (*v)[i].get<double>();
  }
  return out;
}

/// The numbers of the array at `key`.
Eigen::VectorXd vector_at(const Keys& keys, const std::string& key, Eigen::Index size) {
  return numbers_of(keys.find(key, true), keys, key, size);
}

}  // namespace

std::string lssvm_model_file_text(const lssvm::Model& model, const std::vector<std::string>& trained_on,
                                  const std::string& dampbench_version) {
  Json j;
  j["format"] = kLssvmModelFileFormat;
  j["format_version"] = kLssvmModelFileVersion;
  j["dampbench_version"] = dampbench_version;
  j["lags"] = lssvm::format_lags(model.lags());
  j["c"] = model.c();
  j["sigma"] = model.sigma();
  j["normalizer"] = {{"mean", vector_json(model.normalizer().mean)}, {"scale", vector_json(model.normalizer().scale)}};
  j["b"] = model.coefficients().b;
  j["alpha"] = vector_json(model.coefficients().alpha);
  Json points = Json::array();  // one normalized training point (a regressor) per entry
  for (Eigen::Index n = 0; n < model.points().cols(); ++n) points.push_back(vector_json(model.points().col(n)));
  j["points"] = points;
  j["trained_on"] = trained_on;
  return exact_json_text(j);
}

void write_lssvm_model_file(const std::string& path, const lssvm::Model& model,
                            const std::vector<std::string>& trained_on, const std::string& dampbench_version) {
  write_text_file(path, lssvm_model_file_text(model, trained_on, dampbench_version));
}

lssvm::Model parse_lssvm_model_file(const std::string& text, const std::string& source) {
  const Json j = parse_json_object(text, source);
  const Keys top{source, j, ""};
  check_format(top, kLssvmModelFileFormat, kLssvmModelFileVersion);
  const lssvm::Lags lags = lssvm::parse_lags(top.string("lags"), source + ": key 'lags'");
  const Eigen::Index dim = lags.dim();
  const Keys norm = top.object_at("normalizer");
  lssvm::Normalizer normalizer{vector_at(norm, "mean", dim), vector_at(norm, "scale", dim)};
  lssvm::Coefficients coef{top.number("b"), vector_at(top, "alpha", -1)};
  const Json* list = top.find("points", true);
  if (!list->is_array() || static_cast<Eigen::Index>(list->size()) != coef.alpha.size())
    top.fail("points", fmt::format("expected an array of {} points (one per alpha)", coef.alpha.size()));
  Eigen::MatrixXd points(dim, coef.alpha.size());
  for (std::size_t n = 0; n < list->size(); ++n) {  // messages name points[n].point
    const Keys at{source, j, fmt::format("points[{}]", n)};
    points.col(static_cast<Eigen::Index>(n)) = numbers_of(&(*list)[n], at, "point", dim);
  }
  return lssvm::Model::from_parts(lags, top.number("c"), top.number("sigma"), std::move(normalizer), std::move(points),
                                  std::move(coef));
}

lssvm::Model load_lssvm_model_file(const std::string& path) {
  return parse_lssvm_model_file(read_model_file_text(path), path);
}

bool is_lssvm_model_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) return false;
  const Json j = Json::parse(in, nullptr, /*allow_exceptions=*/false);
  return j.is_object() && j.contains("format") && j["format"] == kLssvmModelFileFormat;
}

}  // namespace dampbench
