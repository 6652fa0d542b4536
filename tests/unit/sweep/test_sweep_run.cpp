// Running sweeps (engine/sweep/runner.hpp) in process and through the dampbench executable: failed tasks
// are recorded while the sweep completes; a sweep stopped by Ctrl-C or killed with SIGKILL resumes to
// results identical bit for bit to an uninterrupted run; a store from another spec is refused; verify
// passes on a fresh store and fails on one whose number was altered.
#include "engine/sweep/runner.hpp"

#include <gtest/gtest.h>
#include <sqlite3.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <map>
#include <numbers>
#include <thread>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <tbb/task_arena.h>

#include "engine/evaluation/bench_workload.hpp"
#include "engine/record/csv_loader.hpp"
#include "engine/record/excitation.hpp"
#include "engine/kernels/isa.hpp"
#include "engine/sweep/progress.hpp"
#include "engine/sweep/store.hpp"
#include "models/registry.hpp"
#include "tests/sweep_test_support.hpp"
#include "tests/test_support.hpp"

namespace dampbench::sweep {
namespace {

namespace fs = std::filesystem;
using testing::run_dampbench;

/// A sine record, force of a generalized viscous damper plus a little stiffness, with operating variables.
void write_record(const fs::path& p, const std::string& operating, double amp, double freq, int samples) {
  std::string s = operating.empty() ? "" : "# operating: " + operating + "\n";
  s += "t[s],x[mm],F[N]\n";
  for (int k = 0; k < samples; ++k) {
    const double t = 3.0 * k / (freq * (samples - 1)), w = 2 * std::numbers::pi * freq;
    const double x = amp * std::sin(w * t), v = amp * w * std::cos(w * t);
    const double F = 2e4 * (v > 0 ? 1 : -1) * std::pow(std::fabs(v), 0.4) + 3e5 * x + 500 * std::sin(7 * w * t);
    s += fmt::format("{:.9g},{:.9g},{:.9g}\n", t, 1e3 * x, F);
  }
  testing::write_text(p, s);
}

/// Every group of two stores, compared number by number (bits).
void expect_same_results(const std::string& a_path, const std::string& b_path) {
  const Store a = Store::open(a_path), b = Store::open(b_path);
  const auto ha = a.header(), hb = b.header();
  ASSERT_EQ(ha.spec_hash, hb.spec_hash);
  ASSERT_EQ(ha.groups, hb.groups);
  ASSERT_EQ(a.stored_groups(), ha.groups);
  ASSERT_EQ(b.stored_groups(), hb.groups);
  for (std::size_t d = 0; d < ha.datasets.size(); ++d) EXPECT_EQ(ha.datasets[d].hash, hb.datasets[d].hash);
  long long runs = 0;
  for (long long i = 0; i < ha.groups; ++i) {
    const auto ga = a.group(i), gb = b.group(i);
    ASSERT_TRUE(ga && gb) << i;
    const auto diff = compare_records(*ga, *gb);
    EXPECT_TRUE(diff.empty()) << "group " << i << ": " << diff.front();
    EXPECT_EQ(ga->dataset_hash, gb->dataset_hash);
    runs += static_cast<long long>(ga->run_results.size());
  }
  EXPECT_GT(runs, 0);
}

long long stored_groups(const fs::path& store) {
  sqlite3* db = nullptr;
  if (sqlite3_open_v2(store.string().c_str(), &db, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) {
    sqlite3_close(db);
    return 0;
  }
  long long n = 0;
  sqlite3_stmt* s = nullptr;
  if (sqlite3_prepare_v2(db, "SELECT COUNT(*) FROM groups", -1, &s, nullptr) == SQLITE_OK && sqlite3_step(s) == SQLITE_ROW)
    n = sqlite3_column_int64(s, 0);
  sqlite3_finalize(s);
  sqlite3_close(db);
  return n;
}

/// Starts `dampbench run ...` as a child process (output discarded).
pid_t start_run(const std::vector<std::string>& args) {
  // Everything allocated before fork: the child only calls async-signal-safe functions.
  std::vector<char*> argv{const_cast<char*>(DAMPBENCH_EXE), const_cast<char*>("run")};
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    const int null = open("/dev/null", O_WRONLY);
    dup2(null, 1);
    dup2(null, 2);
    execv(DAMPBENCH_EXE, argv.data());
    _exit(127);
  }
  return pid;
}

/// Waits until the store holds at least `n` groups or the child ends; true if it is still running.
bool wait_for_groups(pid_t pid, const fs::path& store, long long n) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (std::chrono::steady_clock::now() < deadline) {
    int status = 0;
    if (waitpid(pid, &status, WNOHANG) == pid) return false;
    if (stored_groups(store) >= n) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return true;
}

int wait_exit(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : (WIFSIGNALED(status) ? 128 + WTERMSIG(status) : -1);
}

// ---- in process -----------------------------------------------------------------------------------

class SmallSweep : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::test_temp_dir("sweeprun");
    for (int i = 0; i < 3; ++i) write_record(dir_ / "data" / fmt::format("c{}.csv", i), fmt::format("I={}", i), 0.01 * (i + 1), 1, 121);
  }
  std::string spec(const std::string& extra = "") const {
    return fmt::format(R"toml(name = "small"
seed = 3
runs = 3
metric = "nrmse"
models = ["fvd.generalized_viscous", "fvd.gv_linear_elastic"]
[optimizer]
name = "pso"
population = 12
iterations = 10
[[datasets]]
name = "grid"
glob = "{}/data/*.csv"
{})toml",
                       dir_.string(), extra);
  }
  /// Runs the sweep in an arena of `threads`, stopping after `stop_after` groups (0: never).
  RunnerSummary run(const std::string& text, const std::string& store_path, int threads, int stop_after = 0) const {
    testing::write_text(dir_ / "small.toml", text);
    const Plan plan(load_sweep((dir_ / "small.toml").string()), testing::csv_loader());
    Store store = Store::create_or_resume(store_path, make_store_header(plan, (dir_ / "small.toml").string()));
    std::atomic<bool> stop{false};
    int written = 0;
    RunnerOptions o;
    o.stop = &stop;
    o.on_group = [&](const GroupRecord&, const std::string&) {
      if (stop_after > 0 && ++written >= stop_after) stop = true;
    };
    RunnerSummary s;
    tbb::task_arena(threads).execute([&] { s = run_sweep(plan, store, o); });
    return s;
  }
  fs::path dir_;
};

