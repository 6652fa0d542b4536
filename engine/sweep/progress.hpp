#pragma once
// A one-line progress bar on stderr: tasks done/total, evaluations per second, ETA. Drawn only when stderr
// is a terminal (and not --quiet); redrawn at most a few times per second.
#include <chrono>
#include <string>

namespace dampbench::sweep {

class ProgressBar {
 public:
  /// `enabled` is ANDed with isatty(stderr). `done` tasks are already finished (resume).
  ProgressBar(bool enabled, long long total_tasks, long long done_tasks);
  ~ProgressBar();

  /// Adds finished tasks and the evaluations they cost; redraws if due.
  void advance(long long tasks, long long evaluations);
  /// Prints a line above the bar (a failure, say).
  void log(const std::string& line);
  /// Clears the bar (final newline).
  void finish();

  [[nodiscard]] bool active() const { return enabled_; }

  /// The bar's text for given figures (testable; no terminal needed).
  static std::string render(long long done, long long total, double evals_per_s, double eta_s, int width = 30);

 private:
  void draw(bool force);
  bool enabled_;
  long long total_, done_, session_done_ = 0, evaluations_ = 0;
  std::chrono::steady_clock::time_point start_, last_draw_;
  bool drawn_ = false;
};

/// "1h02m", "3m05s", "12s".
std::string format_duration(double seconds);

}  // namespace dampbench::sweep
