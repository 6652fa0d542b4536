// Sweep files (engine/sweep/spec.hpp) and their plans (engine/sweep/plan.hpp): every error names the file,
// line, key and what was expected; valid files give the models, datasets, splits and numbered task groups
// they describe; the spec hash ignores what does not change results.
#include "engine/sweep/spec.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <set>

#include <fmt/format.h>

#include "engine/record/csv_loader.hpp"
#include "engine/common/error.hpp"
#include "engine/sweep/plan.hpp"
#include "tests/sweep_test_support.hpp"
#include "tests/test_support.hpp"

namespace dampbench::sweep {
namespace {

namespace fs = std::filesystem;

/// A sine record with a Bingham-like force and "# operating:" variables.
void write_record(const fs::path& p, const std::string& operating, double amp = 0.01, double freq = 1) {
  std::string s = "# synthetic\n# operating: " + operating + "\nt[s],x[mm],F[N]\n";
  for (int k = 0; k <= 100; ++k) {
    const double t = k / (freq * 50.0), w = 2 * std::numbers::pi * freq;
    const double v = amp * w * std::cos(w * t);
    s += fmt::format("{:.9g},{:.9g},{:.9g}\n", t, 1e3 * amp * std::sin(w * t), 1000 * v + 50 * (v > 0 ? 1 : v < 0 ? -1 : 0));
  }
  testing::write_text(p, s);
}

/// The message of parsing `text` as dir/x.toml.
std::string spec_error(const fs::path& dir, const std::string& text) {
  testing::write_text(dir / "x.toml", text);
  return testing::error_of([&] { (void)load_sweep((dir / "x.toml").string()); });
}

const std::string kHead = "name = \"x\"\nmodels = [\"mrd.bingham\"]\n";
const std::string kData = "[[datasets]]\nname = \"a\"\nfile = \"a.csv\"\n";

class SpecErrors : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::test_temp_dir("spec");
    write_record(dir_ / "a.csv", "I=0");
  }
  void expect(const std::string& text, const std::string& message) {
    const std::string e = spec_error(dir_, text);
    EXPECT_NE(e.find(message), std::string::npos) << "expected: " << message << "\ngot: " << e;
  }
  fs::path dir_;
  std::string x() const { return (dir_ / "x.toml").string(); }
};