TEST_F(SmallSweep, StoppedSweepResumesToTheSameBitsWithAnyThreadCount) {
  const std::string full = (dir_ / "full.sqlite").string(), parts = (dir_ / "parts.sqlite").string();
  const RunnerSummary a = run(spec(), full, 1);
  EXPECT_EQ(a.groups, 6);
  EXPECT_EQ(a.tasks, 18);
  EXPECT_EQ(a.ran, 6);
  EXPECT_FALSE(a.interrupted);

  const RunnerSummary b = run(spec(), parts, 2, 2);
  EXPECT_TRUE(b.interrupted);
  EXPECT_GE(b.ran, 2);
  EXPECT_LT(b.ran, 6);
  const RunnerSummary c = run(spec(), parts, 2);
  EXPECT_EQ(c.stored_before, b.ran);
  EXPECT_EQ(c.ran, 6 - b.ran);
  EXPECT_FALSE(c.interrupted);
  expect_same_results(full, parts);
  // Nothing left: a third run does no work.
  EXPECT_EQ(run(spec(), parts, 2).ran, 0);
}

TEST_F(SmallSweep, RecomputedGroupsMatchTheStoreBitForBit) {
  // What verify does, on groups with joint fits, predictions and sensitivities: run_group again, compare.
  const std::string text = spec(R"toml([[splits]]
name = "joint"
by = "all"
fit = { I = [0, 1] }
predict = { I = 2 }
[[splits]]
name = "each"
fit = { I = [0, 2] }
predict = { I = 1 }
sensitivity = { points = 5, where = { I = 0 } }
)toml");
  const std::string path = (dir_ / "v.sqlite").string();
  run(text, path, 2);
  const Plan plan(load_sweep((dir_ / "small.toml").string()), testing::csv_loader());
  const Store store = Store::open(path);
  int with_predictions = 0, with_sensitivity = 0;
  for (long long i = 0; i < plan.groups(); ++i) {
    const auto stored = store.group(i);
    ASSERT_TRUE(stored);
    with_predictions += !stored->dataset_metrics.empty();
    with_sensitivity += stored->sensitivity.has_value();
    const auto diff = compare_records(*stored, run_group(plan, i));
    EXPECT_TRUE(diff.empty()) << "group " << i << ": " << diff.front();
  }
  EXPECT_EQ(with_predictions, plan.groups());  // the joint fit and both per-condition fits predict
  EXPECT_EQ(with_sensitivity, 2);              // I = 0, both models
}

TEST_F(SmallSweep, FailedTasksAreRecordedAndTheSweepCompletes) {
  testing::write_text(dir_ / "data" / "c9.csv", "t,x,F\n0,0,0\n1,1,abc\n2,2,2\n3,3,3\n4,4,4\n5,5,5\n6,6,6\n7,7,7\n8,8,8\n");
  write_record(dir_ / "data" / "c5.csv", "", 0.02, 2, 121);  // no current: the law in I cannot be evaluated
  std::string s = spec();
  s.replace(s.find("models = [\"fvd.generalized_viscous\", \"fvd.gv_linear_elastic\"]"),
            std::string("models = [\"fvd.generalized_viscous\", \"fvd.gv_linear_elastic\"]").size(),
            "models = [\"fvd.generalized_viscous\", { name = \"gv(I)\", model = \"fvd.generalized_viscous\", laws = \"C=poly(I,1)\" }]");
  const std::string path = (dir_ / "f.sqlite").string();
  const RunnerSummary r = run(s, path, 2);
  // 5 datasets x 2 models; c9 fails for both models (bad cell), c5 for the law model (no I).
  EXPECT_EQ(r.groups, 10);
  EXPECT_EQ(r.ran, 10);
  EXPECT_EQ(r.failed, 3);
  const Store store = Store::open(path);
  int failed = 0, done = 0;
  for (const auto& g : store.groups()) {
    if (!g.failed) {
      ++done;
      EXPECT_EQ(g.run_results.size(), 3u);
      continue;
    }
    ++failed;
    EXPECT_TRUE(g.run_results.empty());
    const bool bad_cell = g.message.find("c9.csv:3: column 3 ('F'): expected a number, got 'abc'") != std::string::npos;
    const bool no_current = g.message.find("dataset 'c5' has no operating variable 'I'") != std::string::npos;
    EXPECT_TRUE(bad_cell || no_current) << g.message;
  }
  EXPECT_EQ(failed, 3);
  EXPECT_EQ(done, 7);
  EXPECT_NE(store.header().datasets[4].error.find("expected a number"), std::string::npos);  // c9 sorts last
}

/// `dampbench run` of one model fitted by DE (runs × population × iterations) to every CSV in dir/data, fresh,
/// into dir/out; then `table --kind <kind> --format csv` of its store.
testing::CommandResult sweep_table(const fs::path& dir, const std::string& model, int runs, int population, int iterations,
                                   const std::string& kind) {
  testing::write_text(dir / "s.toml", fmt::format(R"toml(name = "one_model"
runs = {}
metric = "nrmse"
models = ["{}"]
[optimizer]
name = "de"
population = {}
iterations = {}
[[datasets]]
name = "d"
glob = "{}/data/*.csv"
)toml",
                                    runs, model, population, iterations, dir.string()));
  const auto run = run_dampbench(fmt::format("run {} -o {} --quiet --fresh", (dir / "s.toml").string(), (dir / "out").string()));
  EXPECT_EQ(run.exit_code, 0) << run.output;
  return run_dampbench(fmt::format("table {} --kind {} --format csv", (dir / "out" / "store.sqlite").string(), kind));
}

