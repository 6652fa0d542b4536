// The reproduction report (engine/sweep/reproduction.hpp): hand-made tables of ours against a hand-written paper
// file, one case per verdict, and the messages of a malformed paper file.
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "engine/sweep/reproduction.hpp"
#include "tests/test_support.hpp"

namespace dampbench::sweep {
namespace {

/// Our table `id` with rows "Test 1", "Test 2" and columns Min, Mean (an fvd-style OF table).
Table ours(const std::string& id, double t1, double t2) {
  Table t{id, id, {"Test", "Mean", "Min"}, {}};
  t.rows.push_back({"Test 1", number_cell(t1 * 1.01), number_cell(t1)});
  t.rows.push_back({"Test 2", number_cell(t2 * 1.01), number_cell(t2)});
  return t;
}

/// A paper file: model A's table (Min 0.10, 0.20) ranked above model B's (0.30, 0.40), compared on Min.
ReproductionSpec paper_file(const std::string& extra = "", bool truth_is_compared_model = false) {
  const auto path = testing::test_temp_dir("reproduction") / "paper.toml";
  testing::write_text(path, "paper = \"p\"\ntitle = \"A paper\"\nsource = \"seed x, Tables 1-2\"\ntolerance_rel = 0.1\n"
                            "[[claims]]\ntext = \"A fits better than B\"\ncolumn = \"Min\"\n"
                            "order = [\"Table 1\", \"Table 2\"]\n"
                            "[[tables]]\ntable = \"Table 1\"\nlabel = \"A\"\nours = \"a\"\ncolumns = [\"Min\", \"Mean\"]\n"
                            "compare = [\"Min\"]\nrows = [[\"Test 1\", 0.10, 0.11], [\"Test 2\", 0.20, 0.21]]\n"
                            "[[tables]]\ntable = \"Table 2\"\nlabel = \"B\"\nours = \"b\"\ncolumns = [\"Min\", \"Mean\"]\n"
                            "compare = [\"Min\"]\nrows = [[\"Test 1\", 0.30, 0.31], [\"Test 2\", 0.40, 0.41]]\n" +
                                extra);
  return {path.string(), "synthetic", "a model", truth_is_compared_model, ""};
}

TEST(Reproduction, NumbersWithinTheToleranceAndTheSameRankingHold) {
  // Each of ours within 10 % of the paper's (0.105 is +5 %, 0.38 is −5 %).
  const Reproduction r = reproduce(paper_file(), {ours("a", 0.105, 0.19), ours("b", 0.31, 0.38)});
  ASSERT_EQ(r.items.size(), 3u);  // the claim, then each table
  EXPECT_EQ(r.items[0].verdict, "holds") << r.items[0].detail;
  EXPECT_EQ(r.items[1].verdict, "holds");
  EXPECT_EQ(r.items[2].verdict, "holds");
  // Labels shared between the paper's values and ours, in the same order
  ASSERT_EQ(r.items[0].values.size(), 4u);
  EXPECT_EQ(r.items[0].values[1].first, "Test 1: B");
  EXPECT_EQ(r.items[0].paper_values[1].first, "Test 1: B");
  EXPECT_DOUBLE_EQ(r.items[0].paper_values[1].second, 0.30);
  EXPECT_DOUBLE_EQ(r.items[0].values[1].second, 0.31);
}

TEST(Reproduction, TheSameRankingWithOtherNumbersDiffers) {
  // Ten times lower, the same order: the claim's ranking stands, its numbers do not.
  const Reproduction r = reproduce(paper_file(), {ours("a", 0.01, 0.02), ours("b", 0.03, 0.04)});
  EXPECT_EQ(r.items[0].verdict, "differs");
  EXPECT_NE(r.items[0].detail.find("same ranking on every row"), std::string::npos) << r.items[0].detail;
  EXPECT_NE(r.items[0].detail.find("-90.0 %"), std::string::npos) << r.items[0].detail;
  EXPECT_EQ(r.items[1].verdict, "differs");
}

TEST(Reproduction, APairRankedTheOtherWayIsReversed) {
  // On Test 2, B (0.18) is below A (0.20): the claim is reversed there, even with every number within 10 %.
  const Reproduction r = reproduce(paper_file(), {ours("a", 0.10, 0.20), ours("b", 0.30, 0.18)});
  EXPECT_EQ(r.items[0].verdict, "reversed");
  EXPECT_NE(r.items[0].detail.find("A above B on 1 of 2 rows (Test 2)"), std::string::npos) << r.items[0].detail;
  EXPECT_EQ(r.items[1].verdict, "holds");
}

TEST(Reproduction, AMissingTableIsNotComparableWithTheReason) {
  const Reproduction r = reproduce(paper_file(), {ours("a", 0.10, 0.20)});
  EXPECT_EQ(r.items[0].verdict, "not-comparable");
  EXPECT_EQ(r.items[2].verdict, "not-comparable");
  EXPECT_NE(r.items[2].detail.find("this run wrote no table 'b'"), std::string::npos) << r.items[2].detail;
}

TEST(Reproduction, RecordsOfAnotherDamperJudgeRankingsOnly) {
  // Ten times lower in the same order would be "differs" (above); with the preset saying the records are another
  // damper's, the numbers are not judged: the claim holds on its ranking, each table is not comparable, with why.
  ReproductionSpec spec = paper_file();
  spec.numbers_not_comparable = "another damper";
  const Reproduction same = reproduce(spec, {ours("a", 0.01, 0.02), ours("b", 0.03, 0.04)});
  EXPECT_EQ(same.items[0].verdict, "holds") << same.items[0].detail;
  EXPECT_NE(same.items[0].detail.find("ranking only, the numbers are not comparable: another damper"), std::string::npos)
      << same.items[0].detail;
  EXPECT_EQ(same.items[1].verdict, "not-comparable");
  EXPECT_EQ(same.items[1].detail, "another damper");
  // A ranking the other way is still reversed.
  const Reproduction other = reproduce(spec, {ours("a", 0.05, 0.02), ours("b", 0.03, 0.04)});
  EXPECT_EQ(other.items[0].verdict, "reversed") << other.items[0].detail;
}

TEST(Reproduction, AClaimOnOurRowsFollowsItsOrderOnEveryRowOfOurs) {
  // Records at other conditions than the paper's: rows "Test 1", "Test 2" are ours, whatever the paper's rows are
  // named; the claim (A below B) is checked on each of them and no number is set against the paper's.
  ReproductionSpec spec = paper_file();
  spec.numbers_not_comparable = "the real damper";
  spec.claims_on_our_rows = true;
  Table a = ours("a", 0.10, 0.50), b = ours("b", 0.30, 0.40);
  a.rows[0][0] = b.rows[0][0] = "10mm1Hz0A";  // not a row of the paper file
  a.rows.push_back({"mean", number_cell(9), number_cell(9)});  // a mean row is not a condition
  b.rows.push_back({"mean", number_cell(0), number_cell(0)});
  const Reproduction r = reproduce(spec, {a, b});
  EXPECT_EQ(r.items[0].verdict, "reversed") << r.items[0].detail;
  EXPECT_NE(r.items[0].detail.find("A above B on 1 of 2 rows (Test 2)"), std::string::npos) << r.items[0].detail;
  EXPECT_NE(r.items[0].detail.find("at our conditions: the real damper"), std::string::npos) << r.items[0].detail;
  ASSERT_EQ(r.items[0].values.size(), 4u);
  EXPECT_EQ(r.items[0].values[0].first, "10mm1Hz0A: A");
  EXPECT_TRUE(r.items[0].paper_values.empty());
  EXPECT_EQ(r.items[1].verdict, "not-comparable");
  // The report lists ours alone for it (there is no paper number to set beside them).
  const std::string md = reproduction_markdown(r);
  EXPECT_NE(md.find("| | ours |\n|---|---:|\n| 10mm1Hz0A: A | 0.1 |"), std::string::npos) << md;
  // The same order on every row holds.
  const Reproduction same = reproduce(spec, {ours("a", 0.10, 0.20), ours("b", 0.30, 0.40)});
  EXPECT_EQ(same.items[0].verdict, "holds") << same.items[0].detail;
}

TEST(Reproduction, AClaimSaysWhenItRestsOnFitsThatDidNotConverge) {
  // B's Test 2 carries the tables' † (runs apart, or still improving): the verdict stands, its detail says so.
  Table b = ours("b", 0.30, 0.40);
  b.rows[1][2] = Cell("0.4†", 0.40);
  const Reproduction r = reproduce(paper_file(), {ours("a", 0.105, 0.19), b});
  EXPECT_EQ(r.items[0].verdict, "holds");
  EXPECT_NE(r.items[0].detail.find("ours not converged (†: runs more than 2 % apart, or a best still improving late): "
                                   "B at 1 of 2 rows"),
            std::string::npos)
      << r.items[0].detail;
  const Reproduction clean = reproduce(paper_file(), {ours("a", 0.105, 0.19), ours("b", 0.31, 0.38)});
  EXPECT_EQ(clean.items[0].detail.find("not converged"), std::string::npos) << clean.items[0].detail;
}

TEST(Reproduction, NumbersTheRecordsDoNotDetermineAreShownButNotJudged) {
  // Our Test 2 of table a is 4.5x the paper's but marked ‡ (the records do not determine it): Table 1 holds on Test 1
  // alone and names Test 2; b's Test 1 sits at a bound (⊥) and is judged (within 10 %) and named.
  Table a = ours("a", 0.105, 0.9);
  a.rows[1][2] = Cell("0.9‡", 0.9);
  Table b = ours("b", 0.31, 0.38);
  b.rows[0][2] = Cell("0.31⊥", 0.31);
  const Reproduction r = reproduce(paper_file("", true), {a, b});
  ASSERT_EQ(r.items.size(), 3u);
  EXPECT_EQ(r.items[1].verdict, "holds") << r.items[1].detail;
  EXPECT_EQ(r.items[1].not_determined, std::vector<std::string>{"Test 2 Min"});
  EXPECT_NE(r.items[1].detail.find("not determined by the records (‡, not judged) 1 of 2: Test 2 Min"), std::string::npos)
      << r.items[1].detail;
  EXPECT_NE(r.items[1].detail.find("largest difference Test 1 Min"), std::string::npos) << r.items[1].detail;
  EXPECT_EQ(r.items[2].verdict, "holds");
  EXPECT_NE(r.items[2].detail.find("at a bound of the search box (⊥) 1 of 2: Test 1 Min"), std::string::npos)
      << r.items[2].detail;
  const auto j = nlohmann::json::parse(reproduction_json(r, {}));
  EXPECT_EQ(j.at("items").at(1).at("not_determined").at(0), "Test 2 Min");
  EXPECT_NE(reproduction_markdown(r).find("| Test 2 Min | 0.2 | 0.9‡ |"), std::string::npos) << reproduction_markdown(r);

  // Without the mark the same number is judged, and differs.
  const Reproduction judged = reproduce(paper_file("", true), {ours("a", 0.105, 0.9), b});
  EXPECT_EQ(judged.items[1].verdict, "differs");
  EXPECT_TRUE(judged.items[1].not_determined.empty());

  // Every number undetermined: nothing to judge.
  a.rows[0][2] = Cell("0.105‡", 0.105);
  const Reproduction none = reproduce(paper_file("", true), {a, b});
  EXPECT_EQ(none.items[1].verdict, "not-comparable");
  EXPECT_NE(none.items[1].detail.find("the records determine none of these numbers of ours"), std::string::npos)
      << none.items[1].detail;
}

// A paper's levels of error (`at_most`: "the maximum error is within 10 N"): ours hold at any distance below them
// and up to the tolerance above; beyond it they differ, whatever the others do.
TEST(Reproduction, LevelsOfErrorHoldAtOrBelowThePapersAndDifferAbove) {
  const std::string level = "[[tables]]\ntable = \"Fig. 9\"\nours = \"err\"\ncolumns = [\"Min\"]\n"
                            "rows = [[\"Test 1\", 1.0], [\"Test 2\", 2.0]]\nat_most = true\n";
  const auto item_with = [&](double t1, double t2) {
    const Reproduction r = reproduce(paper_file(level), {ours("a", 0.1, 0.2), ours("b", 0.3, 0.4), ours("err", t1, t2)});
    return r.items.at(3);
  };
  // A tenth of the paper's level, and 9 % above it: both hold (the plain table rule would call the first −90 %).
  const ReproductionItem below = item_with(0.1, 2.18);
  EXPECT_EQ(below.verdict, "holds") << below.detail;
  EXPECT_NE(below.detail.find("0 of 2 numbers of ours above the paper's level by more than 10 %"), std::string::npos)
      << below.detail;
  EXPECT_NE(below.detail.find("highest against the paper's level Test 2 Min: ours 2.18, paper 2 (+9.0 %)"),
            std::string::npos)
      << below.detail;
  // 12 % above on Test 1 differs, however far below Test 2 is.
  const ReproductionItem above = item_with(1.12, 0.01);
  EXPECT_EQ(above.verdict, "differs") << above.detail;
  EXPECT_NE(above.detail.find("1 of 2 numbers of ours above"), std::string::npos) << above.detail;
  EXPECT_NE(above.detail.find("Test 1 Min: ours 1.12, paper 1 (+12.0 %)"), std::string::npos) << above.detail;
  // Without `at_most` the same tenth differs: levels are the only tables judged one-sided.
  const std::string plain = level.substr(0, level.find("at_most"));
  const Reproduction r = reproduce(paper_file(plain), {ours("a", 0.1, 0.2), ours("b", 0.3, 0.4), ours("err", 0.1, 2.0)});
  EXPECT_EQ(r.items.at(3).verdict, "differs") << r.items.at(3).detail;
}

// A command that knows its records names the tables of ours that are not comparable (errors in N of another damper)
// beside others that are judged; the preset-wide reason applies to the rest.
TEST(Reproduction, TablesNamedNotComparableAreShownWithTheirReasonAndTheRestJudged) {
  ReproductionSpec spec = paper_file();
  spec.tables_not_comparable = {{"b", "forces of another damper"}};
  const Reproduction r = reproduce(spec, {ours("a", 0.105, 0.19), ours("b", 0.31, 0.38)});
  EXPECT_EQ(r.items[1].verdict, "holds") << r.items[1].detail;
  EXPECT_EQ(r.items[2].verdict, "not-comparable");
  EXPECT_EQ(r.items[2].detail, "forces of another damper");
  ASSERT_EQ(r.items[2].values.size(), 2u);  // ours still beside the paper's
  EXPECT_DOUBLE_EQ(r.items[2].values[0].second, 0.31);
  EXPECT_NE(r.items[0].detail.find("ranking only, the numbers are not comparable: forces of another damper"),
            std::string::npos)
      << r.items[0].detail;
}

// [[laws]]: the paper's printed law and our regression of the same parameter, compared by their values at the given
// conditions. Paper: k = (2 + 1·I)(1 + 0.5·amp) × 10 at I = 0 and 2, amp = 1: 30 and 60. Ours: k = (2.1 + 1·I)(1 +
// 0.5·amp) scaled by 10 in its first factor instead, i.e. (21 + 10 I)(1 + 0.5 amp): 31.5 and 61.5, within 10 %.
Table law_table(double k_I0, const std::string& undetermined = "none") {
  Table t{"reg", "reg", {"Parameter", "Law", "Coefficient", "Value", "Not identifiable at"}, {}};
  t.rows.push_back({Cell("k"), Cell("prod(poly(I,1),poly(amp,1))"), Cell("k_I0"), number_cell(k_I0), Cell(undetermined)});
  t.rows.push_back({Cell(""), Cell(""), Cell("k_I1"), number_cell(10), Cell("")});
  t.rows.push_back({Cell(""), Cell(""), Cell("k_amp0"), number_cell(1), Cell("")});
  t.rows.push_back({Cell(""), Cell(""), Cell("k_amp1"), number_cell(0.5), Cell("")});
  t.rows.push_back({Cell("other"), Cell("poly(I,1)"), Cell("other_I0"), number_cell(99), Cell("none")});
  return t;
}
const std::string kLaw = "[[laws]]\ntable = \"eq. 9\"\nours = \"reg\"\nparameter = \"k\"\nlaw = \"prod(poly(I,1),poly(amp,1))\"\n"
                         "scale = 10\ncoefficients = [[\"k_I0\", 2], [\"k_I1\", 1], [\"k_amp0\", 1], [\"k_amp1\", 0.5]]\n"
                         "at = [{ I = 0, amp = 1 }, { I = 2, amp = 1 }]\n";

TEST(Reproduction, APrintedLawIsComparedByItsValuesAtTheConditions) {
  const std::vector<Table> base{ours("a", 0.105, 0.19), ours("b", 0.31, 0.38)};
  auto with = [&](const Table& t) {
    std::vector<Table> all = base;
    all.push_back(t);
    return reproduce(paper_file(kLaw), all).items.back();
  };
  const ReproductionItem near = with(law_table(21));
  ASSERT_EQ(near.values.size(), 2u);
  EXPECT_EQ(near.values[1].first, "k at I=2, amp=1");
  EXPECT_DOUBLE_EQ(near.paper_values[0].second, 30);  // the printed law × scale
  EXPECT_DOUBLE_EQ(near.paper_values[1].second, 60);
  EXPECT_DOUBLE_EQ(near.values[0].second, 31.5);
  EXPECT_DOUBLE_EQ(near.values[1].second, 61.5);
  EXPECT_EQ(near.verdict, "holds") << near.detail;
  EXPECT_EQ(with(law_table(30)).verdict, "differs");  // (30 + 10 I)·1.5: 45 against 30
  // Our coefficient determined at no condition: shown, not judged.
  const ReproductionItem nowhere = with(law_table(30, "‡ 3 of 3"));
  EXPECT_EQ(nowhere.verdict, "not-comparable") << nowhere.detail;
  EXPECT_EQ(nowhere.not_determined.size(), 2u);
  EXPECT_EQ(with(law_table(30, "‡ 2 of 3")).verdict, "differs");
  // No regression of k in our tables.
  Table other = law_table(21);
  other.rows.erase(other.rows.begin(), other.rows.begin() + 4);
  EXPECT_EQ(with(other).verdict, "not-comparable");
  // Coefficients that are not the law's, in its order, are refused naming them.
  std::string wrong = kLaw;
  wrong.replace(wrong.find("[\"k_I1\", 1], "), 13, "");
  const std::string message = testing::error_of([&] { (void)reproduce(paper_file(wrong), base); });
  EXPECT_NE(message.find("expected the coefficients of k = prod(poly(I,1),poly(amp,1)) in order: k_I0, k_I1, k_amp0, "
                         "k_amp1"),
            std::string::npos)
      << message;
}

// A regression table names each coefficient in a later column, its first column only on a law's first row
// (Parameter, Law, Coefficient, Value): `row_key` names the column whose text labels the rows.
TEST(Reproduction, RowsAreFoundByTheColumnRowKeyNames) {
  Table laws{"reg", "reg", {"Parameter", "Law", "Coefficient", "Value"}, {}};
  laws.rows.push_back({Cell("c_r"), Cell("poly(phi,1)"), Cell("c_r_phi0"), number_cell(1.0)});
  laws.rows.push_back({Cell(""), Cell(""), Cell("c_r_phi1"), number_cell(0.25)});
  const std::string table = "[[tables]]\ntable = \"Table 5\"\nours = \"reg\"\ncolumns = [\"Value\"]\n"
                            "rows = [[\"c_r_phi0\", 1.05], [\"c_r_phi1\", 0.2]]\n";
  const Reproduction keyed = reproduce(paper_file(table + "row_key = \"Coefficient\"\n"),
                                       {ours("a", 0.105, 0.19), ours("b", 0.31, 0.38), laws});
  ASSERT_EQ(keyed.items.size(), 4u);
  EXPECT_EQ(keyed.items[3].verdict, "differs") << keyed.items[3].detail;  // 0.25 is +25 % of 0.2; 1.0 within 10 %
  ASSERT_EQ(keyed.items[3].values.size(), 2u);
  EXPECT_EQ(keyed.items[3].values[1].first, "c_r_phi1 Value");
  EXPECT_DOUBLE_EQ(keyed.items[3].values[1].second, 0.25);
  // Keyed by the first column, the coefficients are not found.
  const Reproduction first = reproduce(paper_file(table), {ours("a", 0.105, 0.19), ours("b", 0.31, 0.38), laws});
  EXPECT_EQ(first.items[3].verdict, "not-comparable");
  EXPECT_NE(first.items[3].detail.find("has no number at row 'c_r_phi"), std::string::npos)
      << first.items[3].detail;
  // A key that is not one of our columns finds nothing either.
  const Reproduction wrong = reproduce(paper_file(table + "row_key = \"Name\"\n"),
                                       {ours("a", 0.105, 0.19), ours("b", 0.31, 0.38), laws});
  EXPECT_EQ(wrong.items[3].verdict, "not-comparable");
}

TEST(Reproduction, JsonFollowsTheContractAndMarksRecoveryChecks) {
  const Reproduction r = reproduce(paper_file("", true), {ours("a", 0.10, 0.20), ours("b", 0.30, 0.40)});
  const auto j = nlohmann::json::parse(reproduction_json(r, {"rec1", "rec2"}));
  EXPECT_EQ(j.at("paper"), "p");
  EXPECT_EQ(j.at("data").at("kind"), "synthetic");
  EXPECT_EQ(j.at("data").at("truth_is_compared_model"), true);
  EXPECT_EQ(j.at("data").at("records").size(), 2u);
  const auto& item = j.at("items").at(1);
  EXPECT_EQ(item.at("table"), "Table 1");
  EXPECT_EQ(item.at("id"), "Table 1");
  EXPECT_EQ(j.at("items").at(0).at("id"), "claim 1");  // a claim without an id: its place, from 1
  EXPECT_DOUBLE_EQ(item.at("paper_values").at("Test 2 Min").get<double>(), 0.20);
  EXPECT_DOUBLE_EQ(item.at("values").at("Test 2 Min").get<double>(), 0.20);
  EXPECT_EQ(item.at("recovery_check"), true);
  EXPECT_NE(reproduction_markdown(r).find("(recovery check)"), std::string::npos);
}

TEST(Reproduction, APaperInPercentComparesAfterItsScaleAndAClaimRanksOneColumnPerTable) {
  // Two models in one table of ours (a column each), the paper's errors printed in % (mfm Tables 4-5's layout).
  const auto path = testing::test_temp_dir("reproduction") / "percent.toml";
  testing::write_text(path, "paper = \"q\"\ntitle = \"Q\"\nsource = \"seed y\"\n"
                            "[[claims]]\ntext = \"M below P\"\norder = [\"T M\", \"T P\"]\n"
                            "[[tables]]\ntable = \"T M\"\nlabel = \"M\"\nours = \"errors\"\ncolumns = [\"m\"]\n"
                            "scale = 0.01\nrows = [[\"r1\", 1.5], [\"r2\", 2.0]]\n"
                            "[[tables]]\ntable = \"T P\"\nlabel = \"P\"\nours = \"errors\"\ncolumns = [\"p\"]\n"
                            "scale = 0.01\nrows = [[\"r1\", 4.0], [\"r2\", 5.0]]\n");
  Table errors{"errors", "errors", {"Dataset", "m", "p"}, {}};
  errors.rows.push_back({"r1", number_cell(0.14), number_cell(0.041)});
  errors.rows.push_back({"r2", number_cell(0.15), number_cell(0.05)});
  const Reproduction r = reproduce({path.string(), "synthetic", "P", true, ""}, {errors});
  ASSERT_EQ(r.items.size(), 3u);
  EXPECT_DOUBLE_EQ(r.items[1].paper_values[0].second, 0.015);  // 1.5 % as a fraction
  EXPECT_NE(r.items[1].detail.find("printed values x 0.01"), std::string::npos) << r.items[1].detail;
  EXPECT_EQ(r.items[2].verdict, "holds");  // 0.041 and 0.05 against the paper's 4.0 and 5.0 %
  EXPECT_EQ(r.items[0].verdict, "reversed");  // M above P on both rows here
  EXPECT_NE(r.items[0].detail.find("M above P on every row (2)"), std::string::npos) << r.items[0].detail;
}

/// Our energy-style table: a row per test, a signed column per model ("dE A", "dE B") and a mean row.
Table energy(double a1, double a2, double b1, double b2) {
  Table t{"energy", "energy", {"Dataset", "dE A", "dE B"}, {}};
  t.rows.push_back({"Test 1", number_cell(a1), number_cell(b1)});
  t.rows.push_back({"Test 2", number_cell(a2), number_cell(b2)});
  t.rows.push_back({"mean", number_cell(-99), number_cell(99)});  // not a condition: never judged
  return t;
}

TEST(Reproduction, AClaimWithoutPublishedNumbersIsJudgedOnOurTableAlone) {
  // "A overestimates at every velocity" (a sign) and "B is closer than A" (|B| below |A|), with a margin of 1.
  const auto spec = paper_file(
      "[[claims]]\nid = \"sign\"\ntext = \"A overestimates\"\nours = \"energy\"\ncolumn = \"dE A\"\n"
      "sign = \"positive\"\nmargin = 1.0\n"
      "[[claims]]\nid = \"closer\"\ntext = \"B closer than A\"\nours = \"energy\"\n"
      "order = [\"dE B\", \"dE A\"]\nmagnitude = true\nmargin = 1.0\n");
  const std::vector<Table> base{ours("a", 0.10, 0.20), ours("b", 0.30, 0.40)};
  auto with = [&](Table e) {
    std::vector<Table> t = base;
    t.push_back(std::move(e));
    return reproduce(spec, t);
  };
  // A above +1 on both rows, |B| at least 1 below |A| on both (−3 is far from 0 in magnitude order: |−3| < |5|).
  Reproduction r = with(energy(5, 2.5, -3, 0.5));
  ASSERT_EQ(r.items.size(), 5u);  // the ranking claim, the two claims on ours, the two tables
  EXPECT_EQ(r.items[1].id, "sign");
  EXPECT_EQ(r.items[1].verdict, "holds") << r.items[1].detail;
  EXPECT_EQ(r.items[2].verdict, "holds") << r.items[2].detail;
  EXPECT_TRUE(r.items[1].paper_values.empty());
  ASSERT_EQ(r.items[1].values.size(), 2u);  // the mean row is left out
  EXPECT_EQ(r.items[1].values[1].first, "Test 2: dE A");
  ASSERT_EQ(r.items[2].values.size(), 4u);
  // Below −1 on one row: the other way there.
  r = with(energy(5, -1.5, -3, 0.5));
  EXPECT_EQ(r.items[1].verdict, "reversed") << r.items[1].detail;
  EXPECT_NE(r.items[1].detail.find("the other way by more than 1 on 1 of 2 rows (Test 2)"), std::string::npos)
      << r.items[1].detail;
  // Within ±1 of 0 on a row and nowhere the other way: neither over nor under there, so it differs.
  r = with(energy(5, 0.4, 0.2, 0.1));
  EXPECT_EQ(r.items[1].verdict, "differs") << r.items[1].detail;
  EXPECT_NE(r.items[1].detail.find("neither way beyond ±1 on 1 of 2 rows (Test 2)"), std::string::npos) << r.items[1].detail;
  EXPECT_EQ(r.items[2].verdict, "differs") << r.items[2].detail;  // |0.1| vs |0.4|: a lead of 0.3, within the margin
  // |B| above |A| by more than the margin on a row: reversed.
  r = with(energy(5, 2.5, -7, 0.5));
  EXPECT_EQ(r.items[2].verdict, "reversed") << r.items[2].detail;
  EXPECT_NE(r.items[2].detail.find("(Test 1)"), std::string::npos) << r.items[2].detail;
  // Without our table: not comparable, with why.
  r = reproduce(spec, base);
  EXPECT_EQ(r.items[1].verdict, "not-comparable");
  EXPECT_NE(r.items[1].detail.find("this run wrote no table 'energy'"), std::string::npos) << r.items[1].detail;
  // The markdown lists ours alone for such a claim.
  const std::string md = reproduction_markdown(with(energy(5, 2.5, -3, 0.5)));
  EXPECT_NE(md.find("| | ours |\n|---|---:|\n| Test 1: dE A | 5 |"), std::string::npos) << md;
}

TEST(Reproduction, ALargestClaimNamesOurLargestRowWhenItIsAnother) {
  // The paper's Table 3: C varies most (2.4 against 1.2); ours: C 0.3 against alpha 0.26 (holds), or 0.5 (reversed).
  const auto spec = paper_file(
      "[[claims]]\nid = \"var\"\ntext = \"C varies most\"\ntable = \"Table 3\"\ncolumn = \"ratio\"\n"
      "largest = \"C\"\n"
      "[[tables]]\ntable = \"Table 3\"\nours = \"v\"\ncolumns = [\"mean\", \"ratio\"]\n"
      "numbers_not_comparable = \"another damper\"\nrows = [[\"C\", 126.0, 2.4], [\"alpha\", 0.42, 1.2]]\n");
  auto variability = [](double c, double alpha) {
    Table t{"v", "v", {"Parameter", "mean", "ratio"}, {}};
    t.rows.push_back({"m", number_cell(1), number_cell(9)});  // a row the paper's table does not list: not compared
    t.rows.push_back({"C", number_cell(50), number_cell(c)});
    t.rows.push_back({"alpha", number_cell(0.4), number_cell(alpha)});
    return t;
  };
  const std::vector<Table> base{ours("a", 0.10, 0.20), ours("b", 0.30, 0.40)};
  std::vector<Table> t = base;
  t.push_back(variability(0.3, 0.26));
  Reproduction r = reproduce(spec, t);
  ASSERT_EQ(r.items.size(), 5u);
  EXPECT_EQ(r.items[1].verdict, "holds") << r.items[1].detail;
  ASSERT_EQ(r.items[1].paper_values.size(), 2u);
  EXPECT_EQ(r.items[1].paper_values[0].first, r.items[1].values[0].first);
  EXPECT_DOUBLE_EQ(r.items[1].paper_values[0].second, 2.4);
  t.back() = variability(0.3, 0.5);
  r = reproduce(spec, t);
  EXPECT_EQ(r.items[1].verdict, "reversed");
  EXPECT_NE(r.items[1].detail.find("the largest ratio here is alpha's (0.5), not C's"), std::string::npos) << r.items[1].detail;
  // A paper file whose own numbers contradict its `largest` is refused.
  const auto bad = paper_file(
      "[[claims]]\ntext = \"x\"\ntable = \"Table 3\"\ncolumn = \"ratio\"\nlargest = \"alpha\"\n"
      "[[tables]]\ntable = \"Table 3\"\nours = \"v\"\ncolumns = [\"mean\", \"ratio\"]\n"
      "rows = [[\"C\", 126.0, 2.4], [\"alpha\", 0.42, 1.2]]\n");
  const std::string e = testing::error_of([&] { (void)reproduce(bad, t); });
  EXPECT_NE(e.find("the paper's largest ratio in Table 3 is row 'C', not 'alpha'"), std::string::npos) << e;
}

TEST(Reproduction, AMalformedPaperFileIsReportedWithFileAndKey) {
  const std::vector<Table> tables{ours("a", 0.10, 0.20), ours("b", 0.30, 0.40)};
  // order naming a table the file does not have
  auto bad = paper_file("[[claims]]\ntext = \"x\"\ncolumn = \"Min\"\norder = [\"Table 1\", \"Table 9\"]\n");
  std::string e = testing::error_of([&] { (void)reproduce(bad, tables); });
  EXPECT_NE(e.find("paper.toml"), std::string::npos) << e;
  EXPECT_NE(e.find("no [[tables]] entry 'Table 9'"), std::string::npos) << e;
  // an order the paper's own numbers contradict
  bad = paper_file("[[claims]]\ntext = \"x\"\ncolumn = \"Min\"\norder = [\"Table 2\", \"Table 1\"]\n");
  e = testing::error_of([&] { (void)reproduce(bad, tables); });
  EXPECT_NE(e.find("best (lowest) first"), std::string::npos) << e;
  // a row with one number too few
  bad = paper_file("[[tables]]\ntable = \"T\"\nours = \"a\"\ncolumns = [\"Min\"]\nrows = [[\"Test 1\"]]\n");
  e = testing::error_of([&] { (void)reproduce(bad, tables); });
  EXPECT_NE(e.find("expected a row label and 1 numbers"), std::string::npos) << e;
  // a claim on our table with both forms, or with neither
  bad = paper_file("[[claims]]\ntext = \"x\"\nours = \"a\"\ncolumn = \"Min\"\nsign = \"positive\"\norder = [\"Min\", \"Mean\"]\n");
  e = testing::error_of([&] { (void)reproduce(bad, tables); });
  EXPECT_NE(e.find("takes either `sign` and `column` or `order`"), std::string::npos) << e;
  bad = paper_file("[[claims]]\ntext = \"x\"\nours = \"a\"\ncolumn = \"Min\"\nsign = \"up\"\n");
  e = testing::error_of([&] { (void)reproduce(bad, tables); });
  EXPECT_NE(e.find("expected positive or negative, got 'up'"), std::string::npos) << e;
  // a sign on the paper's tables (no `ours`)
  bad = paper_file("[[claims]]\ntext = \"x\"\ncolumn = \"Min\"\nsign = \"positive\"\norder = [\"Table 1\", \"Table 2\"]\n");
  e = testing::error_of([&] { (void)reproduce(bad, tables); });
  EXPECT_NE(e.find("belong to a claim on our table alone"), std::string::npos) << e;
  // a missing file
  e = testing::error_of([&] { (void)reproduce({"/nonexistent/paper.toml", "real", "", false, ""}, tables); });
  EXPECT_NE(e.find("/nonexistent/paper.toml"), std::string::npos) << e;
}

}  // namespace
}  // namespace dampbench::sweep
