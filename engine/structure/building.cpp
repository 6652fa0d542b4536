#include "engine/structure/building.hpp"

#include <cmath>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "engine/common/error.hpp"

namespace dampbench::structure {

void check_building(const Building& b, const std::string& where) {
  const int n = b.storeys();
  if (n < 1) throw InputError(fmt::format("{}: mass_kg: expected at least one storey mass", where));
  for (int i = 0; i < n; ++i)
    if (!(b.mass_kg[i] > 0) || !std::isfinite(b.mass_kg[i]))
      throw InputError(fmt::format("{}: mass_kg[{}]: expected a finite mass > 0 kg, got {}", where, i, b.mass_kg[i]));
  const auto& K = b.stiffness_N_m;
  if (K.rows() != n || K.cols() != n)
    throw InputError(fmt::format("{}: stiffness_N_m: expected a {}x{} matrix (one row and column per storey mass), got "
                                 "{}x{}", where, n, n, K.rows(), K.cols()));
  if (!K.allFinite()) throw InputError(fmt::format("{}: stiffness_N_m: expected finite numbers", where));
  const double scale = K.cwiseAbs().maxCoeff();
  if (!((K - K.transpose()).cwiseAbs().maxCoeff() <= 1e-9 * scale))
    throw InputError(fmt::format("{}: stiffness_N_m: expected a symmetric matrix", where));
  if (Eigen::LLT<Eigen::MatrixXd>(K).info() != Eigen::Success)
    throw InputError(fmt::format("{}: stiffness_N_m: expected a positive definite matrix (a building that stands)", where));
  if (b.modal_damping.size() != n)
    throw InputError(fmt::format("{}: modal_damping: expected {} ratios (one per mode) or one number, got {}", where, n,
                                 b.modal_damping.size()));
  for (int i = 0; i < n; ++i)
    if (!(b.modal_damping[i] >= 0 && b.modal_damping[i] < 1))
      throw InputError(fmt::format("{}: modal_damping[{}]: expected a ratio in [0, 1), got {}", where, i, b.modal_damping[i]));
  if (b.damper_storey < 1 || b.damper_storey > n)
    throw InputError(fmt::format("{}: damper_storey: expected a storey from 1 to {}, got {}", where, n, b.damper_storey));
}

Modes modes_of(const Building& b) {
  const Eigen::MatrixXd M = b.mass_kg.asDiagonal();
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(b.stiffness_N_m, M);  // K φ = ω² M φ, φᵀMφ = 1
  Modes m;
  m.omega_rad_s = solver.eigenvalues().cwiseSqrt();
  m.shapes = solver.eigenvectors();
  const Eigen::VectorXd c = 2.0 * b.modal_damping.cwiseProduct(m.omega_rad_s);
  m.damping_N_s_m = M * m.shapes * c.asDiagonal() * m.shapes.transpose() * M;
  return m;
}

namespace {

Eigen::VectorXd numbers(const toml::node* node, const std::string& where, const char* key) {
  const auto* array = node ? node->as_array() : nullptr;
  if (!array) throw InputError(fmt::format("{}: {}: expected an array of numbers", where, key));
  Eigen::VectorXd out(static_cast<Eigen::Index>(array->size()));
  for (std::size_t i = 0; i < array->size(); ++i) {
    const auto value = (*array)[i].value<double>();
    if (!value) throw InputError(fmt::format("{}: {}[{}]: expected a number", where, key, i));
    out[static_cast<Eigen::Index>(i)] = *value;
  }
  return out;
}

}  // namespace

Building read_building_file(const std::string& path) {
  toml::table file;
  try {
    file = toml::parse_file(path);
  } catch (const toml::parse_error& e) {
    throw InputError(fmt::format("{}: not a TOML building file: {}", path, e.description()));
  }
  Building b;
  b.name = file["name"].value_or(std::string{});
  if (b.name.empty()) throw InputError(fmt::format("{}: name: expected the building's name", path));
  b.mass_kg = numbers(file.get("mass_kg"), path, "mass_kg");
  const auto* rows = file["stiffness_N_m"].as_array();
  if (!rows) throw InputError(fmt::format("{}: stiffness_N_m: expected an array of rows (arrays of numbers)", path));
  b.stiffness_N_m.resize(static_cast<Eigen::Index>(rows->size()), b.mass_kg.size());
  for (std::size_t i = 0; i < rows->size(); ++i) {
    const Eigen::VectorXd row = numbers(&(*rows)[i], path, fmt::format("stiffness_N_m[{}]", i).c_str());
    if (row.size() != b.mass_kg.size())
      throw InputError(fmt::format("{}: stiffness_N_m[{}]: expected {} numbers (one per storey mass), got {}", path, i,
                                   b.mass_kg.size(), row.size()));
    b.stiffness_N_m.row(static_cast<Eigen::Index>(i)) = row.transpose();
  }
  if (const auto one = file["modal_damping"].value<double>()) b.modal_damping = Eigen::VectorXd::Constant(b.mass_kg.size(), *one);
  else b.modal_damping = numbers(file.get("modal_damping"), path, "modal_damping");
  if (file.contains("damper_storey")) {
    const auto storey = file["damper_storey"].value<std::int64_t>();
    if (!storey) throw InputError(fmt::format("{}: damper_storey: expected a whole storey number", path));
    b.damper_storey = static_cast<int>(*storey);
  }
  check_building(b, path);
  return b;
}

}  // namespace dampbench::structure