TEST(SweepConvergence, TablesMarkAStarvedGroupAndNotAGenerousOne) {
  const fs::path dir = testing::test_temp_dir("sweeprun");
  write_record(dir / "data" / "c.csv", "", 0.01, 1, 301);
  const auto starved = sweep_table(dir, "fvd.generalized_viscous", 6, 8, 3, "runs"),
             generous = sweep_table(dir, "fvd.generalized_viscous", 6, 30, 200, "runs");
  EXPECT_NE(starved.output.find("Mean,Max,Min,Std,Runs,Converged"), std::string::npos) << starved.output;
  EXPECT_NE(starved.output.find("† runs disagree"), std::string::npos) << starved.output;
  EXPECT_NE(generous.output.find(",6,yes"), std::string::npos) << generous.output;
  EXPECT_EQ(generous.output.find("†"), std::string::npos) << generous.output;
}

// A group under the automatic budget that a cap stops before a restart confirms its best is not converged in the
// tables, although its runs agree (the store keeps the budget's summary as the group's message); with room for the
// confirming restart the same group is.
TEST(SweepConvergence, AnAutomaticBudgetStoppedBeforeItsConfirmingRestartIsMarked) {
  const fs::path dir = testing::test_temp_dir("sweeprun");
  write_record(dir / "data" / "c.csv", "", 0.01, 1, 301);
  const auto table = [&](const std::string& cap) {
    testing::write_text(dir / "s.toml", fmt::format(R"toml(name = "auto_budget"
runs = 4
metric = "nrmse"
models = ["fvd.generalized_viscous"]
[optimizer]
name = "de"
{}
[[datasets]]
name = "d"
glob = "{}/data/*.csv"
)toml",
                                      cap, dir.string()));
    const auto run = run_dampbench(fmt::format("run {} -o {} --quiet --fresh", (dir / "s.toml").string(),
                                               (dir / "out").string()));
    EXPECT_EQ(run.exit_code, 0) << run.output;
    return run_dampbench(fmt::format("table {} --kind runs --format csv", (dir / "out" / "store.sqlite").string()));
  };
  // Round 0 is 4 runs × 50 × 100 = 20 000 evaluations; a round 1 of 40 000 more does not fit in 40 000.
  const auto capped = table("max_total_evaluations = 40000");
  EXPECT_NE(capped.output.find("† not confirmed by a restart"), std::string::npos) << capped.output;
  const auto confirmed = table("");
  EXPECT_NE(confirmed.output.find(",4,yes"), std::string::npos) << confirmed.output;
  EXPECT_EQ(confirmed.output.find("†"), std::string::npos) << confirmed.output;
}

// The energy table: on a record of a linear viscous damper, F = c·v on x = X sin(ωt), the measured loop's area is
// π c ω X² per cycle (hand-computed: 39.478 J for c = 2e4 N·s/m, X = 10 mm, 1 Hz) and the fitted linear viscous
// model dissipates the same; when the record is gone, `table` says so instead of printing a row.
TEST(SweepEnergy, TheLoopAreaOfALinearViscousRecordAndAGoneRecord) {
  const fs::path dir = testing::test_temp_dir("sweeprun");
  const double c = 2e4, X = 0.01, f = 1.0, w = 2 * std::numbers::pi * f;
  std::string csv = "t[s],x[mm],F[N]\n";
  for (int k = 0; k < 601; ++k) {  // 3 cycles, 200 samples each
    const double t = 3.0 * k / (f * 600);
    csv += fmt::format("{:.12g},{:.12g},{:.12g}\n", t, 1e3 * X * std::sin(w * t), c * X * w * std::cos(w * t));
  }
  testing::write_text(dir / "data" / "viscous.csv", csv);
  const auto table = sweep_table(dir, "fvd.linear_viscous", 3, 20, 40, "energy");
  ASSERT_EQ(table.exit_code, 0) << table.output;
  const auto row_at = table.output.find("\nviscous,");
  ASSERT_NE(row_at, std::string::npos) << table.output;
  std::stringstream row(table.output.substr(row_at + 1));
  std::string name, cycles, measured, error;
  std::getline(row, name, ',');
  std::getline(row, cycles, ',');
  std::getline(row, measured, ',');
  std::getline(row, error);
  EXPECT_EQ(cycles, "3");
  const double expected = std::numbers::pi * c * w * X * X;
  EXPECT_NEAR(std::stod(measured), expected, 1e-3 * expected) << table.output;
  EXPECT_LT(std::fabs(std::stod(error)), 0.5) << table.output;  // dE %: the model is the record's own law

  fs::remove(dir / "data" / "viscous.csv");
  const auto gone = run_dampbench(fmt::format("table {} --kind energy --format md", (dir / "out" / "store.sqlite").string()));
  EXPECT_EQ(gone.output.find("| viscous |"), std::string::npos) << gone.output;
  EXPECT_NE(gone.output.find("the records could not be read again: viscous"), std::string::npos) << gone.output;
}

/// A sine record of fvd.gv_linear_elastic's law with m = 0: F = C sgn(v)|v|^0.3 + 4e6 x, 10 mm at `freq` (stated).
void write_viscous_elastic(const fs::path& p, double C, double freq, double K1 = 4e6) {
  std::string s = fmt::format("# operating: freq={}\nt[s],x[mm],F[N]\n", freq);
  for (int k = 0; k < 401; ++k) {
    const double t = 2.0 * k / (freq * 400), w = 2 * std::numbers::pi * freq;
    const double x = 0.01 * std::sin(w * t), v = 0.01 * w * std::cos(w * t);
    s += fmt::format("{:.12g},{:.12g},{:.12g}\n", t, 1e3 * x, C * (v > 0 ? 1 : -1) * std::pow(std::fabs(v), 0.3) + K1 * x);
  }
  testing::write_text(p, s);
}

/// Parameter `name` of the best run of each group of a params table (`table --kind params --format json`), by column.
std::map<std::string, double> params_row(const std::string& json, const std::string& table, const std::string& name) {
  std::map<std::string, double> out;
  const nlohmann::json tables = nlohmann::json::parse(json);  // alive through the loop (a temporary's member is not)
  for (const auto& t : tables.at("tables")) {
    if (t.at("id") != table) continue;
    for (const auto& row : t.at("rows"))
      if (row.at(0) == name)
        for (std::size_t j = 2; j < row.size(); ++j)
          if (row.at(j).is_number()) out[t.at("columns").at(j).get<std::string>()] = row.at(j).get<double>();
  }
  return out;
}

