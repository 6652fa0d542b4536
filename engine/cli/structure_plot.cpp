#include "engine/cli/structure_plot.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>

namespace dampbench::cli {
namespace {

constexpr double kWidth = 900, kPanelHeight = 170, kLeft = 70, kRight = 20, kTop = 40, kGap = 45;

struct Series {
  const std::vector<double>* y;
  const char* colour;
  std::string label;
};

/// One panel: the series against t on a shared symmetric y range, with its axis labels and legend.
std::string panel(int index, const std::vector<double>& t, const std::vector<Series>& series, const std::string& unit) {
  const double top = kTop + index * (kPanelHeight + kGap), width = kWidth - kLeft - kRight;
  double peak = 0;
  for (const auto& s : series)
    for (double v : *s.y)
      if (std::isfinite(v)) peak = std::max(peak, std::fabs(v));
  if (!(peak > 0)) peak = 1;
  const double t0 = t.front(), span = std::max(t.back() - t0, 1e-12);
  const auto X = [&](double tt) { return kLeft + width * (tt - t0) / span; };
  const auto Y = [&](double v) { return top + kPanelHeight * (0.5 - 0.5 * v / peak); };
  std::string out = fmt::format(R"svg(<rect x="{}" y="{}" width="{}" height="{}" fill="none" stroke="#999"/>)svg", kLeft, top,
                                width, kPanelHeight);
  out += fmt::format(R"svg(<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="#ddd"/>)svg", kLeft, Y(0), kLeft + width, Y(0));
  out += fmt::format(R"svg(<text x="{}" y="{}" text-anchor="end">{:.4g}</text><text x="{}" y="{}" text-anchor="end">{:.4g}</text>)svg",
                     kLeft - 5, top + 10, peak, kLeft - 5, top + kPanelHeight, -peak);
  out += fmt::format(R"svg(<text x="{}" y="{}" transform="rotate(-90 {} {})" text-anchor="middle">{}</text>)svg", 15,
                     top + kPanelHeight / 2, 15, top + kPanelHeight / 2, unit);
  for (std::size_t s = 0; s < series.size(); ++s) {
    // At most kBins bins of samples, each drawn by its lowest and highest value in time order, so the peaks stay.
    constexpr std::size_t kBins = 1200;
    const std::size_t bin = std::max<std::size_t>(1, (t.size() + kBins - 1) / kBins);
    std::string points;
    const auto& y = *series[s].y;
    for (std::size_t b0 = 0; b0 < t.size(); b0 += bin) {
      std::size_t lo = b0, hi = b0;
      for (std::size_t k = b0; k < std::min(t.size(), b0 + bin); ++k) {
        if (!std::isfinite(y[k])) continue;
        if (!std::isfinite(y[lo]) || y[k] < y[lo]) lo = k;
        if (!std::isfinite(y[hi]) || y[k] > y[hi]) hi = k;
      }
      for (const std::size_t k : {std::min(lo, hi), std::max(lo, hi)})
        if (std::isfinite(y[k])) points += fmt::format("{:.1f},{:.1f} ", X(t[k]), Y(y[k]));
    }
    out += fmt::format(R"svg(<polyline fill="none" stroke="{}" stroke-width="1" points="{}"/>)svg", series[s].colour, points);
    out += fmt::format(R"svg(<text x="{}" y="{}" fill="{}">{}</text>)svg", kLeft + 10 + 260 * static_cast<double>(s),
                       top - 6, series[s].colour, series[s].label);
  }
  return out;
}

std::vector<double> column(const Eigen::MatrixXd& m, int j, double scale) {
  std::vector<double> out(static_cast<std::size_t>(m.rows()));
  for (Eigen::Index i = 0; i < m.rows(); ++i) out[static_cast<std::size_t>(i)] = scale * m(i, j);
  return out;
}

}  // namespace

std::string structure_svg(const std::string& title, int storey, const structure::SeismicResponse& bare,
                          const structure::SeismicResponse& damped, const std::string& command_name) {
  const int j = storey - 1;
  const auto drift_bare = column(bare.drift_m, j, 1e3), drift = column(damped.drift_m, j, 1e3);
  const auto acc_bare = column(bare.abs_acc_m_s2, j, 1.0), acc = column(damped.abs_acc_m_s2, j, 1.0);
  std::vector<double> command = damped.command;
  double force_peak = 0, command_peak = 0;
  for (double f : damped.force_N) force_peak = std::max(force_peak, std::fabs(f));
  for (double c : command) command_peak = std::max(command_peak, std::isfinite(c) ? std::fabs(c) : 0.0);
  const bool has_command = command_peak > 0;
  for (double& c : command) c = has_command ? c * force_peak / command_peak : std::nan("");  // on the force's scale
  const double height = kTop + 3 * (kPanelHeight + kGap);
  std::string svg = fmt::format(R"svg(<svg xmlns="http://www.w3.org/2000/svg" width="{}" height="{}" font-family="sans-serif" font-size="12">)svg",
                                kWidth, height);
  svg += fmt::format(R"svg(<rect width="100%" height="100%" fill="white"/><text x="{}" y="18" font-size="14">{}</text>)svg", kLeft, title);
  svg += panel(0, damped.t_s, {{&drift_bare, "#999999", fmt::format("storey {} drift, bare [mm]", storey)},
                               {&drift, "#1f5fbf", "with the damper [mm]"}}, "drift [mm]");
  svg += panel(1, damped.t_s, {{&acc_bare, "#999999", fmt::format("storey {} absolute acceleration, bare", storey)},
                               {&acc, "#1f5fbf", "with the damper [m/s2]"}}, "acc. [m/s2]");
  std::vector<Series> force{{&damped.force_N, "#bf3f1f", "damper force [N]"}};
  if (has_command) force.push_back({&command, "#2f9f4f", fmt::format("command {} (0 to {:g}, scaled)", command_name, command_peak)});
  svg += panel(2, damped.t_s, force, "force [N]");
  svg += fmt::format(R"svg(<text x="{}" y="{}">{:g}</text><text x="{}" y="{}" text-anchor="end">{:g}</text>)svg", kLeft,
                     height - 22, damped.t_s.front(), kWidth - kRight, height - 22, damped.t_s.back());
  svg += fmt::format(R"svg(<text x="{}" y="{}" text-anchor="middle">t [s]</text></svg>)svg", kLeft + (kWidth - kLeft - kRight) / 2,
                     height - 8);
  return svg + "\n";
}

}  // namespace dampbench::cli
