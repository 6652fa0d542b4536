// The SQLite results store (engine/sweep/store.hpp): bit-exact round trips, WAL mode, resume checks that
// refuse another spec, version, format or changed datasets, and the bit-for-bit comparison verify uses.
#include "engine/sweep/store.hpp"

#include <gtest/gtest.h>
#include <sqlite3.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "engine/common/error.hpp"
#include "tests/test_support.hpp"

namespace dampbench::sweep {
namespace {

namespace fs = std::filesystem;

StoreHeader header() {
  StoreHeader h;
  h.name = "s";
  h.spec_hash = "00000000000000aa";
  h.spec_path = "/tmp/s.toml";
  h.dampbench_version = "1.2.3";
  h.build_flags = "Release,test";
  h.groups = 4;
  h.tasks = 8;
  h.parts.push_back({"s", "S", "/tmp/s.toml", "name = \"s\"", 5, 2});
  h.models.push_back({0, "mrd.bingham", "mrd.bingham", "", "", "", {"f_c", "c0", "f0"}});
  h.optimizers.push_back({0, "pso", "pso", 10, 5, {{"variant", "constriction"}}});
  h.splits.emplace_back(0, "");
  h.datasets.push_back({0, "d0", "grid", "d0", "/tmp/d0.csv", "aaaa", "", 100, {{"I", 0.5}, {"amp", 0.01}}});
  h.datasets.push_back({0, "d1", "grid", "d1", "/tmp/d1.csv", "bbbb", "bad line 3", 0, {}});
  h.fitsets.push_back({0, 0, "d0", {0}, {1}});
  return h;
}

GroupRecord record(long long index) {
  GroupRecord g;
  g.index = index;
  g.metric = Metric::nrmse;
  g.runs = 2;
  g.task_key = 0xFEDCBA9876543210ULL;
  g.wall_time_s = 0.5;
  g.candidate_samples = 1.5e6;
  g.evaluations = 100;
  g.dampbench_version = "1.2.3";
  g.build_flags = "Release,test";
  g.spec_hash = "00000000000000aa";
  g.dataset_hash = "cccc";
  g.laws = "f_c=hill(I,2);c0=mono(I,0,1)";
  const double inf = std::numeric_limits<double>::infinity();
  for (int r = 0; r < 2; ++r) {
    RunRecord x;
    x.run = r;
    x.best_value = 0.1 + 1.0 / 3.0 * r;  // not representable in decimal text with few digits
    x.metrics = {1.0 / 7, inf, -0.0, 5e-324, std::nextafter(1.0, 2.0)};
    x.params = {1.0 / 3, -2.5e300, std::nan("")};
    x.evaluations = 50;
    x.stop_reason = "iterations";
    x.trace = {{10, 3.0}, {20, 2.0 / 3}, {50, 2.0 / 3}};
    g.run_results.push_back(x);
  }
  g.dataset_metrics.push_back({1, 1, true, {0.25, 0.5, 0.75, 1.0 / 9, 2.0}});
  g.sensitivity = SensitivityRecord{0, {1.0 / 3, 2.0}, {14.28, 85.72}};
  return g;
}

bool same_bits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

/// Runs one SQL statement on a store file with the plain sqlite3 API.
void sql(const fs::path& path, const std::string& statement) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.string().c_str(), &db), SQLITE_OK);
  char* err = nullptr;
  EXPECT_EQ(sqlite3_exec(db, statement.c_str(), nullptr, nullptr, &err), SQLITE_OK) << (err ? err : "");
  sqlite3_free(err);
  sqlite3_close(db);
}