/// A sweep of models "source" and "held" (fvd.gv_linear_elastic; "held" with `hold`), DE of `population` ×
/// `iterations`, the records of dir/data, and the head of split "source" (which fits "source"), for a test to go on.
std::string hold_sweep(const std::string& hold, int population, int iterations, const fs::path& dir) {
  return fmt::format(R"toml(name = "hold"
runs = 2
metric = "nrmse"
[[models]]
name = "source"
model = "fvd.gv_linear_elastic"
[[models]]
name = "held"
model = "fvd.gv_linear_elastic"
hold = {}
[optimizer]
name = "de"
population = {}
iterations = {}
[[datasets]]
name = "d"
glob = "{}/data/*.csv"
[[splits]]
name = "source"
models = ["source"]
)toml",
                     hold, population, iterations, dir.string());
}

// A model held to another's fit (hold, the fdsp paper's step 2): m, alpha and K1 at the source record's fit, C free
// within ±50 % of the source's C and, in the order of the frequency, ±10 % of the fit before. The record at 1 Hz has
// 1.4 times the source's C (inside the window: found), the one at 2 Hz the source's own C, which the window of the fit
// before (1.26–1.54 times) leaves out: its fit sits at the window's lower edge, 0.9 times the 1 Hz fit, where
// without the sequence it would have found the source's C again.
TEST(SweepHold, HeldParametersComeFromTheSourceFitAndTheWindowsFollowTheSequence) {
  const fs::path dir = testing::test_temp_dir("sweeprun");
  const double C = 8e5;
  write_viscous_elastic(dir / "data" / "a_source.csv", C, 0.5);
  write_viscous_elastic(dir / "data" / "b_1Hz.csv", 1.4 * C, 1.0);
  write_viscous_elastic(dir / "data" / "c_2Hz.csv", C, 2.0);
  testing::write_text(dir / "s.toml", hold_sweep(R"({ from = "source", split = "source", free = ["C"], first = 0.5, next = 0.1, order = "freq" })",
                                                 40, 300, dir) + R"toml(fit = { freq = 0.5 }
by = "all"
[[splits]]
name = "chain"
models = ["held"]
fit = { freq = [1, 2] }
)toml");
  const auto run = run_dampbench(fmt::format("run {} -o {} --quiet --fresh", (dir / "s.toml").string(), (dir / "out").string()));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const auto table = run_dampbench(fmt::format("table {} --kind params --format json", (dir / "out" / "store.sqlite").string()));
  ASSERT_EQ(table.exit_code, 0) << table.output;
  const auto source_C = params_row(table.output, "params_source_source", "C");
  const auto source_K1 = params_row(table.output, "params_source_source", "K1");
  const auto held_C = params_row(table.output, "params_held_chain", "C");
  ASSERT_EQ(source_C.size(), 1u) << table.output;
  ASSERT_EQ(held_C.size(), 2u) << table.output;
  // The source's table is in the paper's units (kN/(mm/s)^alpha, kN/mm), the held law model's in SI.
  const double c_source = source_C.begin()->second * 1e3 / std::pow(1e-3, 0.3);
  EXPECT_NEAR(c_source, C, 0.01 * C);
  EXPECT_NEAR(held_C.at("b_1Hz"), 1.4 * c_source, 0.01 * c_source);
  EXPECT_NEAR(held_C.at("c_2Hz"), 0.9 * held_C.at("b_1Hz"), 1e-6 * c_source);  // the window's edge
  // The held laws name the source's own K1 (the params table's laws row, in SI: kN/mm × 1e6).
  EXPECT_NE(table.output.find(fmt::format("K1={:.4f}", source_K1.begin()->second * 1e6).substr(0, 9)), std::string::npos)
      << table.output;
  // One thread (each held group then finds the fits it holds to made before it, or makes them) gives the same bits,
  // and so does verify, whose groups make their own.
  const auto one = run_dampbench(fmt::format("run {} -o {} --quiet --fresh --threads 1", (dir / "s.toml").string(),
                                             (dir / "one").string()));
  ASSERT_EQ(one.exit_code, 0) << one.output;
  expect_same_results((dir / "out" / "store.sqlite").string(), (dir / "one" / "store.sqlite").string());
  const auto verify = run_dampbench(fmt::format("verify {}", (dir / "one" / "store.sqlite").string()));
  EXPECT_EQ(verify.exit_code, 0) << verify.output;
}

// A model held at the means of another's fits over several conditions (hold with mean = true, the crfd paper's eq. 4.4):
// the sources' stiffnesses K1 are 3e6 and 5e6 N/m, the held record's 4e6, their mean, with another C. The held laws
// carry the mean of the sources' fitted K1 (not either one's), and the fit finds the record's C in C's own box.
TEST(SweepHold, MeanHoldsAtTheMeansOfTheSourceFitsAndLeavesTheFreeParametersTheirBox) {
  const fs::path dir = testing::test_temp_dir("sweeprun");
  const double C = 8e5;
  write_viscous_elastic(dir / "data" / "a_soft.csv", C, 0.5, 3e6);
  write_viscous_elastic(dir / "data" / "b_stiff.csv", C, 0.75, 5e6);
  write_viscous_elastic(dir / "data" / "c_held.csv", 1.5 * C, 1.0, 4e6);
  testing::write_text(dir / "s.toml", hold_sweep(R"({ from = "source", split = "source", free = ["C"], mean = true })",
                                                 40, 300, dir) + R"toml(fit = { freq = [0.5, 0.75] }
[[splits]]
name = "meaned"
models = ["held"]
fit = { freq = 1 }
)toml");
  const auto run = run_dampbench(fmt::format("run {} -o {} --quiet --fresh", (dir / "s.toml").string(), (dir / "out").string()));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const auto table = run_dampbench(fmt::format("table {} --kind params --format json", (dir / "out" / "store.sqlite").string()));
  ASSERT_EQ(table.exit_code, 0) << table.output;
  const auto source_K1 = params_row(table.output, "params_source_source", "K1");  // kN/mm
  ASSERT_EQ(source_K1.size(), 2u) << table.output;
  EXPECT_NEAR(source_K1.at("a_soft"), 3.0, 0.05);  // one sinusoid determines K1 - m·ω², not each (m up to 2000 kg)
  EXPECT_NEAR(source_K1.at("b_stiff"), 5.0, 0.05);
  const auto held_C = params_row(table.output, "params_held_meaned", "C");
  ASSERT_EQ(held_C.size(), 1u) << table.output;
  EXPECT_NEAR(held_C.at("c_held"), 1.5 * C, 0.01 * C);  // found in C's own box (the held law model's table is in SI)
  const double K1_mean = 0.5 * (source_K1.at("a_soft") + source_K1.at("b_stiff")) * 1e6;  // SI, as the laws row
  EXPECT_NE(table.output.find(fmt::format("K1={:.4f}", K1_mean).substr(0, 8)), std::string::npos) << table.output;
  const auto refused = [&](const std::string& hold) {
    testing::write_text(dir / "bad.toml", hold_sweep(hold, 10, 10, dir));
    return run_dampbench(fmt::format("run {} -o {} --quiet --fresh", (dir / "bad.toml").string(), (dir / "bad").string()));
  };
  const auto windowed = refused(R"({ from = "source", split = "source", free = ["C"], mean = true, first = 0.5 })");
  EXPECT_NE(windowed.exit_code, 0);
  EXPECT_NE(windowed.output.find("mean = true holds to the means over the split's fit sets and leaves the free parameters "
                                 "their own bounds: drop first, next and order"),
            std::string::npos)
      << windowed.output;
}

