// The numbers an HTML report draws (engine/report/html_report.hpp), on hand-built inputs: the loops are the
// model's force for the best run over optimizers at every k-th sample, unavailable records are listed, run
// distributions and law curves carry the given values, and text cannot end the page's script early.
// tests/e2e/report_browser_test.py renders a real sweep's report in Chromium.
#include "engine/report/html_report.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "models/registry.hpp"
#include "tests/test_support.hpp"

namespace dampbench::report {
namespace {

using testing::sine_signals;

sweep::RunRecord run_with(int index, double best, std::vector<double> params) {
  sweep::RunRecord r;
  r.run = index;
  r.best_value = best;
  r.params = std::move(params);
  r.evaluations = 100;
  r.trace = {{10, best * 4}, {100, best}};
  return r;
}

struct Fixture {
  const Model& model = find_model("mrd.bingham");
  const std::vector<double> truth{300, 2000, 10}, off{500, 1500, 0};  // f_c, c0, f0
  Signals fitted = sine_signals(0.01, 1, 2, 200, {{"I", 0.0}});       // 401 samples
  Signals other = sine_signals(0.02, 2, 1, 100, {{"I", 1.0}});
  ReportInput in;

  Fixture() {
    fitted.name = "rec0";
    fitted.F_N = model.simulate(truth, fitted);  // the truth fits it exactly
    other.name = "rec1";
    other.F_N = model.simulate(off, other);
    in.title = "test";
    in.records = {{"rec0", "", &fitted, ""}, {"rec1", "", &other, ""}, {"gone", "", nullptr, "its file is no longer found"}};
    FitInput pso{"p", "each", "A", "bingham", "pso", &model, Metric::nrmse, {0}, {1, 2}, {}};
    pso.runs = {run_with(0, 0.5, off), run_with(1, 0.4, off)};
    FitInput de = pso;
    de.optimizer = "de";
    de.runs = {run_with(0, 0.2, off), run_with(1, 0.1, truth), run_with(2, 0.3, off)};
    in.fits = {pso, de};
  }
};

std::vector<double> numbers(const nlohmann::ordered_json& j) {
  std::vector<double> v;
  for (const auto& x : j) v.push_back(x.is_null() ? NAN : x.get<double>());
  return v;
}

TEST(ReportData, LoopsAreTheBestRunsForceAtEveryKthSample) {
  Fixture f;
  HtmlOptions options;
  options.max_points = 100;  // 401 samples → every 5th, 81 drawn
  const auto j = report_data(f.in, options);
  const auto& rec = j["records"][0];
  EXPECT_EQ(rec["samples"], 401);
  ASSERT_EQ(rec["stride"], 5);
  const auto t = numbers(rec["t"]);
  ASSERT_EQ(t.size(), 81u);
  EXPECT_EQ(t[3], f.fitted.t_s[15]);
  EXPECT_EQ(numbers(rec["F"])[7], f.fitted.F_N[35]);

  ASSERT_EQ(j["conditions"].size(), 1u);
  const auto& c = j["conditions"][0];
  EXPECT_EQ(c["condition"], "A");
  ASSERT_EQ(c["records"].size(), 3u);  // the fitted record, then the predicted ones
  EXPECT_EQ(c["records"][0]["role"], "fitted");
  EXPECT_EQ(c["records"][1]["role"], "predicted");
  const auto& model = c["records"][0]["models"];
  ASSERT_EQ(model.size(), 1u);  // one model: the best of its two optimizers' fits
  EXPECT_EQ(model[0]["optimizer"], "de");
  EXPECT_EQ(model[0]["value"], 0.1);
  EXPECT_EQ(numbers(model[0]["params"]), f.truth);
  // The truth's force is the measured force: the loop lies on it, sample for sample.
  EXPECT_EQ(numbers(model[0]["F"]), numbers(rec["F"]));
  // On the predicted record the same parameters give the truth's force there, not the record's.
  const auto predicted = f.model.simulate(f.truth, f.other);
  const auto drawn = numbers(c["records"][1]["models"][0]["F"]);
  const std::size_t stride = j["records"][1]["stride"];
  ASSERT_EQ(drawn.size(), (predicted.size() + stride - 1) / stride);
  for (std::size_t k = 0; k < drawn.size(); ++k) EXPECT_EQ(drawn[k], predicted[k * stride]);
  // A record that could not be read again: the reason, no signals, no model force.
  EXPECT_EQ(j["records"][2]["unavailable"], "its file is no longer found");
  EXPECT_FALSE(j["records"][2].contains("F"));
  EXPECT_TRUE(c["records"][2]["models"].empty());
}

TEST(ReportData, HeldOutRecordsAreDrawnAgainstTheirFoldsPredictionGroupedByFold) {
  Fixture f;
  EXPECT_TRUE(report_data(f.in)["held_out"].empty());  // no held-out evaluation, no section
  const auto by_a = f.model.simulate(f.truth, f.other), by_b = f.model.simulate(f.off, f.fitted);
  f.in.predictions = {{1, "I=1", "rec0", "bingham", "pso", Metric::nrmse, 0.25, 0.1, f.truth, &by_a},
                      {0, "I=0", "rec1", "bingham", "pso", Metric::nrmse, 0.5, std::nullopt, f.off, &by_b},
                      {2, "I=1", "rec0", "bingham", "pso", Metric::nrmse, 0.125, 0.1, f.truth, &by_a}};
  HtmlOptions options;
  options.max_points = 100;
  const auto j = report_data(f.in, options);
  const auto& h = j["held_out"];
  ASSERT_EQ(h.size(), 2u);  // folds in the order of their first record
  EXPECT_EQ(h[0]["fold"], "I=1");
  EXPECT_EQ(h[0]["fitted_on"], "rec0");
  ASSERT_EQ(h[0]["records"].size(), 2u);
  ASSERT_EQ(h[1]["records"].size(), 1u);
  const auto& one = h[0]["records"][0];
  EXPECT_EQ(one["record"], 1);
  EXPECT_EQ(one["role"], "predicted");
  EXPECT_EQ(one["title"], "rec1 held out by fold I=1: nrmse 0.25, 2.5× its per-file fit (0.1)");
  EXPECT_EQ(one["ratio"], 2.5);
  ASSERT_EQ(one["models"].size(), 1u);
  EXPECT_EQ(numbers(one["models"][0]["params"]), f.truth);
  EXPECT_EQ(one["models"][0]["value"], 0.25);
  // The given force at the record's stride: the fold's prediction, not the measured force.
  const auto drawn = numbers(one["models"][0]["F"]);
  const std::size_t stride = j["records"][1]["stride"];
  ASSERT_EQ(drawn.size(), (by_a.size() + stride - 1) / stride);
  for (std::size_t k = 0; k < drawn.size(); ++k) EXPECT_EQ(drawn[k], by_a[k * stride]);
  EXPECT_NE(drawn, numbers(j["records"][1]["F"]));
  // Without a per-file reference the title has no ratio; an unavailable record has no force.
  EXPECT_EQ(h[1]["records"][0]["title"], "rec0 held out by fold I=0: nrmse 0.5");
  EXPECT_TRUE(h[1]["records"][0]["ratio"].is_null());
  EXPECT_TRUE(h[0]["records"][1]["models"].empty());
}

TEST(ReportData, ConvergenceAndRunDistributionsPerOptimizer) {
  Fixture f;
  const auto j = report_data(f.in);
  const auto& conv = j["conditions"][0]["convergence"];
  ASSERT_EQ(conv.size(), 1u);
  ASSERT_EQ(conv[0]["optimizers"].size(), 2u);
  const auto& de = conv[0]["optimizers"][1];
  EXPECT_EQ(de["optimizer"], "de");
  ASSERT_EQ(de["runs"].size(), 3u);
  EXPECT_EQ(de["runs"][1][1][1], 0.1);  // run 1's last trace point
  // At 100 evaluations every run has its best: median of {0.2, 0.1, 0.3}.
  EXPECT_EQ(numbers(de["band"]["median"]).back(), 0.2);
  EXPECT_FALSE(de["converged"]);  // runs 0.1 … 0.3 disagree

  ASSERT_EQ(j["distributions"].size(), 1u);
  const auto& d = j["distributions"][0];
  EXPECT_EQ(d["optimizers"], (std::vector<std::string>{"pso", "de"}));
  EXPECT_EQ(numbers(d["values"][0][0]), (std::vector<double>{0.5, 0.4}));
  EXPECT_EQ(numbers(d["values"][1][0]), (std::vector<double>{0.2, 0.1, 0.3}));
}

TEST(ReportData, LawCurvePassesThroughTheFittedValues) {
  Fixture f;
  // c0 = 2 + 3·I observed exactly at I = 0, 0.5, 1 in two amplitude groups (one curve each).
  const ParameterLaw law = parse_law("prod(poly(I,1),poly(amp,0))", "test");
  std::vector<std::map<std::string, double>> x{{{"I", 0}, {"amp", 0.01}}, {{"I", 0.5}, {"amp", 0.01}},
                                               {{"I", 1}, {"amp", 0.01}}, {{"I", 0}, {"amp", 0.02}},
                                               {{"I", 1}, {"amp", 0.02}}};
  const std::vector<double> y{2, 3.5, 5, 2, 5};
  f.in.laws.push_back({"law", {"a", "b", "c", "d", "e"}, x,
                       {"c0", law, sweep::fit_law(law, "c0", x, y), {false, true, false, false, false}}});
  const auto j = report_data(f.in);
  ASSERT_EQ(j["laws"].size(), 1u);
  const auto& l = j["laws"][0];
  EXPECT_EQ(l["variable"], "I");
  ASSERT_EQ(l["groups"].size(), 2u);
  EXPECT_EQ(l["groups"][0]["label"], "amp = 0.01");
  EXPECT_EQ(l["groups"][0]["points"][1]["undetermined"], true);
  const auto cx = numbers(l["groups"][0]["curve"]["x"]), cy = numbers(l["groups"][0]["curve"]["y"]);
  EXPECT_EQ(cx.front(), 0);
  EXPECT_EQ(cx.back(), 1);
  EXPECT_NEAR(cy.front(), 2, 1e-9);
  EXPECT_NEAR(cy.back(), 5, 1e-9);
  EXPECT_NEAR(cy[cy.size() / 2], 3.5, 0.05);
}

TEST(RenderHtml, TextCannotEndTheDataScript) {
  Fixture f;
  f.in.title = "</script><script>alert(1)</script>";
  const std::string html = render_html(f.in);
  // Three scripts (data, D3, the page) close once each; the title's tags are escaped or neutralised.
  std::size_t closes = 0;
  for (std::size_t at = html.find("</script>"); at != std::string::npos; at = html.find("</script>", at + 1)) ++closes;
  EXPECT_EQ(closes, 3u);
  EXPECT_NE(html.find("<title>&lt;/script&gt;"), std::string::npos);
  EXPECT_NE(html.find("<\\/script>"), std::string::npos);
}

}  // namespace
}  // namespace dampbench::report