TEST_F(SpecErrors, NamesFileLineKeyAndExpectation) {
  expect("name = \"x\"\nmodels = [\"mrd.bingham\", \"mrd.nope\"]\n" + kData,
         x() + ":2: key 'models': unknown model 'mrd.nope' (known: fvd.linear_viscous");
  expect(kHead + "[optimizer]\nname = \"sa\"\n" + kData, x() + ":3: key 'optimizer': unknown optimizer 'sa' (known: pso");
  expect(kHead + "metric = \"r2\"\n" + kData, x() + ":3: key 'metric': unknown metric 'r2' (known: of_abs");
  expect(kHead + "runs = 0\n" + kData, x() + ":3: key 'runs': expected an integer >= 1, got 0");
  expect(kHead + "[optimizer]\npopulation = 1\n" + kData, x() + ":4: key 'optimizer.population': expected an integer >= 2, got 1");
  expect(kHead + "[[datasets]]\nname = \"a\"\nfile = \"missing.csv\"\n",
         x() + ":5: key 'datasets[0].file': cannot open data file '" + (dir_ / "missing.csv").string() + "'");
  expect(kHead + "[[datasets]]\nname = \"g\"\nglob = \"none/*.csv\"\n", "key 'datasets[0].glob': no file matches '");
  expect(kHead + kData + "[bounds]\n\"mrd.bingham\" = \"c0=5:1\"\n",
         x() + ":7: key 'mrd.bingham': bounds c0: lower bound 5 is greater than upper bound 1");
  expect("name = \"x\"\nmodels = [{ model = \"mrd.bingham\", bounds = \"q=1:2\" }]\n" + kData,
         "key 'models[0]': model mrd.bingham has no parameter 'q'");
  expect("name = \"x\"\nmodels = [{ model = \"mrd.bingham\", laws = \"c0=poly(Q,1)\" }]\n" + kData,
         "key 'models[0]': laws c0: unknown operating variable 'Q'");
  expect("name = \"x\"\nmodles = [\"mrd.bingham\"]\n" + kData, x() + ":2: key 'modles': unknown key (known here: name, title");
  expect(kHead + kData + "[[splits]]\ndatasets = [\"b\"]\n",
         x() + ":7: key 'splits[0].datasets': unknown dataset entry 'b' (known: a)");
  expect(kHead + kData + "[[splits]]\nby = [\"Q\"]\n", "key 'splits[0].by': unknown operating variable 'Q'");
  expect(kHead + kData + "[[splits]]\nfit = { T = 1 }\n", "key 'splits[0].fit.T': unknown condition (known: name, I, V, phi");
  expect(kHead + kData + "[[splits]]\nmodels = [\"mrd.spencer\"]\n", "key 'splits[0].models': unknown model 'mrd.spencer' (known: mrd.bingham)");
  expect(kHead + "tables = [\"plots\"]\n" + kData, x() + ":3: key 'tables[0]': unknown table kind 'plots' (known: runs");
  expect(kHead + kData + "[[regressions]]\nmodel = \"m\"\nlaws = \"c0=poly(I,1)\"\n",
         x() + ":7: key 'regressions[0].model': unknown model 'm' (known: mrd.bingham)");
  expect(kHead + kData + "[[regressions]]\nmodel = \"mrd.bingham\"\nlaws = \"c0=3\"\n",
         "a regression needs a law with coefficients, got a number");
  expect(kHead + "[[datasets]]\nname = \"a\"\nfile = \"a.csv\"\n[[datasets]]\nname = \"b\"\nfiles = [\"a.csv\"]\n",
         "key 'datasets[1].files': dataset name 'a' is already used by datasets[0]");
  expect("name = \"x\"\nmodels = [{ model = \"mrd.bingham\", optimizers = [\"ga\"] }]\n" + kData,
         "key 'models[0].optimizers': no optimizer labelled 'ga'");
  expect("name = \"x\"\nmodels = [{ model = \"mrd.spencer_freq\", laws = \"n=2\" }]\n" + kData,
         "key 'models[0]': laws on mrd.spencer_freq, itself a law model, are not supported: write every law on its "
         "base model mrd.spencer_voltage");
  expect("name = \"x\"\nmodels = [{ model = \"mrd.bingham\", laws = \"c0=poly(I,1)\", start = \"box\" }]\n" + kData,
         "key 'models[0].start': expected \"per-file\", got 'box'");
  expect("name = \"x\"\nmodels = [{ model = \"mrd.bingham\", start = \"per-file\" }]\n" + kData,
         "key 'models[0].start': start = \"per-file\" starts a law model from its records' own fits: it needs 'model' "
         "and 'laws'");
  const std::string narrow = "name = \"x\"\nmodels = [{ model = \"mrd.bingham\", laws = \"f_c=poly(I,1)\", narrow = ";
  expect(narrow + "{ rounds = 0 } }]\n" + kData,
         "key 'models[0].narrow.rounds': expected a whole number of rounds from 1 to 20");
  expect(narrow + "{ from = \"paper\" } }]\n" + kData,
         "key 'models[0].narrow.from': expected \"default\" (the model's box for the records) or \"wide\" ([-1e8, 1e8]), got "
         "'paper'");
  expect(narrow + "{ rounds = 2 }, bounds = \"c0=0:10\" }]\n" + kData,
         "key 'models[0].narrow': narrow needs a registered 'model' with its own 'laws' (not \"auto\"), and no start, "
         "hold or bounds: it makes the box and the start");
  expect("name = \"x\"\nmodels = [{ model = \"mrd.bingham\", laws = \"f_c=poly(I,2)\", narrow = {} }]\n" + kData,
         "key 'models[0].narrow': narrow: the law f_c=poly(I,2) has no box from a narrowed range (those that have one: "
         "free, poly(VAR,0), poly(VAR,1))");
  expect(narrow + "{ round = 2 } }]\n" + kData, "key 'models[0].narrow.round': unknown key (known here: rounds, from)");
  expect(kHead + "[[datasets]]\nname = \"a\"\nfile = \"a.csv\"\ntransform = \"crank\"\n",
         "key 'datasets[0].transform': expected slider-crank or slider-crank-printed, got 'crank'");
  expect(kHead + "[[datasets]]\nname = \"a\"\nfile = \"a.csv\"\nunits = \"x=furlong\"\n", "key 'datasets[0].units': ");
  expect("models = [\"mrd.bingham\"]\n" + kData, "missing key 'name' (expected a string)");
  expect(kHead + "[optimizer\n", x() + ":3:");  // malformed TOML: line and column
  expect(kHead, "key 'datasets': expected one or more [[datasets]] tables");
  expect("name = \"all\"\ninclude = [\"nothere.toml\"]\n", "cannot open included sweep file");
  EXPECT_NE(testing::error_of([&] { (void)load_sweep((dir_ / "nothere.toml").string()); }).find("cannot open preset file"),
            std::string::npos);
}