// A hold that names no model the split fits, or a window without its order, is refused before anything runs.
TEST(SweepHold, AHoldThatCannotBeFollowedIsRefusedBeforeAnythingRuns) {
  const fs::path dir = testing::test_temp_dir("sweeprun");
  write_viscous_elastic(dir / "data" / "a.csv", 8e5, 0.5);
  auto refused = [&](const std::string& hold) {
    testing::write_text(dir / "s.toml", hold_sweep(hold, 10, 10, dir));
    const auto r = run_dampbench(fmt::format("run {} -o {} --quiet --fresh", (dir / "s.toml").string(), (dir / "out").string()));
    EXPECT_NE(r.exit_code, 0) << hold;
    return r.output;
  };
  EXPECT_NE(refused(R"({ from = "nobody", split = "source", free = ["C"] })").find("no model named 'nobody'"), std::string::npos);
  EXPECT_NE(refused(R"({ from = "held", split = "source", free = ["C"] })").find("cannot hold to its own fit"), std::string::npos);
  EXPECT_NE(refused(R"({ from = "source", split = "nosuch", free = ["C"] })").find("no split named 'nosuch'"), std::string::npos);
  EXPECT_NE(refused(R"({ from = "source", split = "source", free = ["Q"] })").find("hold.free names 'Q'"), std::string::npos);
  EXPECT_NE(refused(R"({ from = "source", split = "source", free = ["C"], next = 0.2 })").find("go together"),
            std::string::npos);
}

// The landscape table (fdsp Fig. 4) on a linear viscous record, F = c·v: of_sq of fvd.linear_viscous is
// ((c − C)/c)² in C (hand-computed: the mass term is orthogonal to v over whole cycles), so its second difference
// along C on a 5-point grid of ±40 % is 2·(0.2·C_best/c)² ≈ 0.08 wherever the grid lies; the centre is the best run.
TEST(SweepLandscape, AQuadraticObjectiveHasTheHandComputedSecondDifference) {
  const fs::path dir = testing::test_temp_dir("sweeprun");
  const double c = 2e4, w = 2 * std::numbers::pi;
  std::string csv = "# operating: freq=1\nt[s],x[mm],F[N]\n";
  for (int k = 0; k < 401; ++k) {
    const double t = 2.0 * k / 400;
    csv += fmt::format("{:.12g},{:.12g},{:.12g}\n", t, 10 * std::sin(w * t), c * 0.01 * w * std::cos(w * t));
  }
  testing::write_text(dir / "data" / "viscous.csv", csv);
  const std::string head = fmt::format(R"toml(name = "landscape"
runs = 2
metric = "of_sq"
models = ["fvd.linear_viscous"]
[optimizer]
name = "de"
population = 20
iterations = 100
[[datasets]]
name = "d"
glob = "{}/data/*.csv"
[[tables]]
kind = "landscape"
)toml",
                                       dir.string());
  testing::write_text(dir / "s.toml", head + "params = [\"C\", \"m\"]\nrange = 0.4\npoints = 5\n");
  const auto run = run_dampbench(fmt::format("run {} -o {} --quiet --fresh", (dir / "s.toml").string(), (dir / "out").string()));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const auto out = run_dampbench(fmt::format("table {} --kind sweep --format json", (dir / "out" / "store.sqlite").string()));
  ASSERT_EQ(out.exit_code, 0) << out.output;
  const nlohmann::json tables = nlohmann::json::parse(out.output);
  const nlohmann::json* grid = nullptr;
  const nlohmann::json* convexity = nullptr;
  for (const auto& t : tables.at("tables")) {
    if (t.at("id") == "landscape_fvd.linear_viscous_viscous") grid = &t;
    if (t.at("id") == "landscape_fvd.linear_viscous_viscous_convexity") convexity = &t;
  }
  ASSERT_TRUE(grid && convexity) << out.output;
  ASSERT_EQ(grid->at("rows").size(), 5u);
  ASSERT_EQ(grid->at("rows").at(0).size(), 6u);  // the C value, then 5 values of m
  const double best_C = grid->at("rows").at(2).at(0).get<double>();
  EXPECT_NEAR(best_C, c, 0.01 * c);
  const double along_C = convexity->at("rows").at(0).at(1).get<double>();
  EXPECT_NEAR(along_C, 2 * std::pow(0.2 * best_C / c, 2), 0.02 * 0.08) << out.output;
  // The centre is the best run's own objective, bit for bit (the same lane arithmetic as the fit's).
  const auto runs = run_dampbench(fmt::format("table {} --kind runs --format json", (dir / "out" / "store.sqlite").string()));
  const double best = nlohmann::json::parse(runs.output).at("tables").at(0).at("rows").at(0).at(3).get<double>();
  EXPECT_EQ(grid->at("rows").at(2).at(3).get<double>(), best) << runs.output;
  // A landscape without its two parameters, or with an even grid, is refused before anything runs.
  for (const auto& [entry, message] : {std::pair{"params = [\"C\"]", "needs params"}, {"params = [\"C\", \"m\"]\npoints = 4", "odd whole number"}}) {
    testing::write_text(dir / "bad.toml", head + entry + "\n");
    const auto bad = run_dampbench(fmt::format("run {} -o {} --quiet --fresh", (dir / "bad.toml").string(), (dir / "bad").string()));
    EXPECT_NE(bad.exit_code, 0);
    EXPECT_NE(bad.output.find(message), std::string::npos) << bad.output;
  }
}

