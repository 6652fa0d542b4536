// Sweeps beyond one process (engine/distributed, engine/sweep/schedule.hpp): a task group survives its trip as
// bytes bit for bit, and truncated messages are refused; shards split the sweep into disjoint parts that cover
// it, with balanced estimated cost; merging the shards' stores gives the store of one process, refuses parts of
// another sweep and a group whose numbers differ. (Runs under mpirun: tests/e2e/mpi_test.py.)
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>

#include <fmt/format.h>
#include <sqlite3.h>
#include <tbb/task_arena.h>

#include "engine/common/error.hpp"
#include "engine/distributed/group_codec.hpp"
#include "engine/distributed/merge.hpp"
#include "engine/record/csv_loader.hpp"
#include "engine/sweep/runner.hpp"
#include "engine/sweep/schedule.hpp"
#include "tests/test_support.hpp"

namespace dampbench::distributed {
namespace {

namespace fs = std::filesystem;
using sweep::Plan;
using sweep::Shard;
using sweep::Store;

/// The repository's fvd records; an algebraic and an ODE model; one split per record with a sensitivity study,
/// one joint fit of the ±20 mm tests predicting the ±17 mm one (per-dataset metrics): every field of a record.
std::string sweep_text(int seed) {
  const std::string fvd = std::string(DAMPBENCH_SOURCE_DIR) + "/datasets/fvd/";
  return fmt::format(R"toml(name = "distributed"
seed = {}
runs = 3
models = ["fvd.generalized_viscous", "mrd.bouc_wen"]
[optimizer]
name = "pso"
population = 12
iterations = 8
[[datasets]]
name = "fvd"
files = ["{f}test1_20mm_92mms.csv", "{f}test2_20mm_230mms.csv", "{f}test3_20mm_460mms.csv", "{f}test4_17mm_460mms.csv"]
[[splits]]
name = "each"
sensitivity = {{ points = 5, range = 0.5, objective = "rms" }}
[[splits]]
name = "joint"
by = "all"
fit = {{ amp = 0.02 }}
predict = {{ amp = 0.017 }}
)toml",
                     seed, fmt::arg("f", fvd));
}

Plan make_plan(const fs::path& dir, int seed = 4) {
  std::ofstream(dir / "sweep.toml") << sweep_text(seed);
  return Plan(sweep::load_sweep((dir / "sweep.toml").string()),
              [](const RecordOptions& o) { return load_record(o, true); });
}

/// Runs `shard` of the plan into a new store at `path` (2 threads).
void run_into(const Plan& plan, const fs::path& dir, const std::string& path, const Shard& shard = {}) {
  sweep::StoreHeader header = sweep::make_store_header(plan, (dir / "sweep.toml").string());
  header.shard = shard.text();
  Store store = Store::create_or_resume(path, header);
  sweep::RunnerOptions options;
  options.shard = shard;
  tbb::task_arena(2).execute([&] { (void)sweep::run_sweep(plan, store, options); });
}

TEST(GroupCodec, EveryFieldOfEveryGroupSurvivesTheTripBitForBit) {
  const fs::path dir = testing::test_temp_dir("distributed");
  const Plan plan = make_plan(dir);
  int with_sensitivity = 0, with_dataset_metrics = 0, with_identifiability = 0;
  for (long long i = 0; i < plan.groups(); ++i) {
    const sweep::GroupRecord sent = sweep::run_group(plan, i);
    ASSERT_FALSE(sent.failed) << sent.message;
    const sweep::GroupRecord got = decode_group(encode_group(sent));
    const auto diff = sweep::compare_records(sent, got);
    EXPECT_TRUE(diff.empty()) << "group " << i << ": " << diff.front();
    // compare_records leaves out what may differ between two computations; a message must keep it too.
    EXPECT_EQ(got.index, sent.index);
    EXPECT_EQ(std::tie(got.part, got.split, got.fitset, got.model, got.optimizer, got.runs),
              std::tie(sent.part, sent.split, sent.fitset, sent.model, sent.optimizer, sent.runs));
    EXPECT_EQ(got.metric, sent.metric);
    EXPECT_EQ(std::bit_cast<std::uint64_t>(got.wall_time_s), std::bit_cast<std::uint64_t>(sent.wall_time_s));
    EXPECT_EQ(std::tie(got.dampbench_version, got.build_flags, got.spec_hash, got.dataset_hash),
              std::tie(sent.dampbench_version, sent.build_flags, sent.spec_hash, sent.dataset_hash));
    ASSERT_EQ(got.identifiability.has_value(), sent.identifiability.has_value());
    if (sent.identifiability) {
      EXPECT_EQ(got.identifiability->samples, sent.identifiability->samples);
    }
    with_sensitivity += sent.sensitivity.has_value();
    with_dataset_metrics += !sent.dataset_metrics.empty();
    with_identifiability += sent.identifiability.has_value();
  }
  // The sweep exercises every optional part of a record.
  EXPECT_GT(with_sensitivity, 0);
  EXPECT_GT(with_dataset_metrics, 0);
  EXPECT_GT(with_identifiability, 0);
}

/// A record unlike any the test sweep makes: failed with a message, many per-dataset metrics, no optional parts,
/// odd run numbers and flags; every number distinct.
sweep::GroupRecord unusual_record() {
  sweep::GroupRecord g;
  g.index = 123456789012LL;
  g.part = 2, g.split = 3, g.fitset = 4, g.model = 5, g.optimizer = 6, g.runs = 7;
  g.metric = kAllMetrics[kMetricCount - 1];
  g.task_key = 0xfedcba9876543210ULL;
  g.failed = true;
  g.message = "dataset 'x': a message\nover two lines";
  g.wall_time_s = 1.0 / 3, g.candidate_samples = 2.5e12, g.evaluations = 987654321;
  g.dampbench_version = "v", g.build_flags = "f", g.spec_hash = "s", g.dataset_hash = "d";
  for (int r = 0; r < 3; ++r) {
    sweep::RunRecord run;
    run.run = 10 * r + 1;
    run.best_value = -0.0 + r;
    for (int m = 0; m < kMetricCount; ++m) run.metrics[static_cast<std::size_t>(m)] = r + m / 7.0;
    run.params = {std::nan(""), 1e-300 * r, -5.0};
    run.evaluations = 42 + r;
    run.stop_reason = r == 1 ? "" : "stall";
    run.trace = {{1, 2.0}, {3 + r, 0.5}};
    run.at_local_optimum = r == 2;
    g.run_results.push_back(run);
  }
  for (int i = 0; i < 100; ++i) {  // more than the bytes that follow them: a length check by sizeof would refuse it
    sweep::DatasetMetricRecord d;
    d.run = i % 3, d.dataset = i, d.predicted = i % 2 == 0;
    for (int m = 0; m < kMetricCount; ++m) d.metrics[static_cast<std::size_t>(m)] = i * 100.0 + m;
    g.dataset_metrics.push_back(d);
  }
  return g;
}

TEST(GroupCodec, AnUnusualRecordSurvivesAndReencodesToTheSameBytes) {
  sweep::GroupRecord g = unusual_record();
  const std::string bytes = encode_group(g);
  const sweep::GroupRecord got = decode_group(bytes);
  // The encoding writes every field: equal bytes after a round trip mean every field came back.
  EXPECT_EQ(encode_group(got), bytes);
  EXPECT_EQ(got.message, g.message);
  EXPECT_EQ(got.run_results[1].run, 11);
  EXPECT_EQ(got.dataset_metrics[99].dataset, 99);
  EXPECT_TRUE(std::isnan(got.run_results[0].params[0]));
  EXPECT_FALSE(got.sensitivity.has_value());
  EXPECT_FALSE(got.identifiability.has_value());
  // With both optional parts.
  g.sensitivity = sweep::SensitivityRecord{7, {1, 2, 3}, {4, 5, 6}};
  Identifiability id;
  id.std_error = {0.1, INFINITY};
  id.relative_error = {0.2, INFINITY};
  id.correlation = {{1, -0.5}, {-0.5, 1}};
  id.flags = {{}, {"not identifiable", "at bound"}};
  id.samples = 333;
  g.identifiability = id;
  const std::string full = encode_group(g);
  EXPECT_EQ(encode_group(decode_group(full)), full);
  EXPECT_GT(full.size(), bytes.size());
}

TEST(GroupCodec, TruncatedOrPaddedMessagesAreRefused) {
  const fs::path dir = testing::test_temp_dir("distributed");
  const Plan plan = make_plan(dir);
  const std::string bytes = encode_group(sweep::run_group(plan, plan.groups() - 1));
  ASSERT_NO_THROW((void)decode_group(bytes));
  for (std::size_t cut : {std::size_t{0}, std::size_t{1}, std::size_t{7}, bytes.size() / 3, bytes.size() / 2, bytes.size() - 1})
    EXPECT_THROW((void)decode_group(std::string_view(bytes).substr(0, cut)), DataError) << "cut at " << cut;
  EXPECT_THROW((void)decode_group(bytes + "x"), DataError);
  // A length prefix far beyond the message (a corrupted count) is refused before anything is allocated.
  std::string corrupt = bytes;
  const std::size_t message_length_at = 8 + 5 * 4 + sizeof(Metric) + 4 + 8 + 1;  // after index .. failed
  for (int k = 0; k < 8; ++k) corrupt[message_length_at + static_cast<std::size_t>(k)] = '\x7f';
  EXPECT_THROW((void)decode_group(corrupt), DataError);
  // A metric number that names no metric.
  std::string bad_metric = bytes;
  const int metric_number = 1000;
  std::memcpy(bad_metric.data() + 8 + 5 * 4, &metric_number, sizeof metric_number);
  EXPECT_THROW((void)decode_group(bad_metric), DataError);
}

TEST(Shards, TextIsParsedOrRefusedWithTheExpectedForm) {
  EXPECT_EQ(sweep::parse_shard("2/3"), (Shard{1, 3}));
  EXPECT_EQ(sweep::parse_shard("1/1"), (Shard{0, 1}));
  EXPECT_EQ(sweep::parse_shard("8/8").text(), "8/8");
  for (const char* bad : {"0/3", "4/3", "a/3", "3", "1/0", "", "1/3x", "-1/3", "1//3"}) {
    const std::string message = testing::error_of([&] { (void)sweep::parse_shard(bad); });
    EXPECT_NE(message.find("expected i/n"), std::string::npos) << bad << ": " << message;
  }
}

TEST(Shards, CoverTheSweepOnceWithBalancedCost) {
  const fs::path dir = testing::test_temp_dir("distributed");
  const Plan plan = make_plan(dir);
  ASSERT_GE(plan.groups(), 6);
  double total = 0, largest = 0;
  for (long long i = 0; i < plan.groups(); ++i) {
    const double c = sweep::estimated_cost(plan, plan.group(i));
    EXPECT_GT(c, 0);
    total += c;
    largest = std::max(largest, c);
  }
  for (int n = 1; n <= 5; ++n) {
    std::vector<int> owners(static_cast<std::size_t>(plan.groups()), 0);
    for (int s = 0; s < n; ++s) {
      const auto in = sweep::shard_groups(plan, {s, n});
      double cost = 0;
      long long count = 0;
      for (long long i = 0; i < plan.groups(); ++i)
        if (in[static_cast<std::size_t>(i)]) {
          ++owners[static_cast<std::size_t>(i)];
          cost += sweep::estimated_cost(plan, plan.group(i));
          ++count;
        }
      EXPECT_GT(count, 0) << s + 1 << "/" << n;
      // Greedy assignment in decreasing cost: no shard exceeds the mean by more than one group.
      EXPECT_LE(cost, total / n + largest) << s + 1 << "/" << n;
      // The schedule of a shard lists exactly its groups, largest first.
      const auto order = sweep::schedule(plan, std::vector<char>(in.size(), 0), {s, n});
      EXPECT_EQ(static_cast<long long>(order.size()), count);
      for (std::size_t k = 1; k < order.size(); ++k)
        EXPECT_GE(sweep::estimated_cost(plan, plan.group(order[k - 1])), sweep::estimated_cost(plan, plan.group(order[k])));
    }
    for (long long i = 0; i < plan.groups(); ++i) EXPECT_EQ(owners[static_cast<std::size_t>(i)], 1) << "group " << i;
  }
}

/// Every group of two stores, compared number by number.
void expect_same_results(const std::string& a_path, const std::string& b_path) {
  const Store a = Store::open(a_path), b = Store::open(b_path);
  ASSERT_EQ(a.header().groups, b.header().groups);
  ASSERT_EQ(a.stored_groups(), a.header().groups);
  ASSERT_EQ(b.stored_groups(), b.header().groups);
  for (long long i = 0; i < a.header().groups; ++i) {
    const auto diff = sweep::compare_records(*a.group(i), *b.group(i));
    EXPECT_TRUE(diff.empty()) << "group " << i << ": " << diff.front();
  }
}

TEST(Merge, ThreeShardsMergeIntoTheStoreOfOneProcess) {
  const fs::path dir = testing::test_temp_dir("distributed");
  const Plan plan = make_plan(dir);
  run_into(plan, dir, (dir / "whole.sqlite").string());
  std::vector<std::string> parts;
  for (int s = 0; s < 3; ++s) {
    parts.push_back((dir / fmt::format("part{}.sqlite", s + 1)).string());
    run_into(plan, dir, parts.back(), {s, 3});
    EXPECT_EQ(Store::open(parts.back()).header().shard, fmt::format("{}/3", s + 1));
  }
  // When a shard finished its groups is kept through the merge (not replaced by the time of the merge).
  const std::string stamp = "2001-02-03T04:05:06Z";
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(parts[0].c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db, ("UPDATE groups SET finished_at = '" + stamp + "'").c_str(), nullptr, nullptr, nullptr), SQLITE_OK);
  sqlite3_close(db);
  // Two shards first (partial), then all three again: groups already merged are checked, not written twice.
  const MergeSummary first = merge_stores((dir / "merged.sqlite").string(), {parts[0], parts[1]});
  EXPECT_GT(first.missing, 0);
  const MergeSummary all = merge_stores((dir / "merged.sqlite").string(), parts);
  EXPECT_EQ(all.missing, 0);
  EXPECT_EQ(all.merged, first.missing);
  EXPECT_EQ(all.duplicates, first.merged);
  EXPECT_EQ(all.shards, (std::vector<std::string>{"1/3", "2/3", "3/3"}));
  EXPECT_EQ(Store::open((dir / "merged.sqlite").string()).header().shard, "");
  expect_same_results((dir / "whole.sqlite").string(), (dir / "merged.sqlite").string());
  const auto shard1 = Store::open(parts[0]).groups({.runs = false, .details = false});
  ASSERT_FALSE(shard1.empty());
  const Store merged = Store::open((dir / "merged.sqlite").string());
  for (const auto& g : shard1) EXPECT_EQ(merged.group(g.index)->finished_at, stamp) << "group " << g.index;
  EXPECT_NE(merged.group(Store::open(parts[1]).groups({.runs = false, .details = false}).front().index)->finished_at, stamp);
}