TEST(Store, RoundTripIsBitExact) {
  const auto dir = testing::test_temp_dir("store");
  const auto path = (dir / "s.sqlite").string();
  {
    Store store = Store::create_or_resume(path, header());
    store.write(record(2));
    GroupRecord failed = record(0);
    failed.failed = true;
    failed.message = "dataset 'd1': bad line 3";
    failed.run_results.clear();
    failed.dataset_metrics.clear();
    failed.sensitivity.reset();
    store.write(failed);
  }
  const Store store = Store::open(path);
  EXPECT_EQ(store.finished(), (std::vector<char>{1, 0, 1, 0}));
  EXPECT_EQ(store.stored_groups(), 2);
  const auto g = store.group(2);
  ASSERT_TRUE(g.has_value());
  const GroupRecord want = record(2);
  EXPECT_TRUE(compare_records(want, *g).empty());
  EXPECT_EQ(g->task_key, want.task_key);
  EXPECT_EQ(g->metric, Metric::nrmse);
  EXPECT_EQ(g->dataset_hash, "cccc");
  EXPECT_EQ(g->laws, want.laws);
  ASSERT_EQ(g->run_results.size(), 2u);
  for (std::size_t r = 0; r < 2; ++r) {
    EXPECT_TRUE(same_bits(g->run_results[r].best_value, want.run_results[r].best_value));
    for (int m = 0; m < kMetricCount; ++m) EXPECT_TRUE(same_bits(g->run_results[r].metrics[m], want.run_results[r].metrics[m])) << m;
    EXPECT_TRUE(std::isnan(g->run_results[r].params[2]));
    EXPECT_TRUE(same_bits(g->run_results[r].params[1], -2.5e300));
    ASSERT_EQ(g->run_results[r].trace.size(), 3u);
    EXPECT_EQ(g->run_results[r].trace[1].evaluations, 20);
  }
  EXPECT_TRUE(g->dataset_metrics[0].predicted);
  EXPECT_EQ(g->sensitivity->SP[1], 85.72);
  const auto f = store.group(0);
  EXPECT_TRUE(f->failed);
  EXPECT_EQ(f->message, "dataset 'd1': bad line 3");
  EXPECT_FALSE(store.group(1).has_value());

  const StoreHeader h = store.header();
  EXPECT_EQ(h.parts[0].seed, 5u);
  EXPECT_EQ(h.optimizers[0].settings.at("variant"), "constriction");
  EXPECT_EQ(h.datasets[0].variables.at("amp"), 0.01);
  EXPECT_EQ(h.datasets[1].error, "bad line 3");
  EXPECT_EQ(h.fitsets[0].predict, (std::vector<int>{1}));
  EXPECT_EQ(h.dataset(0, 1), 1);
  EXPECT_EQ(h.fitset(0, 0, 0), 0);
  EXPECT_EQ(store.meta("format"), std::to_string(kStoreFormat));
}

TEST(Store, UsesWriteAheadLogging) {
  const auto dir = testing::test_temp_dir("store");
  const auto path = (dir / "s.sqlite").string();
  { Store store = Store::create_or_resume(path, header()); }
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  sqlite3_stmt* s = nullptr;
  ASSERT_EQ(sqlite3_prepare_v2(db, "PRAGMA journal_mode", -1, &s, nullptr), SQLITE_OK);
  ASSERT_EQ(sqlite3_step(s), SQLITE_ROW);
  EXPECT_STREQ(reinterpret_cast<const char*>(sqlite3_column_text(s, 0)), "wal");
  sqlite3_finalize(s);
  sqlite3_close(db);
}

TEST(Store, RewritingAGroupReplacesIt) {
  const auto dir = testing::test_temp_dir("store");
  const auto path = (dir / "s.sqlite").string();
  Store store = Store::create_or_resume(path, header());
  store.write(record(1));
  GroupRecord again = record(1);
  again.run_results.pop_back();
  store.write(again);
  EXPECT_EQ(store.group(1)->run_results.size(), 1u);
  EXPECT_EQ(store.stored_groups(), 1);
}