// Identifiability in the sweep tables. fvd.gv_linear_elastic on one sine cannot tell the mass from
// the stiffness (m·a = −mω²x: only K1 − mω² is determined), so both are marked ‡ in the params table and the
// relative standard errors say why; on a two-frequency record of the same model nothing is marked. The store
// keeps the evidence (read back equal to what the runner computed: the verify test compares it bit for bit).
TEST(SweepIdentifiability, ParamsTableMarksATradeOffAndNotASeparableFit) {
  const fs::path dir = testing::test_temp_dir("sweeprun");
  write_record(dir / "data" / "one_sine.csv", "", 0.01, 1, 301);
  {
    const Model& model = find_model("fvd.gv_linear_elastic");
    Dataset d = testing::two_sine_record(600, 250.0);
    d.F_N = model.simulate(std::vector<double>{300.0, 8.2e5, 0.3, 4e6}, prepare_signals(d));
    std::string csv = "t[s],x[m],F[N]\n";
    for (std::size_t k = 0; k < d.F_N.size(); ++k) csv += fmt::format("{:.17g},{:.17g},{:.17g}\n", d.t_s[k], d.x_m[k], d.F_N[k]);
    testing::write_text(dir / "data" / "two_sine.csv", csv);
  }
  const auto table = sweep_table(dir, "fvd.gv_linear_elastic", 2, 30, 150, "params");
  ASSERT_EQ(table.exit_code, 0) << table.output;
  // Rows "m,kg,<one_sine>,<two_sine>" and "K1,N/m,...": conditions in file order (one_sine, two_sine).
  auto row = [&](const std::string& name) {
    std::istringstream in(table.output);
    for (std::string line; std::getline(in, line);)
      if (line.rfind(name + ",", 0) == 0) return line;
    return std::string("(no row " + name + ")");
  };
  auto cells = [](const std::string& line) {
    std::vector<std::string> out;
    std::istringstream in(line);
    for (std::string c; std::getline(in, c, ',');) out.push_back(c);
    return out;
  };
  for (const std::string name : {"m", "K1"}) {
    const auto c = cells(row(name));
    ASSERT_EQ(c.size(), 4u) << table.output;
    EXPECT_NE(c[2].find("‡"), std::string::npos) << name << " on one sine: " << table.output;
    EXPECT_EQ(c[3].find("‡"), std::string::npos) << name << " on two sines: " << table.output;
  }
  EXPECT_EQ(cells(row("C"))[3].find("‡"), std::string::npos) << table.output;
  EXPECT_NE(table.output.find("not identifiable"), std::string::npos) << table.output;  // the note and the s.e. table

  const Store store = Store::open((dir / "out" / "store.sqlite").string());
  for (const GroupRecord& g : store.groups()) {
    ASSERT_TRUE(g.identifiability.has_value());
    EXPECT_EQ(g.identifiability->std_error.size(), 4u);
    EXPECT_EQ(g.identifiability->correlation.size(), 4u);
  }
}

TEST(ProgressBar, Renders) {
  EXPECT_EQ(ProgressBar::render(25, 100, 1.5e6, 125, 10), "[###       ] 25/100 tasks  25%  1.5e+06 evals/s  ETA 2m05s");
  EXPECT_EQ(format_duration(3725), "1h02m");
  EXPECT_EQ(format_duration(std::nan("")), "--");
  ProgressBar off(true, 10, 0);  // stderr is not a terminal under ctest
  EXPECT_FALSE(off.active());
}

// ---- the executable: interruptions, refusal, verify, tables ---------------------------------------

class ExeSweep : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::test_temp_dir("sweeprun");
    // 8 records x 4 models = 32 groups of ~3e7 candidate-samples: long enough to interrupt on a fast machine.
    for (int i = 0; i < 8; ++i)
      write_record(dir_ / "data" / fmt::format("t{}.csv", i), fmt::format("amp={},freq={}", 0.01 + 0.002 * i, 0.5 + 0.25 * i),
                   0.01 + 0.002 * i, 0.5 + 0.25 * i, 3000);
    spec_ = dir_ / "sweep.toml";
    write_spec(4);
  }
  void write_spec(int runs) {
    testing::write_text(spec_, fmt::format(R"toml(name = "kill"
seed = 11
runs = {}
models = ["fvd.linear_viscous", "fvd.generalized_viscous", "fvd.gv_linear_elastic", "fvd.gv_quadratic_elastic"]
[optimizer]
name = "pso"
population = 40
iterations = 60
[[datasets]]
name = "tests"
glob = "{}/data/*.csv"
)toml",
                             runs, dir_.string()));
  }
  std::string args(const fs::path& store) const {
    return fmt::format("run {} --store {} -o {} --quiet --threads 2", spec_.string(), store.string(), (dir_ / "out").string());
  }
  fs::path dir_;
  fs::path spec_;
};