// The automatic budget: the default of an entry without budget keys, `budget` to say so, its cap only with it,
// and never with one run.
TEST_F(SpecErrors, BudgetKindAndCap) {
  expect(kHead + "[optimizer]\nbudget = \"some\"\n" + kData,
         x() + ":4: key 'optimizer.budget': expected \"auto\" or \"fixed\", got 'some'");
  expect(kHead + "[optimizer]\npopulation = 20\nmax_total_evaluations = 1000\n" + kData,
         x() + ":5: key 'optimizer.max_total_evaluations': caps the automatic budget, and this entry's budget is fixed");
  expect(kHead + "runs = 1\n[optimizer]\nname = \"de\"\n" + kData,
         "key 'optimizer': the automatic budget (no population, iterations or stopping rule given) needs runs >= 2");
  expect(kHead + "runs = 1\n" + kData, x() + ":3: key 'runs': the default optimizer (pso with the automatic budget) "
                                           "needs runs >= 2");
  const auto entries = [&](const std::string& optimizers) {
    testing::write_text(dir_ / "x.toml", kHead + kData + optimizers);
    return load_sweep(x()).parts.at(0).optimizers;
  };
  const auto e = entries(
      "[[optimizers]]\nlabel = \"a\"\n"
      "[[optimizers]]\nlabel = \"b\"\niterations = 20\n"
      "[[optimizers]]\nlabel = \"c\"\ntarget = 0.1\n"
      "[[optimizers]]\nlabel = \"d\"\npopulation = 20\nbudget = \"auto\"\nmax_total_evaluations = 5000\n"
      "[[optimizers]]\nlabel = \"e\"\nbudget = \"fixed\"\n");
  ASSERT_EQ(e.size(), 5u);
  EXPECT_TRUE(e[0].auto_budget);
  EXPECT_FALSE(e[1].auto_budget);
  EXPECT_FALSE(e[2].auto_budget);
  EXPECT_TRUE(e[3].auto_budget);
  EXPECT_EQ(e[3].max_total_evaluations, 5000);
  EXPECT_EQ(e[3].spec.population, 20);
  EXPECT_FALSE(e[4].auto_budget);
  testing::write_text(dir_ / "x.toml", kHead + kData);
  EXPECT_TRUE(load_sweep(x()).parts.at(0).optimizers.at(0).auto_budget);
}

// `precision`: the population search's lanes of an optimizer entry, "mixed" by default; the key changes the spec hash
// (stores of the two are told apart).
TEST_F(SpecErrors, SearchPrecision) {
  expect(kHead + "[optimizer]\nprecision = \"single\"\n" + kData,
         x() + ":4: key 'optimizer.precision': expected \"double\" or \"mixed\" (the population search in float32 "
               "lanes), got 'single'");
  testing::write_text(dir_ / "x.toml", kHead + kData + "[optimizer]\nname = \"de\"\n");
  const SweepSpec plain = load_sweep(x());
  EXPECT_EQ(plain.parts.at(0).optimizers.at(0).search_precision, Precision::float32);  // the default: mixed
  testing::write_text(dir_ / "x.toml", kHead + kData + "[optimizer]\nname = \"de\"\nprecision = \"double\"\n");
  const SweepSpec dbl = load_sweep(x());
  EXPECT_EQ(dbl.parts.at(0).optimizers.at(0).search_precision, Precision::float64);
  EXPECT_NE(plain.hash, dbl.hash);
}

