// The command line end to end (engine/cli): the contract outside checks rely on, and bad input
// reported with a clear message and a non-zero exit code.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <utility>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "engine/fit/fit_records.hpp"
#include "models/registry.hpp"
#include "tests/optimizer_test_support.hpp"
#include "tests/test_support.hpp"

namespace dampbench {
namespace {

using testing::retry;
using testing::run_dampbench;
using testing::run_dampbench_json;

void expect_error(const std::string& args, const std::string& message) {
  const auto r = run_dampbench(args);
  EXPECT_NE(r.exit_code, 0) << args;
  EXPECT_NE(r.output.find(message), std::string::npos) << "args: " << args << "\noutput: " << r.output;
}

/// A noise-free Spencer record (10 mm, 1 Hz, like the UTFSM tests) from parameters inside the default box.
std::filesystem::path synthetic_spencer_record() {
  const auto csv = testing::test_temp_dir("cli") / "spencer.csv";
  const auto r = run_dampbench("simulate --model mrd.spencer --params c0=8000,c1=1e5,k0=500,k1=200,x0=0.002,"
                               "alpha=9000,beta=2e4,gamma=5e4,A=150,n=1.5 --sine amp=0.01,freq=1,cycles=3,fs=200 -o " +
                               csv.string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return csv;
}

}  // namespace

// The guide's table of optimizer settings is what `dampbench optimizers` prints (between its two markers), so a
// setting added, renamed or given another default in the code fails here until the guide says so.
TEST(Cli, OptimizersListIsTheGuidesTable) {
  const auto r = run_dampbench("optimizers");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream in(std::filesystem::path(DAMPBENCH_SOURCE_DIR) / "docs" / "guide.md");
  const std::string guide((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string begin = "<!-- dampbench optimizers: the command's output, checked by Cli.OptimizersListIsTheGuidesTable -->\n";
  const std::size_t from = guide.find(begin), to = guide.find("<!-- end of dampbench optimizers -->");
  ASSERT_NE(from, std::string::npos);
  ASSERT_NE(to, std::string::npos);
  EXPECT_EQ(guide.substr(from + begin.size(), to - from - begin.size()), r.output)
      << "regenerate the block with ./build/dampbench optimizers";
  const auto j = nlohmann::json::parse(run_dampbench("optimizers --format json").output);
  EXPECT_EQ(j.at("optimizers").at("de").at("settings").at(1).at("key"), "F");
  EXPECT_EQ(j.at("optimizers").at("de").at("settings").at(1).at("allowed"), "in (0, 2]");
}

TEST(Cli, ModelsJsonListsEveryFvdModel) {
  const auto r = run_dampbench("models --format json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto j = nlohmann::json::parse(r.output);
  const auto& m = j.at("models").at("fvd.gv_quadratic_elastic");
  ASSERT_EQ(m.at("parameters").size(), 5u);
  EXPECT_EQ(m.at("parameters")[2].at("name"), "alpha");
  EXPECT_EQ(m.at("parameters")[0].at("unit"), "kg");
  EXPECT_LT(m.at("parameters")[3].at("lower").get<double>(), m.at("parameters")[3].at("upper").get<double>());
  for (const char* id : {"fvd.linear_viscous", "fvd.generalized_viscous", "fvd.gv_linear_elastic"})
    EXPECT_TRUE(j.at("models").contains(id)) << id;
}

TEST(Cli, SimulateThenFitRecoversParameters) {
  const auto dir = testing::test_temp_dir("cli");
  const auto csv = dir / "sim.csv";
  auto r = run_dampbench("simulate --model fvd.generalized_viscous --params m=0,C=2e5,alpha=0.4 "
                         "--sine amp=0.02,freq=1,cycles=2,fs=400 -o " + csv.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream in(csv);
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header, "t,x,v,a,F");

  r = run_dampbench("fit --model fvd.generalized_viscous --data " + csv.string() +
                    " --runs 4 --iters 150 --bounds m=0:10 --format json --threads 2");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto j = nlohmann::json::parse(r.output);
  EXPECT_NEAR(j.at("best_params").at("C").get<double>(), 2e5, 2e3);
  EXPECT_NEAR(j.at("best_params").at("alpha").get<double>(), 0.4, 4e-3);
  EXPECT_LT(j.at("metrics").at("of_abs").get<double>(), 1e-3);
  for (const char* k : {"of_abs", "of_sq", "rmse", "nrmse", "mae"}) EXPECT_TRUE(j.at("metrics").contains(k)) << k;
  for (const char* k : {"best", "worst", "mean", "std"}) EXPECT_TRUE(j.at("runs").contains(k)) << k;
  EXPECT_LE(j.at("runs").at("best").get<double>(), j.at("runs").at("mean").get<double>());
}

// Fit's defaults for a model with internal states find the optimum. A Spencer record simulated with
// parameters inside the default box (10 mm, 1 Hz, like the UTFSM tests) is fitted exactly by the defaults (ga-lm
// 24 × 30, 4 runs, under 1 s): measured over seeds 1-10, the best run is exact every time and 29 of the 40 runs
// are (the others end in local optima at nrmse 1e-4 to 0.09), so the runs agree at 6 of the 10 seeds; the old
// default (pso 50 × 100) ends at nrmse 2e-3 to 1.5e-2 with disagreeing runs.
// α, β, γ and A are known up to the scale of z (z → s·z: α/s, s·A, β/sⁿ, γ/sⁿ), so α·A and β/γ are checked.
TEST(Cli, FitDefaultsRecoverASyntheticSpencerRecord) {
  const auto csv = synthetic_spencer_record();
  testing::CommandResult r;
  retry(3, [&](int attempt) {
    r = run_dampbench_json("fit --model mrd.spencer --metric nrmse --format json --seed " +
                           std::to_string(attempt + 1) + " --data " + csv.string());
    EXPECT_EQ(r.exit_code, 0) << r.output << r.errors;
    // The automatic budget's progress lines go to stderr, apart from the JSON.
    EXPECT_NE(r.errors.find("automatic budget: round 0"), std::string::npos) << r.errors;
    const auto j = nlohmann::json::parse(r.output);
    EXPECT_EQ(j.at("optimizer").at("name"), "ga-lm");
    EXPECT_EQ(j.at("runs").at("count"), 4);
    EXPECT_LT(j.at("metrics").at("nrmse").get<double>(), 1e-8);
    const auto& p = j.at("best_params");
    auto value = [&](const char* name) { return p.at(name).get<double>(); };
    for (auto [name, truth] : {std::pair{"c0", 8000.0}, {"c1", 1e5}, {"k0", 500.0}, {"k1", 200.0}, {"x0", 0.002}, {"n", 1.5}})
      EXPECT_NEAR(value(name), truth, 1e-6 * std::abs(truth)) << name;
    EXPECT_NEAR(value("alpha") * value("A"), 9000.0 * 150, 1e-6 * 9000.0 * 150);
    EXPECT_NEAR(value("beta") / value("gamma"), 0.4, 1e-6);
    return j.at("convergence").at("converged").get<bool>();
  });

  // An algebraic model keeps the fvd paper's PSO and 50 runs; the output says which defaults it used.
  r = run_dampbench("fit --model fvd.linear_viscous --iters 5 --data " + csv.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("pso, population 50, 5 iterations, 50 runs: fit's defaults for an algebraic model"),
            std::string::npos) << r.output;
}

// A fit whose restarts were still improving when the cap stopped it gets the reason beside the verdict: an optimizer
// without a local stage (ga) on a model whose default ends with one (ga-lm) is pointed to that default; a fit stopped
// for another reason (its last restart ended above the best) is told to raise the cap only. Rounds of 2 × 8 × 4 and
// 2 × 8 × 8 evaluations fit in the cap of 200, the next round does not.
TEST(Cli, ACappedFitStillImprovingIsPointedToALocalStage) {
  const auto csv = synthetic_spencer_record();
  testing::CommandResult r;
  int improving = 0;
  for (int seed = 1; seed <= 3; ++seed) {
    r = run_dampbench_json("fit --model mrd.spencer --optimizer ga --budget auto --pop 8 --iters 4 --runs 2 "
                           "--max-evals 200 --seed " + std::to_string(seed) + " --data " + csv.string());
    ASSERT_EQ(r.exit_code, 0) << r.output << r.errors;
    ASSERT_NE(r.output.find("192 of 200 evaluations: stopped at the cap"), std::string::npos) << r.output;
    const bool still_improving = r.output.find("the last restart improved the best by") != std::string::npos;
    improving += still_improving;
    const bool pointed = r.output.find("ga has no local stage to make it precise (fit with --optimizer ga-lm, fit's "
                                       "default for this model, or raise --max-evals)") != std::string::npos;
    EXPECT_EQ(pointed, still_improving) << r.output;
    if (!still_improving) {
      EXPECT_NE(r.output.find("do not trust this fit; raise --max-evals"), std::string::npos);
    }
  }
  EXPECT_GE(improving, 1);  // a 4-generation GA restarted with 8 improves its best (measured: seeds 1 and 2)
}

TEST(Cli, SimulateOnAnInputFileUsesItsSamples) {
  const auto dir = testing::test_temp_dir("cli");
  testing::write_text(dir / "in.csv", "t[ms],x[mm]\n0,0\n10,1\n20,2\n30,3\n40,4\n50,5\n60,6\n70,7\n80,8\n");
  const auto out = dir / "out.csv";
  const auto r = run_dampbench("simulate --model fvd.linear_viscous --params m=0,C=1000 --input " +
                               (dir / "in.csv").string() + " -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream in(out);
  std::string line;
  std::getline(in, line);
  int rows = 0;
  while (std::getline(in, line)) {
    double t, x, v, a, F;
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf,%lf", &t, &x, &v, &a, &F), 5);
    EXPECT_NEAR(t, 0.01 * rows, 1e-15);
    EXPECT_NEAR(x, 0.001 * rows, 1e-15);
    EXPECT_NEAR(v, 0.1, 1e-12);       // x rises 1 mm per 10 ms: 0.1 m/s, exact for a 3rd-order scheme
    EXPECT_NEAR(F, 100.0, 1e-9);      // C·v
    ++rows;
  }
  EXPECT_EQ(rows, 9);
}

TEST(Cli, BadInputIsReportedClearly) {
  const auto dir = testing::test_temp_dir("cli");
  const auto good = dir / "good.csv";
  testing::write_text(good, "t,x,F\n0,0,0\n1,1,1\n2,2,2\n3,3,3\n4,4,4\n5,5,5\n6,6,6\n7,7,7\n8,8,9\n");
  const std::string data = " --data " + good.string();
  expect_error("fit --model fvd.nope" + data, "unknown model 'fvd.nope' (known: fvd.linear_viscous");
  expect_error("fit --model fvd.linear_viscous --bounds K9=0:1" + data,
               "model fvd.linear_viscous has no parameter 'K9' (parameters: m, C)");
  expect_error("fit --model fvd.linear_viscous --bounds C=5:1" + data,
               "--bounds C: lower bound 5 is greater than upper bound 1");
  expect_error("fit --model fvd.linear_viscous --bounds C=abc:1" + data, "--bounds C lower bound");
  expect_error("fit --model fvd.linear_viscous --metric r2" + data, "unknown metric 'r2'");
  expect_error("fit --model fvd.linear_viscous --optimizer sa" + data, "unknown optimizer 'sa' (known: pso");
  expect_error("fit --model fvd.linear_viscous --pop 1" + data, "pso: population must be at least 2, got 1");
  expect_error("fit --model fvd.linear_viscous --runs 0" + data, "runs must be at least 1, got 0");
  expect_error("fit --model fvd.linear_viscous --format xml" + data, "--format: expected md or json, got 'xml'");
  expect_error("fit --model fvd.linear_viscous --data " + (dir / "missing.csv").string(), "cannot open data file");
  expect_error("simulate --model fvd.linear_viscous --params m=1 --sine amp=0.01,freq=1,fs=100",
               "--params: missing parameter 'C'");
  expect_error("simulate --params m=1 --sine amp=0.01,freq=1,fs=100", "give exactly one of --model M or --fixture NAME");
  expect_error("simulate --fixture mfm.table3 --sine amp=0.01,freq=1,fs=100",
               "dataset 'sine' has no operating variable 'I' (needed by the law of c0");
  expect_error("fit --model mrd.bingham --laws 'f_c=poly(Q,1)'" + data, "--laws f_c: unknown operating variable 'Q'");
  expect_error("fit --model fvd.linear_viscous --transform crank" + data, "--transform: expected slider-crank");
  expect_error("fit --model fvd.linear_viscous --conditions utfsm" + data, "'good': expected a UTFSM file name");
  expect_error("fit --model fvd.linear_viscous --set T=3" + data, "--set: unknown operating variable 'T'");
  expect_error("simulate --model fvd.linear_viscous --params m=1,C=2,Q=3 --sine amp=0.01,freq=1,fs=100",
               "has no parameter 'Q'");
  expect_error("simulate --model fvd.linear_viscous --params m=1,C=2", "give exactly one of --input FILE or --sine");

  const auto no_force = dir / "noF.csv";
  testing::write_text(no_force, "t,x\n0,0\n1,1\n2,2\n3,3\n4,4\n5,5\n6,6\n7,7\n8,8\n");
  expect_error("fit --model fvd.linear_viscous --data " + no_force.string(), "missing column 'F'");
  const auto bad_time = dir / "time.csv";
  testing::write_text(bad_time, "t,x,F\n0,0,0\n1,1,1\n1,2,2\n3,3,3\n4,4,4\n5,5,5\n6,6,6\n7,7,7\n8,8,9\n");
  expect_error("fit --model fvd.linear_viscous --data " + bad_time.string(), "time.csv:4: time must increase");
  const auto bad_cell = dir / "cell.csv";
  testing::write_text(bad_cell, "t,x,F\n0,0,0\n1,1,abc\n2,2,2\n3,3,3\n4,4,4\n5,5,5\n6,6,6\n7,7,7\n8,8,9\n");
  expect_error("fit --model fvd.linear_viscous --data " + bad_cell.string(),
               "cell.csv:3: column 3 ('F'): expected a number, got 'abc'");
  expect_error("fit --model fvd.linear_viscous --units x=furlong" + data, "unknown unit 'furlong'");
}

TEST(Cli, RunPresetWritesTheFvdTables) {
  const auto dir = testing::test_temp_dir("cli");
  const std::string root = DAMPBENCH_SOURCE_DIR;
  testing::write_text(dir / "mini.toml",
        "name = \"mini\"\nseed = 3\nruns = 3\nmodels = [\"fvd.linear_viscous\", \"fvd.gv_linear_elastic\"]\n"
        "[optimizer]\nname = \"pso\"\npopulation = 20\niterations = 20\n"
        "[[datasets]]\nname = \"Test 1\"\nfile = \"" + root + "/datasets/fvd/test1_20mm_92mms.csv\"\n"
        "[[datasets]]\nname = \"Test 3\"\nfile = \"" + root + "/datasets/fvd/test3_20mm_460mms.csv\"\n");
  const auto out = dir / "out";
  const auto r = run_dampbench("run " + (dir / "mini.toml").string() + " -o " + out.string() + " --threads 2");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* f : {"table03_of_abs_fvd.linear_viscous.csv", "table05_params_fvd.linear_viscous.csv",
                        "table08_variability_fvd.gv_linear_elastic.csv", "ranking.csv", "tables.md", "summary.md",
                        "report.html"})
    EXPECT_TRUE(std::filesystem::exists(out / f)) << f;
  EXPECT_NE(r.output.find("candidate-samples/s"), std::string::npos);
}

/// The lines of `path` between the heading `from` and the next heading of its level.
std::string section_of(const std::filesystem::path& path, const std::string& from) {
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto begin = text.find("\n" + from + "\n");
  if (begin == std::string::npos) return "";
  const auto end = text.find("\n## ", begin + from.size() + 1);
  return text.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
}

// The fvd preset as a user runs it: the paper's Tables 3-14 and its energy argument beside ours with verdicts, and the figures
// docs/reproduce.md shows are the ones this build writes (a doc table row per CSV row, the leading columns).
TEST(Cli, FvdPresetWritesItsReproductionAndTheDocsShowItsFigures) {
  const auto out = testing::test_temp_dir("cli_fvd") / "fvd";
  const std::filesystem::path root = DAMPBENCH_SOURCE_DIR;
  const auto r = run_dampbench("run " + (root / "datasets/presets/fvd.toml").string() + " -o " + out.string() + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream in(out / "reproduction.json");
  const auto j = nlohmann::json::parse(in);
  EXPECT_EQ(j.at("paper"), "fvd");
  EXPECT_EQ(j.at("data").at("kind"), "synthetic");
  EXPECT_EQ(j.at("data").at("truth_is_compared_model"), false);
  EXPECT_EQ(j.at("data").at("records").size(), 4u);
  // The ranking claim, the two energy claims, the three variability claims, Tables 3-14.
  ASSERT_EQ(j.at("items").size(), 18u);
  const auto& claim = j.at("items").at(0);
  // The nested models rank as the paper's do on every test; our synthetic truth sits close to the elastic models,
  // so their OF values are far below the paper's real-damper ones.
  EXPECT_EQ(claim.at("verdict"), "differs") << claim.at("detail");
  EXPECT_EQ(claim.at("values").size(), 16u);
  EXPECT_DOUBLE_EQ(claim.at("paper_values").at("Test 1: fvd.linear_viscous").get<double>(), 0.324322);

  const std::string docs = section_of(root / "docs/reproduce.md", "## fvd: Tables 3–14");
  ASSERT_FALSE(docs.empty()) << "docs/reproduce.md has no section '## fvd: Tables 3–14'";
  const auto expect_rows_in_docs = [&](const std::string& csv, std::size_t columns) {
    std::ifstream f(out / csv);
    std::string line;
    std::getline(f, line);  // header
    while (std::getline(f, line)) {
      std::vector<std::string> cells;
      std::stringstream ss(line);
      for (std::string c; cells.size() < columns && std::getline(ss, c, ',');) cells.push_back(c);
      std::string row = "|";
      for (const auto& c : cells) row += " " + c + " |";
      EXPECT_NE(docs.find(row), std::string::npos) << csv << ": docs/reproduce.md lacks the row\n" << row;
    }
  };
  expect_rows_in_docs("ranking.csv", 6);
  expect_rows_in_docs("table06_of_abs_fvd.gv_quadratic_elastic.csv", 5);
  expect_rows_in_docs("table14_variability_fvd.gv_quadratic_elastic.csv", 4);
  expect_rows_in_docs("energy.csv", 7);
  for (const auto& item : j.at("items"))
    EXPECT_NE(docs.find(fmt::format("| {} | **{}** |", item.at("id").get<std::string>(),
                                    item.at("verdict").get<std::string>())),
              std::string::npos)
        << "docs/reproduce.md lacks the verdict of " << item.at("id");
}

/// The JSON document embedded in an HTML report (engine/report/html_report.hpp).
nlohmann::json report_data_of(const std::filesystem::path& html_file) {
  std::ifstream in(html_file);
  const std::string html((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string open = "<script type=\"application/json\" id=\"dampbench-data\">";
  const auto begin = html.find(open);
  if (begin == std::string::npos) return nullptr;
  const auto end = html.find("</script>", begin);
  return nlohmann::json::parse(html.substr(begin + open.size(), end - begin - open.size()));
}

TEST(Cli, FitWritesAReportOfItsRuns) {
  const auto dir = testing::test_temp_dir("cli");
  const std::string data = std::string(DAMPBENCH_SOURCE_DIR) + "/datasets/fvd/test1_20mm_92mms.csv";
  const auto file = dir / "fit.html";
  const auto r = run_dampbench("fit --model fvd.linear_viscous --data " + data +
                               " --runs 3 --pop 10 --iters 5 --format json --report " + file.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto fit = nlohmann::json::parse(r.output);
  const auto j = report_data_of(file);
  ASSERT_FALSE(j.is_null());
  ASSERT_EQ(j.at("conditions").size(), 1u);
  const auto& model = j.at("conditions")[0].at("records")[0].at("models")[0];
  EXPECT_EQ(model.at("runs"), 3);
  EXPECT_EQ(model.at("value").get<double>(), fit.at("runs").at("best").get<double>());
  EXPECT_EQ(model.at("params")[1].get<double>(), fit.at("best_params").at("C").get<double>());
  EXPECT_EQ(j.at("conditions")[0].at("convergence")[0].at("optimizers")[0].at("runs").size(), 3u);

  // A report that cannot be written is refused before the fit runs.
  expect_error("fit --model fvd.linear_viscous --data " + data + " --runs 3 --report " + (dir / "no/such/dir/x.html").string(),
               "--report: the folder");
}

TEST(Cli, FitReportDrawsEachHeldOutRecordAgainstItsFoldsPrediction) {
  const auto dir = testing::test_temp_dir("cli");
  const std::string fvd = std::string(DAMPBENCH_SOURCE_DIR) + "/datasets/fvd/";
  const std::vector<std::string> paths{fvd + "test1_20mm_92mms.csv", fvd + "test2_20mm_230mms.csv",
                                       fvd + "test3_20mm_460mms.csv", fvd + "test4_17mm_460mms.csv"};
  const std::string fit = "fit --model fvd.linear_viscous --runs 3 --pop 10 --iters 5 --format json --data " + paths[0] +
                          " --data " + paths[1] + " --data " + paths[2];
  const auto file = dir / "held_out.html";
  // Three settings (one frequency each): three folds, each predicting its left-out record, and the fit on all three
  // predicting the fourth record.
  const auto r = run_dampbench_json(fit + " --folds leave-setting --reference per-file --predict " + paths[3] +
                                    " --report " + file.string());
  ASSERT_EQ(r.exit_code, 0) << r.errors;
  const auto out = nlohmann::json::parse(r.output);
  const auto& h = out.at("held_out");
  const auto j = report_data_of(file);
  ASSERT_FALSE(j.is_null());
  const auto& section = j.at("held_out");
  ASSERT_EQ(section.size(), 4u);  // one group per fold, one loop per held-out record
  const Model& model = find_model("fvd.linear_viscous");
  std::vector<std::string> names;
  for (const auto& p : model.parameters()) names.push_back(p.name);
  for (std::size_t i = 0; i < 4; ++i) {
    const auto& fold = h.at("folds")[i];
    const auto& row = h.at("records")[3 + i];  // the three fitted records first, then the held-out ones
    EXPECT_EQ(section[i].at("fold"), fold.at("name"));
    ASSERT_EQ(section[i].at("records").size(), 1u);
    const auto& rec = section[i].at("records")[0];
    EXPECT_EQ(j.at("records")[rec.at("record").get<std::size_t>()].at("name"), fold.at("predict")[0]);
    EXPECT_EQ(rec.at("title"), fmt::format("{} held out by fold {}: {} {:.4g}, {:.3g}× its per-file fit ({:.4g})",
                                           row.at("record").get<std::string>(), row.at("fold").get<std::string>(),
                                           h.at("metric").get<std::string>(), row.at("metric").get<double>(), row.at("ratio").get<double>(),
                                           row.at("per_file").get<double>()));
    // The drawn force is the fold's model with the fold's best parameters on the held-out record, sample for sample.
    std::vector<double> params;
    for (const auto& n : names) params.push_back(fold.at("best_params").at(n).get<double>());
    const FitRecords held = load_fit_records(model, {paths[i]}, RecordOptions{});
    const std::vector<double> expected = model.simulate(params, held.signals[0]);
    const auto& drawn = rec.at("models")[0].at("F");
    ASSERT_EQ(drawn.size(), expected.size()) << i;
    for (std::size_t k = 0; k < expected.size(); ++k) ASSERT_EQ(drawn[k].get<double>(), expected[k]) << i << " " << k;
  }
  std::vector<std::string> tables;
  for (const auto& t : j.at("tables")) tables.push_back(t.at("id"));
  EXPECT_EQ(tables, (std::vector<std::string>{"best_params", "metrics", "runs", "held_out_folds", "held_out",
                                               "held_out_summary"}));

  // Without held-out evaluation: no held-out section and no held-out tables.
  const auto plain = dir / "plain.html";
  ASSERT_EQ(run_dampbench(fit + " --report " + plain.string()).exit_code, 0);
  const auto p = report_data_of(plain);
  EXPECT_TRUE(p.at("held_out").empty());
  EXPECT_EQ(p.at("tables").size(), 3u);
}

TEST(Cli, StoreReportShowsTheRuntimeTablesOfItsOwnTargetBesideTheEcdfs) {
  const auto dir = testing::test_temp_dir("cli");
  const std::string root = DAMPBENCH_SOURCE_DIR;
  const std::string fvd = root + "/datasets/fvd/";
  auto sweep = [&](const std::string& top, const std::string& tail) {
    return "name = \"rt\"\nseed = 3\nruns = 3\nmodels = [\"fvd.linear_viscous\"]\n" + top +
           "[[optimizers]]\nname = \"pso\"\npopulation = 10\niterations = 5\n"
           "[[optimizers]]\nname = \"de\"\npopulation = 10\niterations = 5\n"
           "[[datasets]]\nname = \"t\"\nfiles = [\"" + fvd + "test1_20mm_92mms.csv\", \"" + fvd +
           "test2_20mm_230mms.csv\"]\n" + tail;
  };
  // The sweep's own runtime table sets the target: the report's tables and ECDF use it.
  testing::write_text(dir / "rt.toml", sweep("", "[[tables]]\nkind = \"runtime\"\ntarget_rel = 0.05\n"));
  ASSERT_EQ(run_dampbench("run " + (dir / "rt.toml").string() + " -o " + (dir / "out").string() + " --quiet").exit_code, 0);
  const auto j = report_data_of(dir / "out" / "report.html");
  ASSERT_FALSE(j.is_null());
  ASSERT_EQ(j.at("runtimes").size(), 1u);
  ASSERT_EQ(j.at("ecdfs").size(), 1u);
  const auto& t = j.at("runtimes")[0];
  EXPECT_EQ(t.at("columns"), nlohmann::json({"Condition", "Model", "target", "pso success", "pso ERT", "pso ERT s",
                                             "de success", "de ERT", "de ERT s"}));
  EXPECT_EQ(t.at("rows").size(), 2u);  // two records, one model
  EXPECT_NE(t.at("title").get<std::string>().find("best known + 0.05 ×"), std::string::npos) << t.at("title");
  EXPECT_NE(j.at("ecdfs")[0].at("title").get<std::string>().find("best known + 0.05 ×"), std::string::npos);
  // Without a runtime table in the file, the report still shows one, at the default target.
  testing::write_text(dir / "plain.toml", sweep("tables = [\"runs\"]\n", ""));
  ASSERT_EQ(run_dampbench("run " + (dir / "plain.toml").string() + " -o " + (dir / "plain").string() + " --quiet").exit_code,
            0);
  const auto p = report_data_of(dir / "plain" / "report.html");
  ASSERT_EQ(p.at("runtimes").size(), 1u);
  EXPECT_NE(p.at("runtimes")[0].at("title").get<std::string>().find("best known + 0.01 ×"), std::string::npos);
}

TEST(Cli, ReportOfAStoreAndItsErrors) {
  const auto dir = testing::test_temp_dir("cli");
  expect_error("report " + (dir / "missing.sqlite").string(), "dampbench: error:");
  testing::write_text(dir / "text.sqlite", "not a database");
  expect_error("report " + (dir / "text.sqlite").string() + " -o " + (dir / "r.html").string(), "dampbench: error:");
  EXPECT_FALSE(std::filesystem::exists(dir / "r.html"));
  expect_error("report x.sqlite --max-points 1", "--max-points");
}

TEST(Cli, EveryErrorHasThePrefixAndTheExitCodeOfItsClass) {
  const auto dir = testing::test_temp_dir("cli");
  const std::string data = std::string(DAMPBENCH_SOURCE_DIR) + "/datasets/fvd/test1_20mm_92mms.csv";
  testing::write_text(dir / "bad.toml", "name = \"bad\"\nmodels = [\"fvd.linear_viscous\"\n");  // unclosed array
  testing::write_text(dir / "not_a_store.sqlite", "hello");
  testing::write_text(dir / "file", "a regular file");
  struct Case {
    std::string args;
    int code;
    std::string message;
  };
  const std::vector<Case> cases{
      // usage (2): command-line syntax from CLI11 and option values
      {"fit --model fvd.linear_viscous --data " + data + " --pop abc", 2, "Could not convert: --pop = abc"},
      {"--threads 0 models", 2, "--threads"},
      {"no-such-command", 2, "no-such-command"},
      {"models --bogus", 2, "--bogus"},
      {"fit --model fvd.linear_viscous --data " + data + " --metric r2", 2, "unknown metric 'r2'"},
      // input data (3): records and sweep files
      {"fit --model fvd.linear_viscous --data " + (dir / "missing.csv").string(), 3, "cannot open data file"},
      {"run " + (dir / "bad.toml").string() + " -o " + (dir / "out").string(), 3, "bad.toml:"},
      // store and output (4)
      {"table " + (dir / "not_a_store.sqlite").string() + " --kind runs", 4, "is not a dampbench store"},
      {"report " + (dir / "missing.sqlite").string(), 4, "no store at"},
      {"simulate --model fvd.linear_viscous --params m=0,C=1e6 --sine amp=0.01,freq=1,cycles=1,fs=100 -o " +
           (dir / "file" / "x.csv").string(),
       4, "x.csv"},
  };
  for (const Case& c : cases) {
    const auto r = run_dampbench(c.args);
    EXPECT_EQ(r.exit_code, c.code) << c.args << "\n" << r.output;
    EXPECT_EQ(r.output.rfind("dampbench: error: ", 0), 0u) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find(c.message), std::string::npos) << c.args << "\n" << r.output;
  }
  EXPECT_EQ(run_dampbench("--version").exit_code, 0);
  EXPECT_EQ(run_dampbench("fit --help").exit_code, 0);
}

TEST(Cli, BadPresetIsReportedWithFileLineAndKey) {
  const auto dir = testing::test_temp_dir("cli");
  testing::write_text(dir / "bad.toml", "name = \"bad\"\nruns = 0\nmodels = [\"fvd.linear_viscous\"]\n");
  expect_error("run " + (dir / "bad.toml").string(), "bad.toml:2: key 'runs': expected an integer >= 1, got 0");
  testing::write_text(dir / "bad2.toml", "name = \"bad\"\nmodels = [\"fvd.linear_viscous\", \"fvd.x\"]\n");
  expect_error("run " + (dir / "bad2.toml").string(), "key 'models': unknown model 'fvd.x'");
  testing::write_text(dir / "bad3.toml", "name = \"bad\"\nmodels = [\"fvd.linear_viscous\"]\n[[datasets]]\nname = \"a\"\nfile = \"nowhere.csv\"\n");
  expect_error("run " + (dir / "bad3.toml").string(), "cannot open data file");
  testing::write_text(dir / "bad4.toml", "name = \"bad\"\nmodels = [\"fvd.linear_viscous\"]\n[[datasets]]\nname = \"a\"\n"
                           "file = \"a.csv\"\n[bounds]\n\"fvd.linear_viscous\" = \"C=3:1\"\n");
  expect_error("run " + (dir / "bad4.toml").string(), "bad4.toml:7: key 'fvd.linear_viscous': bounds C: lower bound 3");
  expect_error("run " + (dir / "nothere.toml").string(), "cannot open preset file");
}

TEST(Cli, BenchJsonHasTheKeysOutsideChecksRead) {
  // A short run: the keys and their consistency, never a time (the machines are shared).
  const auto r = run_dampbench("bench --models fvd.linear_viscous,mrd.bouc_wen --min-time 0.01 --trials 1 --format json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto j = nlohmann::json::parse(r.output);
  for (const char* id : {"fvd.linear_viscous", "mrd.bouc_wen"}) {
    const auto& m = j.at("models").at(id);
    const double one = m.at("cand_samples_per_s_1t"), scalar = m.at("cand_samples_per_s_scalar");
    EXPECT_GT(one, 0) << id;
    EXPECT_GT(m.at("cand_samples_per_s_2t").get<double>(), 0) << id;
    EXPECT_DOUBLE_EQ(m.at("scalar_ratio").get<double>(), one / scalar) << id;
    EXPECT_DOUBLE_EQ(m.at("limit_ratio").get<double>(), one / j.at("machine").at("exp_per_s_1t").get<double>()) << id;
    EXPECT_EQ(m.at("masked_share").get<double>(), 0.0) << id;
  }
  EXPECT_EQ(j.at("models").size(), 2u);
  EXPECT_TRUE(j.at("machine").contains("vector_isa"));
}

TEST(Cli, BenchRejectsBadValues) {
  expect_error("bench --models fvd.nope", "fvd.nope");
  expect_error("bench --trials 0", "--trials");
  expect_error("bench --format xml", "--format: expected md or json, got 'xml'");
  expect_error("bench --workload square", "--workload: expected sine or real-records, got 'square'");
  const auto empty = testing::test_temp_dir("bench_real_records");  // a data folder without the UTFSM records
  expect_error("bench --workload real-records --data-dir " + empty.string(), (empty / "10mm1Hz1A.txt").string());
}

}  // namespace dampbench