TEST_F(ExeSweep, InterruptedAndKilledSweepResumesBitIdentical) {
  const fs::path store = dir_ / "resumed.sqlite";
  const std::vector<std::string> argv{spec_.string(), "--store", store.string(), "-o", (dir_ / "out").string(), "--quiet",
                                      "--threads", "2"};
  // 1. Ctrl-C after the first stored group: the groups in flight finish, the run ends with 130, the store is valid.
  pid_t pid = start_run(argv);
  ASSERT_TRUE(wait_for_groups(pid, store, 1)) << "the sweep ended before it could be interrupted";
  kill(pid, SIGINT);
  EXPECT_EQ(wait_exit(pid), 130);
  const long long after_interrupt = stored_groups(store);
  EXPECT_GE(after_interrupt, 1);
  EXPECT_LT(after_interrupt, 32);
  EXPECT_EQ(Store::open(store.string()).stored_groups(), after_interrupt);

  // 2. Resume, then SIGKILL once two more groups are stored: at most the groups in flight are lost.
  pid = start_run(argv);
  ASSERT_TRUE(wait_for_groups(pid, store, after_interrupt + 2)) << "the sweep ended before it could be killed";
  kill(pid, SIGKILL);
  EXPECT_EQ(wait_exit(pid), 128 + SIGKILL);
  const long long after_kill = stored_groups(store);
  EXPECT_GE(after_kill, after_interrupt + 2);
  EXPECT_LT(after_kill, 32) << "the kill came too late to test a resume";

  RecordProperty("groups_after_sigint", static_cast<int>(after_interrupt));
  RecordProperty("groups_after_sigkill", static_cast<int>(after_kill));
  std::cout << "stored after Ctrl-C: " << after_interrupt << ", after SIGKILL: " << after_kill << " of 32 groups\n";

  // 3. Resume to the end; 4. an uninterrupted run elsewhere; every stored number must agree.
  auto r = run_dampbench(args(store));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find(fmt::format("{} from the store", after_kill)), std::string::npos) << r.output;
  const fs::path fresh = dir_ / "fresh.sqlite";
  r = run_dampbench(args(fresh));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("candidate-samples/s"), std::string::npos);
  expect_same_results(store.string(), fresh.string());
}

TEST_F(ExeSweep, AStoreKeepsItsVectorLevel) {
  // The vector level is part of the build flags (engine/kernels/isa.hpp): a store written with one level is
  // resumed with that level only, and verify re-runs it with the store's level, bit for bit. Bouc–Wen: its
  // state carries libmvec's last-bit differences forward, so the levels give different fits (checked first).
  if (supported_isas().size() < 2) GTEST_SKIP() << "one vector level on this machine and build (" << isa_summary() << ")";
  unsetenv("DAMPBENCH_ISA");
  const std::string low(isa_name(supported_isas().front())), best(isa_name(best_isa()));
  {  // The premise: this build's kernels give different bits at the two levels. A build whose lane loops are not
     // vectorized (the sanitizer build, -O2) calls scalar exp and log at every level and gives the same bits.
    const Isa before = active_isa();
    const Model& model = find_model("mrd.bouc_wen");
    const Signals data = bench_record(model, 2049, 1.0, 1024.0);
    const CandidateBatch candidates = bench_candidates(model, 1, 3);
    select_isa(supported_isas().front());
    const auto at_low = model.simulate(candidates.candidate(0), data);
    select_isa(best_isa());
    const auto at_best = model.simulate(candidates.candidate(0), data);
    select_isa(before);
    if (at_low == at_best)
      GTEST_SKIP() << "this build's Bouc-Wen kernel gives the same bits at " << low << " and " << best
                   << " (lane loops not vectorized, e.g. the sanitizer build): the level cannot be seen in a store";
  }
  testing::write_text(spec_, fmt::format(R"toml(name = "levels"
runs = 2
models = ["mrd.bouc_wen"]
[optimizer]
population = 10
iterations = 8
[[datasets]]
name = "tests"
files = ["{0}/data/t0.csv"]
)toml",
                           dir_.string()));
  const fs::path store = dir_ / "low.sqlite", other = dir_ / "best.sqlite";
  auto r = run_dampbench("--isa " + low + " " + args(store));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(Store::open(store.string()).header().build_flags.find(",isa=" + low), std::string::npos);
  r = run_dampbench(args(other));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::vector<std::string> names;
  for (const auto& p : find_model("mrd.bouc_wen").parameters()) names.push_back(p.name);
  ASSERT_FALSE(compare_records(*Store::open(store.string()).group(0), *Store::open(other.string()).group(0), names).empty())
      << "the fit came out the same bits at " << low << " and " << best << ": this test cannot see the level";

  r = run_dampbench(args(store));  // resumed at the CPU's best level: refused, naming the store's level
  EXPECT_EQ(r.exit_code, 4) << r.output;
  EXPECT_NE(r.output.find("isa=" + best), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("--isa " + low), std::string::npos) << r.output;
  r = run_dampbench("--isa " + low + " " + args(store));
  EXPECT_EQ(r.exit_code, 0) << r.output;
  r = run_dampbench(args(store) + " --isa " + low);  // after the subcommand too
  EXPECT_EQ(r.exit_code, 0) << r.output;

  r = run_dampbench("verify " + store.string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("verify re-runs them with " + low), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("every stored number identical bit for bit"), std::string::npos) << r.output;
  r = run_dampbench("verify " + store.string() + " --isa " + best);  // the user's level is kept: the bits differ
  EXPECT_NE(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("verify re-runs them with " + best + " as --isa or DAMPBENCH_ISA asks"), std::string::npos)
      << r.output;

  r = run_dampbench("--isa avx1024 " + args(store));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--isa: expected one of"), std::string::npos) << r.output;
  setenv("DAMPBENCH_ISA", "avx1024", 1);
  r = run_dampbench("models");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("DAMPBENCH_ISA: expected one of"), std::string::npos) << r.output;
  setenv("DAMPBENCH_ISA", low.c_str(), 1);
  r = run_dampbench("--version");
  unsetenv("DAMPBENCH_ISA");
  EXPECT_NE(r.output.find("vector kernels " + low), std::string::npos) << r.output;
  r = run_dampbench("--version");
  EXPECT_NE(r.output.find("vector kernels " + best), std::string::npos) << r.output;
}

