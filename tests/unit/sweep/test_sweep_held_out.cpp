// Held-out evaluation in sweeps (engine/sweep/spec.hpp). A model with laws = "auto" (engine/fit/law_selection.hpp):
// on synthetic records generated from known laws, its group chooses the true families, recovers their coefficients,
// predicts a setting it did not fit, stores its laws beside its parameters, and gives the same laws and bits as `fit
// --laws auto` on the same records; a spec that would have it choose laws on one record or under the automatic budget
// is refused before anything runs. A split with folds: one fit set per left-out setting or value, fitted on the others
// and predicting it with the predict datasets of that value.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "engine/common/error.hpp"
#include "engine/model/metrics.hpp"
#include "engine/record/csv_loader.hpp"
#include "engine/record/excitation.hpp"
#include "engine/sweep/plan.hpp"
#include "engine/sweep/schedule.hpp"
#include "engine/sweep/spec.hpp"
#include "engine/sweep/runner.hpp"
#include "engine/sweep/store.hpp"
#include "engine/sweep/store/verify_diff.hpp"
#include "models/registry.hpp"
#include "tests/sweep_test_support.hpp"
#include "tests/test_support.hpp"

namespace dampbench::sweep {
namespace {

namespace fs = std::filesystem;
using testing::run_dampbench;
using testing::run_dampbench_json;

/// A Bingham record (F = f_c·sgn(v) + c0·v + f0) on a sine, with f_c = hill(I,2) (60, 500, 0.6 A), c0 linear in I
/// (1000 + 2000·I) and f0 = 5 N shared, written with its operating variables.
fs::path write_bingham_record(const fs::path& dir, double amp, double freq, double current) {
  SineSpec spec;
  spec.amplitude_m = amp, spec.freq_hz = freq, spec.cycles = 2, spec.fs_hz = 400 * freq;
  Dataset d = make_sine(spec);
  const double f_c = 60 + 500 * current * current / (0.36 + current * current), c0 = 1000 + 2000 * current;
  d.operating["I"] = current;
  d.F_N = find_model("mrd.bingham").simulate(std::vector<double>{f_c, c0, 5.0}, prepare_signals(d));
  const fs::path p = dir / fmt::format("{}mm{}Hz{}A.csv", amp * 1e3, freq, current);
  std::ofstream out(p);
  out << fmt::format("# operating: I={},amp={},freq={}\nt[s],x[m],v[m/s],F[N]\n", current, amp, freq);
  for (std::size_t k = 0; k < d.F_N.size(); ++k)
    out << fmt::format("{:.17g},{:.17g},{:.17g},{:.17g}\n", d.t_s[k], d.x_m[k], d.v_m_s[k], d.F_N[k]);
  return p;
}

constexpr const char* kGaLm = "[optimizer]\nname = \"ga-lm\"\npopulation = 24\niterations = 30\n";

/// A sweep of the records in `data`: one Bingham model with `laws` (and the model's further keys that may open
/// `optimizer`), `optimizer`, then `splits`.
std::string sweep_text(const std::string& laws, const fs::path& data, const std::string& splits,
                       const std::string& optimizer = kGaLm) {
  return fmt::format(R"toml(name = "held_out"
seed = 1
runs = 2
metric = "nrmse"
[[models]]
name = "bingham(damper)"
model = "mrd.bingham"
laws = "{}"
{}[[datasets]]
name = "d"
glob = "{}/*.csv"
{})toml",
                     laws, optimizer, data.string(), splits);
}

// narrow = { rounds } (the mfm paper's bound narrowing) in a sweep: the group fits each record alone twice, then
// searches the box their ranges give the laws' coefficients, and says so in its stored message. c0 is linear in I
// (1000 + 2000·I): its per-record fits span 1000-3000 N·s/m over 0-1 A, so its slope's bound is the true slope.
/// `dir/s.toml` run into `dir/out` (the run must succeed) and its store's groups.
std::vector<GroupRecord> run_groups(const fs::path& dir) {
  const auto run = run_dampbench(fmt::format("run {} -o {} --quiet --fresh", (dir / "s.toml").string(),
                                             (dir / "out").string()));
  EXPECT_EQ(run.exit_code, 0) << run.output;
  if (run.exit_code != 0) return {};
  return Store::open((dir / "out" / "store.sqlite").string()).groups();
}

TEST(SweepNarrow, AGroupSearchesTheBoxOfItsRecordsNarrowedFitsAndSaysSo) {
  const fs::path dir = testing::test_temp_dir("sweep_narrow");
  fs::create_directories(dir / "data");
  for (double I : {0.0, 0.5, 1.0}) write_bingham_record(dir / "data", 0.01, 1.0, I);
  std::ofstream(dir / "s.toml") << sweep_text("f_c=poly(I,1);c0=poly(I,1)", dir / "data",
                                              "[[splits]]\nname = \"damper\"\nby = \"all\"\n",
                                              std::string("narrow = { rounds = 2 }\n") + kGaLm);
  const auto groups = run_groups(dir);
  ASSERT_EQ(groups.size(), 1u);
  const GroupRecord& g = groups[0];
  ASSERT_FALSE(g.failed) << g.message;
  EXPECT_NE(g.message.find("bounds narrowed over 3 records in 2 rounds (failed records per round: 0, 0;"),
            std::string::npos)
      << g.message;
  long long run_evaluations = 0;
  for (const auto& r : g.run_results) run_evaluations += r.evaluations;
  EXPECT_GT(g.evaluations, run_evaluations);  // the rounds' per-record fits count as the group's
  const auto& best = g.run_results.at(static_cast<std::size_t>(g.best_run()));
  ASSERT_EQ(best.params.size(), 5u);  // f_c_I0, f_c_I1, c0_I0, c0_I1, f0
  EXPECT_NEAR(best.params[2], 1000.0, 20.0);
  EXPECT_NEAR(best.params[3], 2000.0, 40.0);
  EXPECT_LE(best.params[3], 2000.0 * (1 + 1e-6));  // inside the narrowed box: the slope of the per-record range
}

TEST(SweepLawsAuto, AGroupChoosesTheTrueLawsPredictsAndMatchesFitLawsAutoBitForBit) {
  const fs::path dir = testing::test_temp_dir("sweep_laws_auto");
  fs::create_directories(dir / "data");
  std::vector<std::string> train;
  for (auto [amp, freq] : {std::pair{0.01, 1.0}, {0.005, 2.0}, {0.02, 0.5}})
    for (double I : {0.0, 0.25, 0.5, 0.75, 1.0}) train.push_back(write_bingham_record(dir / "data", amp, freq, I).string());
  // in the sweep's order (a glob's files sorted by name): a joint fit sums its records' errors in their order
  std::sort(train.begin(), train.end());
  write_bingham_record(dir / "data", 0.015, 1.5, 0.6);  // a setting and a current it never fits
  std::ofstream(dir / "s.toml") << sweep_text("auto", dir / "data",
                                              "[[splits]]\nname = \"damper\"\nby = \"all\"\nfit = { freq = [1, 2, 0.5] }\n"
                                              "predict = { freq = 1.5 }\n");
  const auto groups = run_groups(dir);
  ASSERT_EQ(groups.size(), 1u);
  const GroupRecord& g = groups[0];
  ASSERT_FALSE(g.failed) << g.message;
  EXPECT_EQ(g.laws, "f_c=hill(I,2);c0=mono(I,0,1)");
  const auto& best = g.run_results.at(static_cast<std::size_t>(g.best_run()));
  ASSERT_EQ(best.params.size(), 6u);  // f_c: a, b, h; c0: two; f0
  const double truth[] = {60, 500, 0.6, 1000, 2000, 5};
  for (std::size_t j = 0; j < best.params.size(); ++j) EXPECT_NEAR(best.params[j], truth[j], 0.02 * truth[j]) << j;
  bool predicted = false;
  for (const auto& m : g.dataset_metrics)
    if (m.predicted && m.run == g.best_run()) {
      predicted = true;
      EXPECT_LT(m.metrics[static_cast<std::size_t>(Metric::nrmse)], 0.01);  // the true laws predict the new setting
    }
  EXPECT_TRUE(predicted);

  // `fit --laws auto` on the same records and budget: one piece of code, so the same laws and the same bits
  const auto fit = run_dampbench_json(fmt::format(
      "fit --model mrd.bingham --laws auto --data {} --optimizer ga-lm --pop 24 --iters 30 --runs 2 --metric nrmse "
      "--seed 1 --format json",
      fmt::join(train, " ")));
  ASSERT_EQ(fit.exit_code, 0) << fit.output << fit.errors;
  const auto j = nlohmann::json::parse(fit.output);
  EXPECT_EQ(j.at("laws").get<std::string>(), g.laws);
  const auto& each = j.at("run_results");
  ASSERT_EQ(each.size(), g.run_results.size());
  for (std::size_t r = 0; r < each.size(); ++r)
    EXPECT_EQ(each[r].at("best_value").get<double>(), g.run_results[r].best_value) << r;
  // the group's evaluations are the whole group's: the records' own fits before the joint fit's runs
  long long joint = 0;
  for (const auto& result : g.run_results) joint += result.evaluations;
  const long long own_fits = j.at("law_selection").at("evaluations").get<long long>();
  EXPECT_GE(own_fits, static_cast<long long>(train.size()) * 2 * 24 * 31);  // each record: 2 runs of 24 × (30 + 1)
  EXPECT_EQ(g.evaluations, joint + own_fits);

  // the params table names the group's laws and its law model's coefficients
  const auto table = run_dampbench(fmt::format("table {} --kind params --format csv", (dir / "out" / "store.sqlite").string()));
  ASSERT_EQ(table.exit_code, 0) << table.output;
  EXPECT_NE(table.output.find("laws,,\"f_c=hill(I,2);c0=mono(I,0,1)\""), std::string::npos) << table.output;
  EXPECT_NE(table.output.find("f0,"), std::string::npos) << table.output;
}

/// The spec of the laws = "auto" model with its split and optimizer replaced.
std::string sweep_with(const std::string& split, const std::string& optimizer) {
  return sweep_text("auto", "/nonexistent", split, optimizer);
}

std::string refusal(const std::string& text) {
  SpecOptions o;
  o.check_files = false;
  try {
    (void)parse_sweep(text, "s.toml", o);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(SweepLawsAuto, ASpecThatWouldChooseLawsOnOneRecordOrUnderTheAutomaticBudgetIsRefused) {
  const std::string fixed = "[optimizer]\nname = \"ga-lm\"\npopulation = 24\niterations = 30\n";
  const std::string all = "[[splits]]\nname = \"damper\"\nby = \"all\"\n";
  EXPECT_EQ(refusal(sweep_with(all, fixed)), "(accepted)");
  EXPECT_NE(refusal(sweep_with("", fixed)).find("the default split (no [[splits]]) fits each dataset alone"), std::string::npos)
      << refusal(sweep_with("", fixed));
  EXPECT_NE(refusal(sweep_with("[[splits]]\nname = \"each\"\n", fixed)).find("split 'each' fits each dataset alone"),
            std::string::npos);
  const std::string automatic = refusal(sweep_with(all, "[optimizer]\nname = \"ga-lm\"\n"));
  EXPECT_NE(automatic.find("optimizer 'ga-lm' has the automatic budget"), std::string::npos) << automatic;
  std::string with_start = sweep_with(all, fixed);
  with_start.insert(with_start.find("laws = \"auto\"") + 14, "start = \"per-file\"\n");
  EXPECT_NE(refusal(with_start).find("always starts from the records' own fits"), std::string::npos) << refusal(with_start);
  std::string with_bounds = sweep_with(all, fixed);
  with_bounds.insert(with_bounds.find("laws = \"auto\"") + 14, "bounds = \"f0=0:10\"\n");
  EXPECT_NE(refusal(with_bounds).find("bounds with laws auto"), std::string::npos) << refusal(with_bounds);
}

/// Bingham records of three settings at five currents; a split of them with `folds` and the true laws.
fs::path folds_sweep(const std::string& name, const std::string& folds,
                     const std::string& laws = "f_c=hill(I,2);c0=mono(I,0,1)") {
  const fs::path dir = testing::test_temp_dir(name);
  fs::create_directories(dir / "data");
  for (auto [amp, freq] : {std::pair{0.01, 1.0}, {0.005, 2.0}, {0.02, 0.5}})
    for (double I : {0.0, 0.25, 0.5, 0.75, 1.0}) write_bingham_record(dir / "data", amp, freq, I);
  std::ofstream(dir / "s.toml") << sweep_text(laws, dir / "data",
                                              fmt::format("[[splits]]\nname = \"folds\"\nfolds = \"{}\"\n"
                                                          "fit = {{ I = [0, 0.5, 1] }}\npredict = {{ I = [0.25, 0.75] }}\n",
                                                          folds));
  return dir;
}

/// "name+name": the datasets of a fit set, sorted.
std::string names(const PartPlan& part, std::vector<int> ds) {
  std::vector<std::string> n;
  for (int d : ds) n.push_back(part.spec->datasets[d].name);
  std::sort(n.begin(), n.end());
  return fmt::format("{}", fmt::join(n, "+"));
}

TEST(SweepFolds, LeavingASettingOutFitsTheOthersAndPredictsEveryCurrentOfIt) {
  const fs::path dir = folds_sweep("sweep_folds_setting", "leave-setting");
  const Plan plan(load_sweep((dir / "s.toml").string()), testing::csv_loader());
  const PartPlan& part = plan.parts().at(0);
  const auto& fitsets = part.splits.at(0).fitsets;
  ASSERT_EQ(fitsets.size(), 3u);
  // folds sorted by the setting they leave out: amp 0.005, 0.01, 0.02
  EXPECT_EQ(fitsets[0].label, "amp=0.005,freq=2");
  EXPECT_EQ(names(part, fitsets[0].predict), "5mm2Hz0.25A+5mm2Hz0.5A+5mm2Hz0.75A+5mm2Hz0A+5mm2Hz1A");
  EXPECT_EQ(names(part, fitsets[0].fit), "10mm1Hz0.5A+10mm1Hz0A+10mm1Hz1A+20mm0.5Hz0.5A+20mm0.5Hz0A+20mm0.5Hz1A");
  EXPECT_EQ(fitsets[2].label, "amp=0.02,freq=0.5");

  const auto groups = run_groups(dir);
  ASSERT_EQ(groups.size(), 3u);
  for (const GroupRecord& g : groups) {
    ASSERT_FALSE(g.failed) << g.message;
    int predicted = 0;
    for (const auto& m : g.dataset_metrics)
      if (m.predicted && m.run == g.best_run()) {
        ++predicted;  // the true laws, fitted on two settings, predict the third at every current
        EXPECT_LT(m.metrics[static_cast<std::size_t>(Metric::nrmse)], 0.01) << g.fitset << " " << m.dataset;
      }
    EXPECT_EQ(predicted, 5) << g.fitset;
  }
}

TEST(SweepFolds, GroupsThatChooseLawsShareTheRecordsOwnFitsWithTheSameBits) {
  const fs::path dir = folds_sweep("sweep_folds_shared_fits", "leave-setting", "auto");
  const Plan plan(load_sweep((dir / "s.toml").string()), testing::csv_loader());
  ASSERT_EQ(plan.groups(), 3);  // each fits the 0, 0.5 and 1 A records of two settings
  RecordFitCache shared;
  for (long long i = 0; i < plan.groups(); ++i) {
    const GroupRecord alone = run_group(plan, i);
    const GroupRecord sharing = run_group(plan, i, &shared);
    ASSERT_FALSE(alone.failed) << alone.message;
    const auto diff = compare_records(alone, sharing, {});
    EXPECT_TRUE(diff.empty()) << i << ": " << fmt::format("{}", fmt::join(diff, "; "));
    EXPECT_EQ(alone.evaluations, sharing.evaluations) << i;  // the fits it rests on count, whoever made them
  }
  EXPECT_EQ(shared.size(), 9u);  // each record fitted alone once, not once per group that fits it (18)
}

TEST(SweepFolds, LeavingACurrentOutPredictsOnlyThatCurrent) {
  const fs::path dir = folds_sweep("sweep_folds_current", "leave-one:I");
  const Plan plan(load_sweep((dir / "s.toml").string()), testing::csv_loader());
  const PartPlan& part = plan.parts().at(0);
  const auto& fitsets = part.splits.at(0).fitsets;
  ASSERT_EQ(fitsets.size(), 3u);  // the fit currents 0, 0.5, 1 A; 0.25 and 0.75 A are no fold's
  EXPECT_EQ(fitsets[1].label, "I=0.5");
  EXPECT_EQ(names(part, fitsets[1].predict), "10mm1Hz0.5A+20mm0.5Hz0.5A+5mm2Hz0.5A");
  EXPECT_EQ(fitsets[1].fit.size(), 6u);
}

/// The schedule hands out the largest groups first: a laws = "auto" group (each record's own fit, the choice and a
/// joint fit) outweighs a group fitting given laws of twice the base model's coefficients on the same records, and
/// so does a group that starts from its records' own fits.
TEST(SweepFolds, AGroupThatChoosesLawsOrFitsItsRecordsFirstIsEstimatedAsTheLargerJob) {
  const fs::path dir = folds_sweep("sweep_folds_cost", "leave-setting");
  const auto cost_of = [&](const std::string& laws, const std::string& extra) {
    std::string text = sweep_text(laws, dir / "data", "[[splits]]\nname = \"folds\"\nfolds = \"leave-setting\"\n");
    text.insert(text.find('\n', text.find("laws = ")) + 1, extra);
    std::ofstream(dir / "c.toml") << text;
    const Plan plan(load_sweep((dir / "c.toml").string()), testing::csv_loader());
    return estimated_cost(plan, plan.group(0));
  };
  const double given = cost_of("f_c=hill(I,2);c0=mono(I,0,1)", "");  // 6 coefficients, the base model's 3
  EXPECT_GT(cost_of("auto", ""), given);
  EXPECT_GT(cost_of("f_c=hill(I,2);c0=mono(I,0,1)", "start = \"per-file\"\n"), given);
}

TEST(SweepFolds, AnUnknownRuleOrFoldsBesideByEachAreRefused) {
  const auto fixed = [](const std::string& split) { return sweep_text("f_c=hill(I,2)", "/nonexistent", split); };
  EXPECT_NE(refusal(fixed("[[splits]]\nfolds = \"leave-two\"\n")).find("expected \"leave-setting\" or \"leave-one:VAR\""),
            std::string::npos);
  EXPECT_NE(refusal(fixed("[[splits]]\nfolds = \"leave-one:Q\"\n")).find("got 'leave-one:Q'"), std::string::npos);
  EXPECT_NE(refusal(fixed("[[splits]]\nby = \"each\"\nfolds = \"leave-setting\"\n")).find("by = \"all\" or none"),
            std::string::npos);
  EXPECT_EQ(refusal(fixed("[[splits]]\nfolds = \"leave-setting\"\n")), "(accepted)");
}

// Folds of a laws = "auto" model may choose different laws: the params table keeps each set of laws in a block of
// its own (their coefficients mean different things), a "-" in the groups of the other block. The store's groups are
// given two different sets of laws of six coefficients each, as two folds would choose them.
TEST(SweepLawsAuto, TheParamsTableKeepsGroupsWithDifferentLawsApart) {
  const fs::path dir = folds_sweep("sweep_laws_blocks", "leave-setting");
  const auto run = run_dampbench(fmt::format("run {} -o {} --quiet --fresh", (dir / "s.toml").string(),
                                             (dir / "out").string()));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::string store_path = (dir / "out" / "store.sqlite").string();
  {
    Store store = Store::open(store_path);
    const char* laws[] = {"f_c=hill(I,2);c0=mono(I,0,1)", "f_c=sat(I);c0=mono(I,0,1)", "f_c=sat(I);c0=mono(I,0,1)"};
    for (long long i = 0; i < 3; ++i) {
      GroupRecord g = *store.group(i);
      g.laws = laws[i];
      store.write(g);
    }
  }
  const auto table = run_dampbench(fmt::format("table {} --kind params --format csv", store_path));
  ASSERT_EQ(table.exit_code, 0) << table.output;
  EXPECT_NE(table.output.find("laws,,\"f_c=hill(I,2);c0=mono(I,0,1)\",-,-"), std::string::npos) << table.output;
  EXPECT_NE(table.output.find("laws,,-,\"f_c=sat(I);c0=mono(I,0,1)\",\"f_c=sat(I);c0=mono(I,0,1)\""), std::string::npos)
      << table.output;
  EXPECT_NE(table.output.find("f_c_Ih,A,"), std::string::npos) << table.output;  // hill's half-saturation current
}

}  // namespace
}  // namespace dampbench::sweep
