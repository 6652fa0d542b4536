#include "engine/record/preprocess.hpp"

#include <algorithm>
#include <numeric>

#include <fmt/format.h>

#include "engine/common/error.hpp"

namespace dampbench {

std::vector<double> centred_moving_average(const std::vector<double>& values, int window) {
  const auto n = static_cast<std::ptrdiff_t>(values.size());
  const std::ptrdiff_t before = window / 2, width = window;
  std::vector<double> out(values.size());
  for (std::ptrdiff_t k = 0; k < n; ++k) {
    const std::ptrdiff_t lo = std::max<std::ptrdiff_t>(0, k - before), hi = std::min(n, k - before + width);
    double sum = 0;
    for (std::ptrdiff_t j = lo; j < hi; ++j) sum += values[static_cast<std::size_t>(j)];
    out[static_cast<std::size_t>(k)] = sum / static_cast<double>(hi - lo);
  }
  return out;
}

void remove_mean(std::vector<double>& values) {
  const double mean = std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
  for (double& v : values) v -= mean;
}

std::pair<std::size_t, std::size_t> whole_cycles_span(const std::vector<double>& x, const std::string& source) {
  const double mean = std::accumulate(x.begin(), x.end(), 0.0) / static_cast<double>(x.size());
  std::vector<std::size_t> upward;
  for (std::size_t k = 1; k < x.size(); ++k)
    if (x[k - 1] < mean && x[k] >= mean) upward.push_back(k);
  if (upward.size() < 2)
    throw InputError(fmt::format("{}: --whole-cycles: x crosses its mean upward {} time{}; a whole cycle needs two",
                                 source, upward.size(), upward.size() == 1 ? "" : "s"));
  return {upward.front(), upward.back()};
}

}  // namespace dampbench