TEST_F(ExeSweep, ChangedSpecIsRefusedAndVerifyDetectsAlteredNumbers) {
  testing::write_text(spec_, fmt::format(R"toml(name = "small"
runs = 2
models = ["fvd.generalized_viscous"]
tables = ["runs", "errors", "bootstrap"]
[optimizer]
population = 10
iterations = 8
[[datasets]]
name = "tests"
files = ["{0}/data/t0.csv", "{0}/data/t1.csv"]
)toml",
                           dir_.string()));
  const fs::path store = dir_ / "s.sqlite";
  auto r = run_dampbench(args(store));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* f : {"runs_fvd.generalized_viscous.csv", "errors.csv", "tables.md", "summary.md"})
    EXPECT_TRUE(fs::exists(dir_ / "out" / f)) << f;

  r = run_dampbench("verify " + store.string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("verify: 2 task groups (4 runs) re-run, every stored number identical bit for bit"), std::string::npos)
      << r.output;

  // Tables from the store, in every format.
  r = run_dampbench("table " + store.string() + " --kind runs --format json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto j = nlohmann::json::parse(r.output);
  EXPECT_EQ(j.at("tables")[0].at("rows").size(), 2u);
  for (const char* f : {"md", "csv", "latex"}) EXPECT_EQ(run_dampbench("table " + store.string() + " --kind params --format " + f).exit_code, 0) << f;
  r = run_dampbench("table " + store.string() + " --kind nope");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("--kind: unknown table kind 'nope' (known: runs"), std::string::npos) << r.output;

  // One altered bit of one stored number: verify names it and fails.
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(store.string().c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db, "UPDATE runs SET best_value = best_value * (1 + 1e-12) WHERE grp = 1 AND run = 0", nullptr,
                         nullptr, nullptr),
            SQLITE_OK);
  sqlite3_close(db);
  r = run_dampbench("verify " + store.string() + " --sample 2");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("DIFFERENT: task group 1 (fvd.generalized_viscous on t1, pso, of_abs)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("run 0 best_value: stored 0x"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("1 of 2 re-run task groups differ"), std::string::npos) << r.output;

  // The same store with another spec is refused before anything runs; --fresh starts over.
  std::string text;
  {
    std::ifstream in(spec_);
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  text.replace(text.find("runs = 2"), 8, "runs = 3");
  testing::write_text(spec_, text);
  r = run_dampbench(args(store));
  EXPECT_EQ(r.exit_code, 4) << r.output;  // store
  EXPECT_NE(r.output.find("belongs to another sweep spec ('small' from"), std::string::npos) << r.output;
  r = run_dampbench(args(store) + " --fresh");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("2 task groups, 6 tasks (2 run now, 0 from the store, 0 failed)"), std::string::npos) << r.output;
}

TEST_F(ExeSweep, ARunRemovesTheOutputsOfThePreviousRunThatItDoesNotWriteAgain) {
  const auto spec = [&](const char* tables) {
    testing::write_text(spec_, fmt::format(R"toml(name = "small"
runs = 2
models = ["fvd.linear_viscous"]
tables = [{}]
[optimizer]
population = 8
iterations = 4
[[datasets]]
name = "tests"
files = ["{}/data/t0.csv"]
)toml",
                             tables, dir_.string()));
  };
  const fs::path store = dir_ / "s.sqlite", out = dir_ / "out";
  spec(R"("runs", "errors")");
  auto r = run_dampbench(args(store));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ASSERT_TRUE(fs::exists(out / "errors.csv"));
  ASSERT_TRUE(fs::exists(out / "report.html"));
  std::ifstream manifest(out / "outputs.txt");
  const std::string listed((std::istreambuf_iterator<char>(manifest)), {});
  EXPECT_NE(listed.find("\nerrors.csv\n"), std::string::npos) << listed;
  EXPECT_NE(listed.find("\nreport.html\n"), std::string::npos) << listed;

  // The manifest as an editor on another system might leave it (CRLF, a trailing space, "./"), with lines that
  // must never remove anything: a user's file and a store-like file in the folder, files outside it by "..", by
  // an absolute path and through a symlinked subfolder.
  testing::write_text(out / "my_notes.txt", "mine\n");
  testing::write_text(out / "fake.sqlite", "a store\n");
  testing::write_text(dir_ / "outside.csv", "not an output\n");
  testing::write_text(dir_ / "elsewhere" / "linked.csv", "not an output\n");
  fs::create_directory_symlink(dir_ / "elsewhere", out / "link");
  std::ofstream(out / "outputs.txt", std::ios::trunc)
      << "# header\r\nerrors.csv\r\n./runs_fvd.linear_viscous.csv\r\nreport.html \r\ntables.md\r\nmy_notes.txt\r\n"
      << "fake.sqlite\r\n../outside.csv\r\n" << fs::absolute(dir_ / "outside.csv").string() << "\r\nlink/linked.csv\r\n";

  spec(R"("runs")");
  r = run_dampbench(args(store) + " --fresh --no-report");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(fs::exists(out / "runs_fvd.linear_viscous.csv"));
  EXPECT_TRUE(fs::exists(out / "tables.md"));
  EXPECT_FALSE(fs::exists(out / "errors.csv"));
  EXPECT_FALSE(fs::exists(out / "report.html"));
  EXPECT_NE(r.output.find("removed 2 file(s) of the previous run"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(out / "my_notes.txt"));
  EXPECT_TRUE(fs::exists(out / "fake.sqlite"));
  EXPECT_TRUE(fs::exists(dir_ / "outside.csv"));
  EXPECT_TRUE(fs::exists(dir_ / "elsewhere" / "linked.csv"));
  EXPECT_TRUE(fs::exists(store));
}

TEST_F(ExeSweep, NothingStartsUntilTheWholeFileIsValid) {
  testing::write_text(spec_, fmt::format("name = \"bad\"\nmodels = [\"fvd.linear_viscous\"]\n[[datasets]]\nname = \"t\"\nglob = \"{}/data/*.csv\"\n"
                           "[[tables]]\nkind = \"plots\"\n",
                           dir_.string()));
  const fs::path store = dir_ / "never.sqlite";
  const auto r = run_dampbench(args(store));
  EXPECT_EQ(r.exit_code, 3);  // input data: the sweep file
  EXPECT_NE(r.output.find("sweep.toml:6: key 'tables[0]': unknown table kind 'plots'"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(store));
}

}  // namespace
}  // namespace dampbench::sweep