TEST(Store, ResumeRefusesAnotherSweep) {
  const auto dir = testing::test_temp_dir("store");
  const auto path = (dir / "s.sqlite").string();
  { Store store = Store::create_or_resume(path, header()); }
  EXPECT_EQ(testing::error_of([&] { (void)Store::create_or_resume(path, header()); }), "no error");

  StoreHeader other = header();
  other.spec_hash = "00000000000000bb";
  other.name = "t";
  EXPECT_EQ(testing::error_of([&] { (void)Store::create_or_resume(path, other); }),
            "store '" + path + "' belongs to another sweep spec ('s' from /tmp/s.toml, spec hash 00000000000000aa; this spec "
            "'t' has hash 00000000000000bb): give another --store, or --fresh to start over");

  StoreHeader version = header();
  version.dampbench_version = "9.9.9";
  EXPECT_NE(testing::error_of([&] { (void)Store::create_or_resume(path, version); })
                .find("was written by dampbench 1.2.3 (Release,test), this is dampbench 9.9.9 (Release,test)"),
            std::string::npos);

  StoreHeader data = header();
  data.datasets[0].hash = "dddd";
  EXPECT_NE(testing::error_of([&] { (void)Store::create_or_resume(path, data); })
                .find("dataset 'd0' (/tmp/d0.csv) changed since the store was written (hash aaaa, now 'd0' hash dddd)"),
            std::string::npos);
  StoreHeader fewer = header();
  fewer.datasets.pop_back();
  EXPECT_NE(testing::error_of([&] { (void)Store::create_or_resume(path, fewer); }).find("was written for 2 datasets, the sweep now has 1"),
            std::string::npos);
}

TEST(Store, RefusesOtherFormatsAndFiles) {
  const auto dir = testing::test_temp_dir("store");
  const auto path = dir / "s.sqlite";
  { Store store = Store::create_or_resume(path.string(), header()); }
  sql(path, "PRAGMA user_version = 99");
  EXPECT_NE(testing::error_of([&] { (void)Store::open(path.string()); }).find("has format 99, this dampbench"), std::string::npos);
  EXPECT_NE(testing::error_of([&] { (void)Store::create_or_resume(path.string(), header()); }).find("has format 99"),
            std::string::npos);

  sql(path, "PRAGMA user_version = " + std::to_string(kStoreFormat));
  sql(path, "UPDATE meta SET value = 'of_abs,rmse' WHERE key = 'metrics'");
  EXPECT_NE(testing::error_of([&] { (void)Store::open(path.string()); }).find("records the metrics (of_abs,rmse), this dampbench computes (of_abs,of_sq,"),
            std::string::npos);

  std::ofstream(dir / "text.sqlite") << "not a database at all, just text that is long enough to have a header......";
  EXPECT_NE(testing::error_of([&] { (void)Store::open((dir / "text.sqlite").string()); }).find("is not a dampbench store"),
            std::string::npos);
  sql(dir / "other.sqlite", "CREATE TABLE t(x)");
  EXPECT_NE(testing::error_of([&] { (void)Store::open((dir / "other.sqlite").string()); }).find("is not a dampbench store"),
            std::string::npos);
  EXPECT_EQ(testing::error_of([&] { (void)Store::open((dir / "none.sqlite").string()); }),
            "no store at '" + (dir / "none.sqlite").string() + "'");
}

// The store keeps lists and maps as JSON text; a damaged one (fuzz_store found the truncated identifiability flags)
// is a StoreError naming its table and column, as any other damage, not an exception of the JSON library.
TEST(Store, DamagedJsonColumnsAreStoreErrorsNamingTheColumn) {
  const auto dir = testing::test_temp_dir("store");
  const auto path = dir / "s.sqlite";
  {
    Store store = Store::create_or_resume(path.string(), header());
    store.write(record(2));
  }
  sql(path, "INSERT INTO identifiability (grp, samples, std_error, relative_error, correlation, flags) "
            "VALUES (2, 10, x'', x'', x'', '[[\"rank\"')");
  GroupQuery query;
  query.traces = true;
  EXPECT_TRUE(testing::HasText(testing::error_of([&] { (void)Store::open(path.string()).groups(query); }),
                               "store: identifiability.flags holds no valid JSON of its kind"));
  sql(path, "UPDATE identifiability SET flags = '{\"rank\": 1}'");  // valid JSON, not a list of lists
  EXPECT_TRUE(testing::HasText(testing::error_of([&] { (void)Store::open(path.string()).groups(query); }),
                               "identifiability.flags holds no valid JSON of its kind"));
  sql(path, "UPDATE identifiability SET flags = '[[\"rank\"]]'");
  EXPECT_EQ(testing::error_of([&] { (void)Store::open(path.string()).groups(query); }), "no error");

  // Integers kept as text: a group's task key (hex) and the counts in meta.
  sql(path, "UPDATE groups SET task_key = 'fedcba98zz'");
  EXPECT_TRUE(testing::HasText(testing::error_of([&] { (void)Store::open(path.string()).groups(query); }),
                               "store: groups.task_key holds 'fedcba98zz', not a base-16 integer"));
  sql(path, "UPDATE meta SET value = '99999999999999' WHERE key = 'groups'");
  EXPECT_TRUE(testing::HasText(testing::error_of([&] { (void)Store::open(path.string()).finished(); }),
                               "store: meta groups holds 99999999999999, more than any store holds"));
  sql(path, "UPDATE meta SET value = '-3' WHERE key = 'groups'");
  EXPECT_TRUE(testing::HasText(testing::error_of([&] { (void)Store::open(path.string()).header(); }),
                               "store: meta groups holds '-3', not a base-10 integer"));
  sql(path, "UPDATE meta SET value = '' WHERE key = 'groups'");

  sql(path, "UPDATE models SET params = '[\"f_c\", '");
  EXPECT_TRUE(testing::HasText(testing::error_of([&] { (void)Store::open(path.string()).header(); }),
                               "store: models.params holds no valid JSON of its kind"));
}

