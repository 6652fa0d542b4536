#include <cmath>
#include <fstream>
#include <numbers>

#include <fmt/format.h>

#include "datasets/synthetic/synthetic.hpp"
#include "engine/common/error.hpp"
#include "engine/common/random.hpp"

namespace dampbench::synthetic {

void write_record(const std::filesystem::path& dir, const Record& r) {
  std::filesystem::create_directories(dir);
  std::ofstream out(dir / r.file);
  out << "# " << r.description << "\n";
  if (!r.operating.empty()) {
    std::string ops;
    for (const auto& [k, v] : r.operating) ops += fmt::format("{}{}={:.9g}", ops.empty() ? "" : ",", k, v);
    out << "# operating: " << ops << "\n";
  }
  out << fmt::format("t[s],x[{}],F[{}]\n", r.x_unit, r.F_unit);
  for (std::size_t k = 0; k < r.t_s.size(); ++k) out << fmt::format("{:.9g},{:.9g},{:.9g}\n", r.t_s[k], r.x[k], r.F[k]);
  out.flush();
  if (!out) throw InputError(fmt::format("cannot write '{}'", (dir / r.file).string()));
}

Dataset sine_record(double amp, double f, int cycles, int per_cycle, Record& r) {
  Dataset d;
  d.name = r.file;
  d.operating = r.operating;
  const double w = 2 * std::numbers::pi * f;
  for (int k = 0; k <= cycles * per_cycle; ++k) {
    const double t = k / (f * per_cycle);
    d.t_s.push_back(t);
    d.x_m.push_back(amp * std::sin(w * t));
    d.v_m_s.push_back(amp * w * std::cos(w * t));
    d.a_m_s2.push_back(-amp * w * w * std::sin(w * t));
    r.t_s.push_back(t);
    r.x.push_back(d.x_m.back() * 1e3);
  }
  return d;
}

void add_noise(std::vector<double>& F, double relative, std::uint64_t seed, const std::string& file) {
  double sum_sq = 0;
  for (double f : F) sum_sq += f * f;
  const double sigma = relative * std::sqrt(sum_sq / static_cast<double>(F.size()));
  RandomStream rng(hash_key({seed, hash_name(file)}));
  for (double& f : F) f += sigma * rng.normal();
}

}  // namespace dampbench::synthetic