// [reproduction]: which rows a claim is judged on, and the reason the numbers are not comparable that "ours" needs.
TEST_F(SpecErrors, ReproductionRows) {
  testing::write_text(dir_ / "paper.toml", "paper = \"p\"\n");
  const std::string head = kHead + kData + "[reproduction]\npublished = \"paper.toml\"\ndata = \"real\"\n";
  expect(head + "rows = \"mine\"\n", x() + ":9: key 'reproduction.rows': expected paper or ours, got 'mine'");
  expect(head + "rows = \"ours\"\n",
         "key 'reproduction.numbers_not_comparable': rows = \"ours\" needs the reason the numbers are not comparable");
  testing::write_text(dir_ / "x.toml", head + "rows = \"ours\"\nnumbers_not_comparable = \"the real damper\"\n");
  const auto spec = load_sweep(x()).parts.at(0).reproduction;
  ASSERT_TRUE(spec.has_value());
  EXPECT_TRUE(spec->claims_on_our_rows);
  EXPECT_EQ(spec->numbers_not_comparable, "the real damper");
}

TEST_F(SpecErrors, BoundsAreCheckedBeforeFiles) {
  // Nothing runs until the whole file is valid; a bad bound is reported even when a file is missing too.
  expect(kHead + "[[datasets]]\nname = \"a\"\nfile = \"gone.csv\"\n[bounds]\n\"mrd.bingham\" = \"c0=5:1\"\n",
         "bounds c0: lower bound 5 is greater than upper bound 1");
}

TEST(SweepSpec, ReadsEveryPart) {
  const auto dir = testing::test_temp_dir("spec");
  for (double I : {0.0, 0.5, 1.0})
    for (double amp : {0.01, 0.02}) write_record(dir / "grid" / fmt::format("I{}_A{}.csv", I, amp), fmt::format("I={},amp={},freq=1", I, amp), amp);
  testing::write_text(dir / "x.toml", R"toml(
name = "x"
title = "A sweep"
seed = 7
runs = 3
metrics = ["rmse", "nrmse"]
[[models]]
model = "mrd.bingham"
[[models]]
name = "bingham(I)"
model = "mrd.bingham"
laws = "f_c=poly(I,1)"
bounds = "f_c_I0=0:100"
optimizers = ["ga"]
[[optimizers]]
name = "pso"
population = 10
iterations = 5
[[optimizers]]
name = "ga"
population = 8
iterations = 4
runs = 2
settings = { pc = 0.7, tournament = 3 }
[[datasets]]
name = "grid"
glob = "grid/*.csv"
[[splits]]
name = "each"
models = ["mrd.bingham"]
fit = { amp = 0.01 }
[[splits]]
name = "by-I"
fit = { amp = 0.01 }
predict = { amp = 0.02 }
by = ["I"]
[[splits]]
name = "joint"
models = ["bingham(I)"]
by = "all"
fit = [{ I = 0 }, { I = 1, amp = 0.01 }]
[[tables]]
kind = "errors"
split = ["by-I", "joint"]
paper = "Table 4"
)toml");
  const SweepSpec spec = load_sweep((dir / "x.toml").string());
  ASSERT_EQ(spec.parts.size(), 1u);
  const PartSpec& p = spec.parts[0];
  EXPECT_EQ(p.title, "A sweep");
  EXPECT_EQ(p.seed, 7u);
  EXPECT_EQ(p.metrics, (std::vector<Metric>{Metric::rmse, Metric::nrmse}));
  ASSERT_EQ(p.models.size(), 2u);
  EXPECT_EQ(p.models[1].name, "bingham(I)");
  EXPECT_EQ(p.optimizers[1].spec.settings.at("pc"), "0.7");
  EXPECT_EQ(p.optimizers[1].spec.settings.at("tournament"), "3");
  EXPECT_EQ(p.optimizers[1].runs, 2);
  ASSERT_EQ(p.datasets.size(), 6u);
  EXPECT_EQ(p.datasets[0].name, "I0.5_A0.01");  // sorted file stems
  EXPECT_EQ(p.datasets[0].collection, "grid");
  EXPECT_EQ(p.tables[0].splits, (std::vector<std::string>{"by-I", "joint"}));

  const Plan plan(load_sweep((dir / "x.toml").string()), testing::csv_loader());
  const auto& pp = plan.parts()[0];
  // each: 3 datasets at amp 0.01 × 2 optimizers (bingham has no restriction) × 2 metrics.
  EXPECT_EQ(pp.splits[0].fitsets.size(), 3u);
  EXPECT_EQ(pp.splits[0].groups, 3 * 2 * 2);
  // by-I: one fit per current, each predicting the same current at 0.02.
  ASSERT_EQ(pp.splits[1].fitsets.size(), 3u);
  for (const auto& fs : pp.splits[1].fitsets) {
    ASSERT_EQ(fs.fit.size(), 1u);
    ASSERT_EQ(fs.predict.size(), 1u);
    EXPECT_EQ(pp.datasets[fs.fit[0]].signals.operating.at("I"), pp.datasets[fs.predict[0]].signals.operating.at("I"));
    EXPECT_EQ(pp.datasets[fs.predict[0]].signals.operating.at("amp"), 0.02);
  }
  EXPECT_EQ(pp.splits[1].fitsets[0].label, "I=0");
  // by-I pairs: bingham × (pso, ga) and bingham(I) × ga only.
  EXPECT_EQ(pp.splits[1].pairs.size(), 3u);
  // joint: I = 0 (both amplitudes) and I = 1 at 0.01, one fit set.
  ASSERT_EQ(pp.splits[2].fitsets.size(), 1u);
  EXPECT_EQ(pp.splits[2].fitsets[0].fit.size(), 3u);
  EXPECT_EQ(pp.splits[2].fitsets[0].label, "joint");

  // Groups decode to distinct (split, fit set, model, optimizer, metric) with distinct keys and their runs.
  EXPECT_EQ(plan.groups(), 12 + 3 * 3 * 2 + 1 * 1 * 2);
  std::set<std::tuple<int, int, int, int, int>> seen;
  std::set<std::uint64_t> keys;
  long long tasks = 0;
  for (long long i = 0; i < plan.groups(); ++i) {
    const GroupRef g = plan.group(i);
    EXPECT_EQ(g.index, i);
    seen.insert({g.split, g.fitset, g.model, g.optimizer, static_cast<int>(g.metric)});
    keys.insert(g.task_key);
    EXPECT_EQ(g.runs, g.optimizer == 1 ? 2 : 3);
    tasks += g.runs;
  }
  EXPECT_EQ(static_cast<long long>(seen.size()), plan.groups());
  EXPECT_EQ(static_cast<long long>(keys.size()), plan.groups());
  EXPECT_EQ(tasks, plan.tasks());
  EXPECT_THROW((void)plan.group(plan.groups()), std::out_of_range);
}