// Format 3 added the groups' chosen laws; a format-2 store opens as one whose groups chose none, and stays readable.
TEST(Store, AFormatTwoStoreOpensWithoutChosenLaws) {
  const auto dir = testing::test_temp_dir("store");
  const auto path = dir / "s.sqlite";
  {
    Store store = Store::create_or_resume(path.string(), header());
    store.write(record(2));
  }
  sql(path, "ALTER TABLE groups DROP COLUMN laws");
  sql(path, "UPDATE meta SET value = '2' WHERE key = 'format'");
  sql(path, "PRAGMA user_version = 2");
  const Store store = Store::open(path.string());
  EXPECT_EQ(store.meta("format"), std::to_string(kStoreFormat));
  const auto g = store.group(2);
  ASSERT_TRUE(g.has_value());
  EXPECT_EQ(g->laws, "");
  GroupRecord want = record(2);
  want.laws.clear();
  EXPECT_TRUE(compare_records(want, *g).empty());
}

TEST(Store, AStoreKilledBeforeItsFirstCommitStartsAgain) {
  const auto dir = testing::test_temp_dir("store");
  const auto path = dir / "s.sqlite";
  std::ofstream(path).close();  // an empty file, as a creation killed at once leaves
  EXPECT_EQ(testing::error_of([&] { (void)Store::create_or_resume(path.string(), header()); }), "no error");
  EXPECT_EQ(Store::open(path.string()).meta("name"), "s");
}

TEST(Store, CompareRecordsNamesEveryDifference) {
  const GroupRecord a = record(1);
  EXPECT_TRUE(compare_records(a, a).empty());
  GroupRecord b = a;
  b.run_results[1].params[0] = std::nextafter(b.run_results[1].params[0], 1.0);
  b.run_results[0].trace[1].value = 0.5;
  b.dataset_metrics[0].metrics[2] = 0.0;
  b.wall_time_s = 99;  // not compared: machine dependent
  const auto diff = compare_records(a, b, {"f_c", "c0", "f0"});
  ASSERT_EQ(diff.size(), 3u);
  EXPECT_EQ(diff[0].rfind("run 0 trace[1]: stored 0x", 0), 0u) << diff[0];
  EXPECT_NE(diff[1].find("run 1 params[0] f_c: stored 0x3fd5555555555555 (0.33333333333333331) vs recomputed 0x3fd5555555555556"),
            std::string::npos)
      << diff[1];
  EXPECT_NE(diff[2].find("run 1 dataset 1 metric rmse"), std::string::npos) << diff[2];
  // Per-dataset metrics compare in (run, dataset) order whatever order a record lists them in.
  GroupRecord d = a;
  d.dataset_metrics.insert(d.dataset_metrics.begin(), {0, 2, true, {}});
  GroupRecord e = d;
  std::reverse(e.dataset_metrics.begin(), e.dataset_metrics.end());
  EXPECT_TRUE(compare_records(d, e).empty());
  GroupRecord c = a;
  c.failed = true;
  EXPECT_EQ(compare_records(a, c)[0], "status: stored done vs recomputed failed");
}

}  // namespace
}  // namespace dampbench::sweep
