#include "engine/structure/ground_motion.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "engine/common/error.hpp"

namespace dampbench::structure {

double GroundMotion::at(double t) const {
  if (t <= t_s.front()) return ag_m_s2.front();
  if (t >= t_s.back()) return ag_m_s2.back();
  const auto k = static_cast<std::size_t>(std::upper_bound(t_s.begin(), t_s.end(), t) - t_s.begin());
  const double th = (t - t_s[k - 1]) / (t_s[k] - t_s[k - 1]);
  return ag_m_s2[k - 1] + th * (ag_m_s2[k] - ag_m_s2[k - 1]);
}

namespace {

std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream s(line);
  std::string field;
  while (std::getline(s, field, ',')) {
    field.erase(0, field.find_first_not_of(" \t\r"));
    field.erase(field.find_last_not_of(" \t\r") + 1);
    out.push_back(field);
  }
  return out;
}

}  // namespace

GroundMotion read_ground_motion(const std::string& path, double scale) {
  if (!std::isfinite(scale)) throw InputError(fmt::format("--scale: expected a finite number, got {}", scale));
  std::ifstream in(path);
  if (!in) throw InputError(fmt::format("{}: cannot read the ground-motion file", path));
  std::string line;
  if (!std::getline(in, line)) throw InputError(fmt::format("{}: empty file; expected a header naming t and ag", path));
  const auto header = split_fields(line);
  const auto column = [&](const char* name) {
    const auto it = std::find(header.begin(), header.end(), name);
    if (it == header.end())
      throw InputError(fmt::format("{}: line 1: expected a header naming the columns t [s] and ag [m/s^2], got '{}'", path, line));
    return static_cast<std::size_t>(it - header.begin());
  };
  const std::size_t it = column("t"), ia = column("ag");
  GroundMotion g;
  g.name = std::filesystem::path(path).stem().string();
  for (int number = 2; std::getline(in, line); ++number) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const auto fields = split_fields(line);
    const auto value = [&](std::size_t i, const char* name) {
      double v = std::nan("");
      std::size_t used = 0;
      try {
        if (i < fields.size()) v = std::stod(fields[i], &used);
      } catch (const std::exception&) {
      }
      if (i >= fields.size() || used != fields[i].size() || !std::isfinite(v))
        throw InputError(fmt::format("{}: line {}: {}: expected a finite number, got '{}'", path, number, name,
                                     i < fields.size() ? fields[i] : ""));
      return v;
    };
    const double t = value(it, "t"), a = value(ia, "ag");
    if (!g.t_s.empty() && !(t > g.t_s.back()))
      throw InputError(fmt::format("{}: line {}: t: expected a time after {} s, got {}", path, number, g.t_s.back(), t));
    g.t_s.push_back(t);
    g.ag_m_s2.push_back(scale * a);
  }
  if (g.t_s.size() < 2) throw InputError(fmt::format("{}: expected at least two samples of t and ag", path));
  return g;
}

}  // namespace dampbench::structure