TEST(SweepSpec, EmptySelectionIsAnErrorBeforeAnythingRuns) {
  const auto dir = testing::test_temp_dir("spec");
  write_record(dir / "a.csv", "I=0");
  testing::write_text(dir / "x.toml", kHead + kData + "[[splits]]\nname = \"s\"\nfit = { I = 9 }\n");
  EXPECT_NE(testing::error_of([&] { Plan(load_sweep((dir / "x.toml").string()), testing::csv_loader()); })
                .find("split 's': 'fit' selects no dataset (of 1 candidates)"),
            std::string::npos);
}

TEST(SweepSpec, HashIgnoresTitlesLabelsAndTablesOnly) {
  const auto dir = testing::test_temp_dir("spec");
  write_record(dir / "a.csv", "I=0");
  auto hash = [&](const std::string& text) {
    testing::write_text(dir / "x.toml", text);
    return load_sweep((dir / "x.toml").string()).hash;
  };
  const std::string base = kHead + "runs = 2\n" + kData;
  const std::string h = hash(base);
  EXPECT_EQ(h.size(), 16u);
  EXPECT_EQ(h, hash("# a comment\n" + base + "\n# another\n"));
  EXPECT_EQ(h, hash("title = \"Another title\"\n" + base));
  EXPECT_EQ(h, hash(kHead + "tables = [\"bootstrap\"]\nruns = 2\n[[datasets]]\nname = \"a\"\nlabel = \"Test A\"\nfile = \"a.csv\"\n"));
  EXPECT_NE(h, hash(kHead + "runs = 3\n" + kData));
  EXPECT_NE(h, hash(kHead + "runs = 2\nseed = 2\n" + kData));
}

