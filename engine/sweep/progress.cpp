#include "engine/sweep/progress.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>

#include <fmt/format.h>

namespace dampbench::sweep {

std::string format_duration(double s) {
  if (!std::isfinite(s) || s < 0) return "--";
  const long long t = std::llround(s);
  if (t >= 3600) return fmt::format("{}h{:02}m", t / 3600, (t % 3600) / 60);
  if (t >= 60) return fmt::format("{}m{:02}s", t / 60, t % 60);
  return fmt::format("{}s", t);
}

ProgressBar::ProgressBar(bool enabled, long long total, long long done)
    : enabled_(enabled && isatty(STDERR_FILENO)), total_(total), done_(done),
      start_(std::chrono::steady_clock::now()), last_draw_(start_) {
  draw(true);
}

ProgressBar::~ProgressBar() { finish(); }

std::string ProgressBar::render(long long done, long long total, double evals_per_s, double eta_s, int width) {
  const double f = total > 0 ? static_cast<double>(done) / static_cast<double>(total) : 1.0;
  const int fill = static_cast<int>(std::lround(f * width));
  return fmt::format("[{}{}] {}/{} tasks {:3.0f}%  {:.3g} evals/s  ETA {}", std::string(fill, '#'),
                     std::string(width - fill, ' '), done, total, 100 * f, evals_per_s, format_duration(eta_s));
}

void ProgressBar::draw(bool force) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (!force && now - last_draw_ < std::chrono::milliseconds(200)) return;
  last_draw_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double rate = elapsed > 0 ? static_cast<double>(evaluations_) / elapsed : 0;
  const double eta = session_done_ > 0 ? elapsed / static_cast<double>(session_done_) * static_cast<double>(total_ - done_)
                                       : std::nan("");
  std::fprintf(stderr, "\r%s\x1b[K", render(done_, total_, rate, eta).c_str());
  std::fflush(stderr);
  drawn_ = true;
}

void ProgressBar::advance(long long tasks, long long evaluations) {
  done_ += tasks;
  session_done_ += tasks;
  evaluations_ += evaluations;
  draw(done_ == total_);
}

void ProgressBar::log(const std::string& line) {
  if (enabled_ && drawn_) std::fprintf(stderr, "\r\x1b[K");
  std::fprintf(stderr, "%s\n", line.c_str());
  if (enabled_) draw(true);
}

void ProgressBar::finish() {
  if (enabled_ && drawn_) {
    draw(true);
    std::fprintf(stderr, "\n");
    std::fflush(stderr);
  }
  drawn_ = false;
  enabled_ = false;
}

}  // namespace dampbench::sweep
