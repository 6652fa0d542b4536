// A fitted model as a file, end to end: fit --save-model, then evaluate and simulate --model-file reproduce the
// fit's metric and force bit for bit (same binary, same vector level); where each operating variable came from
// is printed; a time-varying current column is refused for a law; fit --start FILE starts from a file's coefficients.
#include <bit>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "tests/test_support.hpp"

namespace dampbench {
namespace {

using testing::run_dampbench;

std::string read(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::uint64_t bits(const nlohmann::json& j) { return std::bit_cast<std::uint64_t>(j.get<double>()); }

/// Fits `fit_args` on `csv` with --save-model, then checks the file against the fit's JSON and that evaluate
/// --model-file gives the fit's metric bit for bit. Returns the model file.
nlohmann::json fit_save_evaluate(const std::filesystem::path& dir, const std::string& fit_args,
                                 const std::string& record_args, const std::string& metric) {
  const auto model = dir / "model.json";
  auto r = run_dampbench("fit " + fit_args + " " + record_args + " --metric " + metric +
                         " --format json --save-model " + model.string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  const auto fit = nlohmann::json::parse(r.output);
  const auto file = nlohmann::json::parse(read(model));
  EXPECT_EQ(file.at("format"), "dampbench-model");
  EXPECT_EQ(file.at("metric").at("name"), metric);
  EXPECT_EQ(bits(file.at("metric").at("fitted_value")), bits(fit.at("metrics").at(metric)));
  EXPECT_EQ(bits(file.at("records")[0].at("metric_value")), bits(fit.at("metrics").at(metric)));
  for (const auto& [name, value] : fit.at("best_params").items())
    EXPECT_EQ(bits(file.at("coefficients").at(name)), bits(value)) << name;
  EXPECT_EQ(file.at("records")[0].at("operating"), fit.at("operating")[0].at("variables"));

  r = run_dampbench("evaluate --model-file " + model.string() + " " + record_args + " --format json");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  const auto eval = nlohmann::json::parse(r.output);
  for (const auto& [path, metrics] : eval.items())
    EXPECT_EQ(bits(metrics.at(metric)), bits(fit.at("metrics").at(metric))) << path;
  return file;
}

/// A generalized viscous damper's record (m = 0, C = 2e5, alpha = 0.4) on two cycles of a 20 mm, 1 Hz sine, with
/// `noise` (simulate's --noise-rel arguments, or none).
std::filesystem::path fvd_record(const std::filesystem::path& dir, const std::string& noise) {
  const auto csv = dir / "fvd.csv";
  const auto r = run_dampbench("simulate --model fvd.generalized_viscous --params m=0,C=2e5,alpha=0.4 "
                               "--sine amp=0.02,freq=1,cycles=2,fs=200 " + noise + " -o " + csv.string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return csv;
}

TEST(ModelFileCli, AFittedModelEvaluatesToTheFitsMetricBitForBit) {
  const auto dir = testing::test_temp_dir("model_file");
  const auto csv = fvd_record(dir, "--noise-rel 0.02");
  const auto file = fit_save_evaluate(dir, "--model fvd.generalized_viscous --runs 2 --iters 30 --threads 2",
                                      "--data " + csv.string(), "of_abs");
  EXPECT_EQ(file.at("model").at("base"), "fvd.generalized_viscous");
  EXPECT_EQ(file.at("model").at("laws"), "");
  EXPECT_FALSE(file.at("vector_level").get<std::string>().empty());
  EXPECT_EQ(file.at("records")[0].at("operating").at("amp").at("source"), "record estimate (half peak-to-peak)");
  EXPECT_EQ(file.at("records")[0].at("path"), csv.string());
}

// A law model (Spencer with c0 linear in I) on a record whose current comes from --set: the laws string, the
// coefficients and the current's source are in the file; evaluate and simulate rebuild the same model.
TEST(ModelFileCli, ALawModelRoundTripsWithItsOperatingVariables) {
  const auto dir = testing::test_temp_dir("model_file");
  const auto csv = dir / "spencer.csv";
  auto r = run_dampbench("simulate --model mrd.spencer --params c0=8000,c1=1e5,k0=500,k1=200,x0=0.002,alpha=9000,"
                         "beta=2e4,gamma=5e4,A=150,n=1.5 --sine amp=0.01,freq=1,cycles=2,fs=200 -o " + csv.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string record = "--data " + csv.string() + " --set I=0.5";
  const auto file = fit_save_evaluate(
      dir, "--model mrd.spencer --laws \"c0=poly(I,1)\" --runs 2 --iters 10 --pop 12 --threads 2", record, "nrmse");
  EXPECT_EQ(file.at("model").at("base"), "mrd.spencer");
  EXPECT_EQ(file.at("model").at("laws"), "c0=poly(I,1)");
  EXPECT_TRUE(file.at("coefficients").contains("c0_I0"));
  EXPECT_TRUE(file.at("coefficients").contains("c0_I1"));
  const auto& operating = file.at("records")[0].at("operating");
  EXPECT_EQ(operating.at("I").at("value"), 0.5);
  EXPECT_EQ(operating.at("I").at("source"), "--set");
  EXPECT_EQ(operating.at("freq").at("source"), "record estimate (fdsp eq. 15)");

  // Without the current the law cannot be evaluated: the record options are the ones the command always takes.
  r = run_dampbench("evaluate --model-file " + (dir / "model.json").string() + " --data " + csv.string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("no operating variable 'I'"), std::string::npos) << r.output;

  // simulate --model-file gives the force of the same model with the file's coefficients given by hand.
  std::string params;
  for (const auto& [name, value] : file.at("coefficients").items())
    params += (params.empty() ? "" : ",") + name + "=" + nlohmann::json(value).dump();
  const auto from_file = dir / "from_file.csv", by_hand = dir / "by_hand.csv";
  r = run_dampbench("simulate --model-file " + (dir / "model.json").string() + " --input " + csv.string() +
                    " --set I=0.5 -o " + from_file.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = run_dampbench("simulate --model mrd.spencer --laws \"c0=poly(I,1)\" --params " + params + " --input " +
                    csv.string() + " --set I=0.5 -o " + by_hand.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(read(from_file), read(by_hand));
  EXPECT_GT(read(from_file).size(), 1000u);

  // Fitted at 0.5 A only: another current is an extrapolation of c0's law, flagged (not refused) by evaluate and
  // simulate; the fitted current is not.
  const std::string model = (dir / "model.json").string();
  r = run_dampbench("evaluate --model-file " + model + " --data " + csv.string() + " --set I=2");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("Outside the range the model file was fitted on: spencer: I = 2 (fitted on 0.5 to 0.5)"),
            std::string::npos) << r.output;
  r = run_dampbench("evaluate --model-file " + model + " " + record + " --format json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(nlohmann::json::parse(r.output).at(csv.string()).at("extrapolated").is_null()) << r.output;
  r = run_dampbench("simulate --model-file " + model + " --input " + csv.string() + " --set I=2 -o " +
                    (dir / "at_2A.csv").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("note: outside the range " + model + " was fitted on: I = 2 (fitted on 0.5 to 0.5)"),
            std::string::npos) << r.output;
  r = run_dampbench("simulate --model-file " + model + " --input " + csv.string() + " --set I=0.5 -o " +
                    from_file.string());
  EXPECT_EQ(r.output.find("note: outside"), std::string::npos) << r.output;

  r = run_dampbench("evaluate --model-file " + (dir / "model.json").string() + " --model mrd.spencer " + record);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("--model-file gives the model"), std::string::npos) << r.output;
}

// Fitted on two records: each record's metric in the file is what evaluate gives for it, bit for bit.
TEST(ModelFileCli, EachFittedRecordsMetricIsWhatEvaluateGives) {
  const auto dir = testing::test_temp_dir("model_file");
  std::string data;
  for (const char* amp : {"0.01", "0.02"}) {
    const auto csv = dir / (std::string("amp") + amp + ".csv");
    const auto r = run_dampbench("simulate --model fvd.generalized_viscous --params m=0,C=2e5,alpha=0.4 --sine amp=" +
                                 std::string(amp) + ",freq=1,cycles=2,fs=200 --noise-rel 0.05 -o " + csv.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    data += " --data " + csv.string();
  }
  const auto model = dir / "model.json";
  auto r = run_dampbench("fit --model fvd.generalized_viscous --runs 2 --iters 20 --metric nrmse --threads 2" + data +
                         " --save-model " + model.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto file = nlohmann::json::parse(read(model));
  r = run_dampbench("evaluate --model-file " + model.string() + data + " --format json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto eval = nlohmann::json::parse(r.output);
  ASSERT_EQ(file.at("records").size(), 2u);
  for (const auto& record : file.at("records")) {
    const std::string path = record.at("path");
    EXPECT_EQ(bits(eval.at(path).at("nrmse")), bits(record.at("metric_value"))) << path;
  }
  EXPECT_NE(bits(file.at("records")[0].at("metric_value")), bits(file.at("records")[1].at("metric_value")));
}

TEST(ModelFileCli, OptionsThatCannotGoTogetherAreRefused) {
  const auto dir = testing::test_temp_dir("model_file");
  const auto csv = dir / "r.csv";
  auto r = run_dampbench("simulate --model fvd.linear_viscous --params m=0,C=1e4 --sine amp=0.01,freq=1,fs=100 -o " +
                         csv.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto model = dir / "m.json";
  r = run_dampbench("fit --model fvd.linear_viscous --runs 1 --iters 1 --data " + csv.string() + " --save-model " +
                    model.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::pair<std::string, std::string> cases[] = {
      {"fit --model fvd.generalized_viscous --runs 1 --iters 1 --data " + csv.string() + " --start " + model.string(),
       "--start " + model.string() + ": the file's model is fvd.linear_viscous and this fit's fvd.generalized_viscous"},
      {"fit --model fvd.linear_viscous --runs 1 --iters 1 --data " + csv.string() + " --start " +
           (dir / "none.json").string(),
       "--start: expected per-file or a model file (fit --save-model), got '" + (dir / "none.json").string() + "'"},
      {"fit --model mrd.bingham --laws auto --data " + csv.string() + " --start " + model.string(),
       "--start " + model.string() + " with --laws auto"},
      {"fit --model fvd.linear_viscous --runs 1 --iters 1 --data " + csv.string() + " --save-model " +
           (dir / "no" / "m.json").string(),
       "--save-model: the folder of '" + (dir / "no" / "m.json").string() + "' does not exist"},
      {"evaluate --data " + csv.string(), "evaluate: give --model and --params (or --model-file FILE)"},
      {"evaluate --model-file m.json --params C=1 --data " + csv.string(), "evaluate: --model-file gives the model"},
      {"simulate --model-file m.json --fixture mfm.table3 --sine amp=0.01,freq=1,fs=100",
       "simulate: --model-file gives the model"},
      {"evaluate --model-file " + (dir / "none.json").string() + " --data " + csv.string(),
       "--model-file: cannot open '" + (dir / "none.json").string() + "'"}};
  for (const auto& [args, message] : cases) {
    r = run_dampbench(args);
    EXPECT_NE(r.exit_code, 0) << args;
    EXPECT_NE(r.output.find(message), std::string::npos) << args << "\n" << r.output;
  }
}

/// fit --start FILE: a model file whose coefficients are the true parameters of a noise-free record starts every run
/// there, so that one generation of a small population ends at zero error; from the box it does not.
TEST(ModelFileCli, AFitStartsFromAModelFilesCoefficients) {
  const auto dir = testing::test_temp_dir("model_file");
  const auto csv = fvd_record(dir, "");
  const auto fitted = dir / "fitted.json";
  const std::string tiny = "fit --model fvd.generalized_viscous --data " + csv.string() +
                           " --optimizer de --pop 5 --iters 1 --runs 2 --precision double --metric nrmse --format json";
  auto r = run_dampbench(tiny + " --save-model " + fitted.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const double from_box = nlohmann::json::parse(r.output).at("metrics").at("nrmse").get<double>();
  auto truth = nlohmann::json::parse(read(fitted));
  truth["coefficients"] = {{"m", 0.0}, {"C", 2e5}, {"alpha", 0.4}};
  const auto start = dir / "truth.json";
  std::ofstream(start) << truth.dump();
  r = run_dampbench(tiny + " --start " + start.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto fit = nlohmann::json::parse(r.output);
  EXPECT_GT(from_box, 1e-3);
  EXPECT_LT(fit.at("metrics").at("nrmse").get<double>(), 1e-12);
  EXPECT_NEAR(fit.at("best_params").at("C").get<double>(), 2e5, 1e-6);
  for (const auto& run : fit.at("run_results")) EXPECT_LT(run.at("best_value").get<double>(), 1e-12);
}

TEST(ModelFileCli, FitPrintsWhereEachOperatingVariableComesFrom) {
  const auto dir = testing::test_temp_dir("model_file");
  const auto csv = dir / "10mm1Hz0x5A.csv";
  auto r = run_dampbench("simulate --model fvd.linear_viscous --params m=0,C=1e4 "
                         "--sine amp=0.01,freq=1,cycles=2,fs=100 -o " + csv.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = run_dampbench("fit --model fvd.linear_viscous --runs 2 --iters 5 --conditions utfsm --set freq=1.25 --data " +
                    csv.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("Operating variables (source):\n- 10mm1Hz0x5A: I = 0.5 (file name), amp = 0.01 (file name), "
                          "freq = 1.25 (--set), vamp = 0.0785398 (2π·amp·freq), w = "),  // 2π·0.01·1.25
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find(" (record estimate (fdsp eq. 15))\n"), std::string::npos) << r.output;
}

TEST(ModelFileCli, ATimeVaryingCurrentColumnIsFollowedByALaw) {
  // A current that steps from 0 to 1 A halfway: the law C = C_I0 + C_I1·I follows the column sample by sample,
  // so F = (1000 + 2000·I(t))·v is fitted exactly, which no constant current could do. (The command at a sample
  // holds until the next, so the force at sample k sees the current of sample k − 1.)
  const auto dir = testing::test_temp_dir("model_file");
  std::string text = "t,x,F,I\n";
  for (int k = 0; k < 200; ++k) {
    const double t = 0.01 * k, w = 6.283185307179586;
    const double current = k < 100 ? 0.0 : 1.0, held = k <= 100 ? 0.0 : 1.0;
    text += fmt::format("{},{},{},{}\n", t, 0.01 * std::sin(w * t), (1000 + 2000 * held) * 0.01 * w * std::cos(w * t),
                        current);
  }
  const auto csv = dir / "step.csv";
  std::ofstream(csv) << text;
  auto r = run_dampbench("fit --model fvd.linear_viscous --laws \"C=poly(I,1)\" --bounds m=0:0,C_I0=0:1e4,C_I1=0:1e4 --runs 2 --iters 40 "
                         "--metric nrmse --format json --data " + csv.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto fit = nlohmann::json::parse(r.output.substr(r.output.find('{')));
  EXPECT_LT(fit.at("metrics").at("nrmse").get<double>(), 1e-3) << r.output;
  EXPECT_NE(r.output.find("column varying from 0 to 1: the mean shown, laws follow the column sample by sample"),
            std::string::npos)
      << r.output;
  // A stated constant replaces the column: the record is one current again, and the step cannot be fitted.
  r = run_dampbench("fit --model fvd.linear_viscous --laws \"C=poly(I,1)\" --bounds m=0:0,C_I0=0:1e4,C_I1=0:1e4 --runs 2 --iters 40 "
                    "--metric nrmse --format json --set I=0.5 --data " + csv.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_GT(nlohmann::json::parse(r.output.substr(r.output.find('{'))).at("metrics").at("nrmse").get<double>(), 0.1) << r.output;
}

// An LS-SVM model (lssvm --save-model) predicts the training command's test record again: simulate --model-file
// gives the free run whose error the command reported (the same sums), evaluate --model-file scores it, and the
// commands refuse what an LS-SVM cannot do (a sine without measured forces, --params beside the file).
TEST(ModelFileCli, AnLssvmModelFileRunsTheTrainingCommandsFreeRunAgain) {
  const auto dir = testing::test_temp_dir("lssvm_model_file_cli");
  const std::filesystem::path data = std::filesystem::path(DAMPBENCH_SOURCE_DIR) / "datasets" / "lssvm";
  const auto model = dir / "lssvm.json";
  const std::string test = (data / "test_2Hz_0p2A.csv").string();
  auto r = run_dampbench("lssvm --train " + (data / "train_2Hz_0A.csv").string() + " --train " +
                         (data / "train_2Hz_0p8A.csv").string() + " --test " + test +
                         " --c 50 --sigma 2 --format json --save-model " + model.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto trained = nlohmann::json::parse(r.output).at("free_run");

  const auto sim = dir / "sim.csv";
  r = run_dampbench("simulate --model-file " + model.string() + " --input " + test + " -o " + sim.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::vector<double> predicted, measured;
  std::ifstream in(sim);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "t,x,v,a,F");
  while (std::getline(in, line)) predicted.push_back(std::stod(line.substr(line.rfind(',') + 1)));
  std::ifstream rec(test);
  while (std::getline(rec, line))
    if (!line.empty() && line[0] != '#' && line[0] != 't') measured.push_back(std::stod(line.substr(line.rfind(',') + 1)));
  ASSERT_EQ(predicted.size(), measured.size());
  // The free run's errors from sample 2 on (the first max(d, v, y) = 2 are its measured initial forces).
  double sum_sq = 0;
  for (std::size_t k = 2; k < measured.size(); ++k) sum_sq += (measured[k] - predicted[k]) * (measured[k] - predicted[k]);
  EXPECT_EQ(static_cast<double>(measured.size() - 2), trained.at("samples").get<double>());
  EXPECT_NEAR(sum_sq / static_cast<double>(measured.size() - 2), trained.at("mse").get<double>(),
              1e-12 * trained.at("mse").get<double>());

  r = run_dampbench("evaluate --model-file " + model.string() + " --data " + test + " --format json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const double rmse = nlohmann::json::parse(r.output).at(test).at("rmse").get<double>();
  EXPECT_NEAR(rmse * rmse * static_cast<double>(measured.size()), sum_sq, 1e-9 * sum_sq);  // the whole record's

  r = run_dampbench("simulate --model-file " + model.string() + " --sine amp=0.01,freq=1,cycles=1,fs=100");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("an LS-SVM model runs from a record's first measured forces"), std::string::npos) << r.output;
  r = run_dampbench("evaluate --model-file " + model.string() + " --params c0=1 --data " + test);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("--model-file gives the model: drop --model, --laws and --params"), std::string::npos)
      << r.output;
  r = run_dampbench("lssvm --train " + test + " --test " + test + " --c 1 --sigma 1 --save-model " +
                    (dir / "no" / "such" / "m.json").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("--save-model: the folder of"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace dampbench