TEST(SweepSpec, IncludedFilesAreParts) {
  const auto dir = testing::test_temp_dir("spec");
  write_record(dir / "a.csv", "I=0");
  testing::write_text(dir / "p1.toml", "name = \"p1\"\nmodels = [\"mrd.bingham\"]\n" + kData);
  testing::write_text(dir / "p2.toml", "name = \"p2\"\nmodels = [\"fvd.linear_viscous\"]\n" + kData);
  testing::write_text(dir / "all.toml", "name = \"all\"\ninclude = [\"p1.toml\", \"p2.toml\"]\n");
  const SweepSpec all = load_sweep((dir / "all.toml").string());
  ASSERT_EQ(all.parts.size(), 2u);
  EXPECT_EQ(all.parts[1].name, "p2");
  EXPECT_EQ(all.parts[1].models[0].model, "fvd.linear_viscous");
  EXPECT_NE(all.hash, load_sweep((dir / "p1.toml").string()).hash);
  // The same part gives the same task keys alone and inside all.toml: results are shared bit for bit.
  const Plan alone(load_sweep((dir / "p1.toml").string()), testing::csv_loader());
  const Plan both(load_sweep((dir / "all.toml").string()), testing::csv_loader());
  EXPECT_EQ(alone.group(0).task_key, both.group(0).task_key);
  testing::write_text(dir / "dup.toml", "name = \"all\"\ninclude = [\"p1.toml\", \"p1.toml\"]\n");
  EXPECT_NE(testing::error_of([&] { (void)load_sweep((dir / "dup.toml").string()); }).find("two included files are named 'p1'"),
            std::string::npos);
}

TEST(SweepSpec, AnExtendingFileReplacesTheBasesKeysWhole) {
  const auto dir = testing::test_temp_dir("spec");
  write_record(dir / "a.csv", "I=0");
  write_record(dir / "b.csv", "I=1");
  testing::write_text(dir / "base.toml", "name = \"base\"\nruns = 3\nmodels = [\"mrd.bingham\", \"fvd.linear_viscous\"]\n" + kData);
  testing::write_text(dir / "other.toml", "extends = \"base.toml\"\nname = \"other\"\n"
                                          "[[datasets]]\nname = \"b\"\nfile = \"b.csv\"\n");
  const SweepSpec base = load_sweep((dir / "base.toml").string());
  const SweepSpec other = load_sweep((dir / "other.toml").string());
  ASSERT_EQ(other.parts.size(), 1u);
  const PartSpec& part = other.parts[0];
  EXPECT_EQ(part.name, "other");
  EXPECT_EQ(part.runs, 3);  // from the base
  ASSERT_EQ(part.models.size(), 2u);
  EXPECT_EQ(part.models[1].model, "fvd.linear_viscous");
  ASSERT_EQ(part.datasets.size(), 1u);  // [[datasets]] replaced whole, not appended to
  EXPECT_EQ(part.datasets[0].name, "b");
  EXPECT_NE(other.hash, base.hash);
  // The stored source is the merged part: it reads back without the base file.
  fs::remove(dir / "base.toml");
  const SweepSpec again = parse_sweep(part.source, part.path);
  EXPECT_EQ(again.hash, other.hash);
  EXPECT_EQ(again.parts[0].models.size(), 2u);
  // A missing base, a base in another folder and a base that extends again are errors naming the key.
  EXPECT_NE(testing::error_of([&] { (void)load_sweep((dir / "other.toml").string()); })
                .find("other.toml:1: key 'extends': cannot open extended sweep file"),
            std::string::npos);
  fs::create_directories(dir / "sub");
  testing::write_text(dir / "sub" / "base.toml", "name = \"base\"\nmodels = [\"mrd.bingham\"]\n" + kData);
  testing::write_text(dir / "far.toml", "extends = \"sub/base.toml\"\nname = \"far\"\n");
  EXPECT_NE(testing::error_of([&] { (void)load_sweep((dir / "far.toml").string()); }).find("is not in this file's folder"),
            std::string::npos);
  // A chain of bases reads through; a loop is an error naming the key.
  testing::write_text(dir / "base.toml", "extends = \"root.toml\"\nname = \"base\"\n");
  testing::write_text(dir / "root.toml", "name = \"root\"\nruns = 3\nmodels = [\"mrd.bingham\", \"fvd.linear_viscous\"]\n" + kData);
  EXPECT_EQ(load_sweep((dir / "other.toml").string()).hash, other.hash);
  testing::write_text(dir / "root.toml", "extends = \"other.toml\"\nname = \"root\"\n");
  EXPECT_NE(testing::error_of([&] { (void)load_sweep((dir / "other.toml").string()); }).find("extend each other from here"),
            std::string::npos);
}