TEST(Merge, PartsOfAnotherSweepOrWithOtherNumbersAreRefused) {
  const fs::path dir = testing::test_temp_dir("distributed");
  const std::string part1 = (dir / "part1.sqlite").string(), other = (dir / "other.sqlite").string();
  {
    const Plan plan = make_plan(dir);
    run_into(plan, dir, part1, {0, 2});
  }
  {
    const Plan plan = make_plan(dir, 5);  // another seed: another spec hash
    run_into(plan, dir, other, {1, 2});
  }
  const std::string message =
      testing::error_of([&] { (void)merge_stores((dir / "merged.sqlite").string(), {part1, other}); });
  EXPECT_NE(message.find("another sweep spec"), std::string::npos) << message;
  EXPECT_NE(message.find(other), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(dir / "merged.sqlite"));  // nothing written before every part is checked

  // A copy of part 1 with one number changed by one ulp: the same group with other bits.
  const Plan plan = make_plan(dir);
  const std::string altered = (dir / "altered.sqlite").string();
  fs::copy_file(part1, altered);
  {
    Store store = Store::create_or_resume(altered, Store::open(part1).header());
    const auto stored = store.finished();
    const auto first = std::find(stored.begin(), stored.end(), 1) - stored.begin();
    sweep::GroupRecord g = *store.group(first);
    g.run_results[0].best_value = std::nextafter(g.run_results[0].best_value, 1e300);
    store.write(g);
  }
  const std::string differs =
      testing::error_of([&] { (void)merge_stores((dir / "merged2.sqlite").string(), {part1, altered}); });
  EXPECT_NE(differs.find("differs"), std::string::npos) << differs;
  EXPECT_NE(differs.find("best_value"), std::string::npos) << differs;
  // A shard's store is not resumed as another shard's or as the whole sweep's.
  sweep::StoreHeader whole = sweep::make_store_header(plan, (dir / "sweep.toml").string());
  EXPECT_THROW((void)Store::create_or_resume(part1, whole), StoreError);
}

}  // namespace
}  // namespace dampbench::distributed
