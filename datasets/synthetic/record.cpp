#include <cmath>
#include <fstream>

#include <fmt/format.h>

#include "datasets/synthetic/synthetic.hpp"
#include "engine/random.hpp"

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
}

void add_noise(std::vector<double>& F, double relative, std::uint64_t seed, const std::string& file) {
  double sum_sq = 0;
  for (double f : F) sum_sq += f * f;
  const double sigma = relative * std::sqrt(sum_sq / static_cast<double>(F.size()));
  RandomStream rng(hash_key({seed, hash_name(file)}));
  for (double& f : F) f += sigma * rng.normal();
}

}  // namespace dampbench::synthetic