TEST(SweepSpec, OptionalDatasetsAreSkippedWithANote) {
  const auto dir = testing::test_temp_dir("spec");
  write_record(dir / "a.csv", "I=0");
  testing::write_text(dir / "x.toml", kHead + kData + "[[datasets]]\nname = \"real\"\nglob = \"missing/*.txt\"\nrequired = false\n");
  const SweepSpec spec = load_sweep((dir / "x.toml").string());
  EXPECT_EQ(spec.parts[0].datasets.size(), 1u);
  ASSERT_EQ(spec.notes.size(), 1u);
  EXPECT_NE(spec.notes[0].find("skipped (optional)"), std::string::npos);
  // A part included as optional loses its missing datasets and contributes no task; the others run.
  testing::write_text(dir / "p1.toml", kHead + kData);
  testing::write_text(dir / "p2.toml", "name = \"p2\"\nmodels = [\"mrd.bingham\"]\n[[datasets]]\nname = \"r\"\nglob = \"gone/*.txt\"\n");
  testing::write_text(dir / "all.toml", "name = \"all\"\ninclude = [\"p1.toml\"]\ninclude_optional = [\"p2.toml\"]\n");
  const Plan plan(load_sweep((dir / "all.toml").string()), testing::csv_loader());
  EXPECT_EQ(plan.parts().size(), 2u);
  EXPECT_EQ(plan.groups(), 1);
  EXPECT_EQ(plan.group(0).part, 0);
  EXPECT_NE(testing::error_of([&] { (void)load_sweep((dir / "p2.toml").string()); }).find("no file matches"), std::string::npos);
}

TEST(SweepSpec, GlobOfASweepFileInTheCurrentFolder) {
  // `dampbench run sweep.toml` from the sweep's folder: its glob has no folder part and means this folder.
  const auto dir = testing::test_temp_dir("spec");
  write_record(dir / "r1.csv", "I=0");
  write_record(dir / "r2.csv", "I=1");
  testing::write_text(dir / "sweep.toml", kHead + "[[datasets]]\nname = \"r\"\nglob = \"r*.csv\"\n");
  const auto previous = fs::current_path();
  fs::current_path(dir);
  std::string error;
  std::vector<std::string> files;
  try {
    const SweepSpec spec = load_sweep("sweep.toml");  // (a range-for over a temporary's member would dangle)
    for (const auto& d : spec.parts[0].datasets) files.push_back(d.load.path);
  } catch (const std::exception& e) {
    error = e.what();
  }
  fs::current_path(previous);
  EXPECT_EQ(error, "");
  EXPECT_EQ(files, (std::vector<std::string>{"r1.csv", "r2.csv"}));
}

TEST(SweepSpec, NamedFoldersResolve) {
  EXPECT_EQ(resolve_path("b/c.csv", "/a"), "/a/b/c.csv");
  EXPECT_EQ(resolve_path("/x/y.csv", "/a"), "/x/y.csv");
  ::setenv("DAMPBENCH_GENERATED_DIR", "/gen", 1);
  ::setenv("DAMPBENCH_SHARED_DATA_DIR", "/shared", 1);
  EXPECT_EQ(resolve_path("@generated/mfm/*.csv", "/a"), "/gen/mfm/*.csv");
  EXPECT_EQ(resolve_path("@shared/utfsm/x.txt", "/a"), "/shared/utfsm/x.txt");
  ::unsetenv("DAMPBENCH_GENERATED_DIR");
  ::unsetenv("DAMPBENCH_SHARED_DATA_DIR");
  EXPECT_NE(generated_dir(), "/gen");
}

TEST(SweepSpec, PresetsAreValid) {
  // Every preset parses (files unchecked: the generated grids live in the build tree).
  SpecOptions o;
  o.check_files = false;
  for (const char* name : {"fvd", "crfd", "crfd_neutral", "mfm", "mfm_neutral", "mfm_utfsm", "fdsp", "fdsp_neutral", "fdsp_utfsm", "utfsm", "utfsm_model", "all"}) {
    const std::string path = fmt::format("{}/datasets/presets/{}.toml", DAMPBENCH_SOURCE_DIR, name);
    EXPECT_EQ(testing::error_of([&] { (void)load_sweep(path, o); }), "no error") << name;
  }
}

}  // namespace
}  // namespace dampbench::sweep
