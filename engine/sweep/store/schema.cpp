#include "engine/sweep/store/schema.hpp"

#include <bit>
#include <charconv>
#include <chrono>
#include <ctime>
#include <string>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/model/metrics.hpp"

namespace dampbench::sweep::store_db {

// Doubles are stored as their 8 bytes: the blobs are read back on machines of the same byte order only.
static_assert(std::endian::native == std::endian::little, "store blobs are little-endian doubles");

const char* const kSchema = R"sql(
CREATE TABLE meta(key TEXT PRIMARY KEY, value TEXT NOT NULL);
CREATE TABLE parts(part INTEGER PRIMARY KEY, name TEXT, title TEXT, path TEXT, source TEXT, seed INTEGER, runs INTEGER);
CREATE TABLE models(part INTEGER, model INTEGER, name TEXT, model_id TEXT, fixture TEXT, laws TEXT, bounds TEXT,
                    params TEXT, PRIMARY KEY(part, model));
CREATE TABLE optimizers(part INTEGER, optimizer INTEGER, label TEXT, name TEXT, population INTEGER, iterations INTEGER,
                        settings TEXT, PRIMARY KEY(part, optimizer));
CREATE TABLE splits(part INTEGER, split INTEGER, name TEXT, PRIMARY KEY(part, split));
CREATE TABLE datasets(part INTEGER, dataset INTEGER, name TEXT, collection TEXT, label TEXT, path TEXT, samples INTEGER,
                      hash TEXT, variables TEXT, error TEXT, PRIMARY KEY(part, dataset));
CREATE TABLE fitsets(part INTEGER, split INTEGER, fitset INTEGER, label TEXT, fit TEXT, predict TEXT,
                     PRIMARY KEY(part, split, fitset));
CREATE TABLE groups(grp INTEGER PRIMARY KEY, part INTEGER, split INTEGER, fitset INTEGER, model INTEGER,
                    optimizer INTEGER, metric TEXT, runs INTEGER, task_key TEXT, status TEXT, message TEXT,
                    wall_time_s REAL, candidate_samples REAL, evaluations INTEGER, dampbench_version TEXT,
                    build_flags TEXT, spec_hash TEXT, dataset_hash TEXT, finished_at TEXT, laws TEXT);
CREATE TABLE runs(grp INTEGER, run INTEGER, best_value REAL, metrics BLOB, params BLOB, evaluations INTEGER,
                  stop_reason TEXT, trace BLOB, local_optimum INTEGER, PRIMARY KEY(grp, run)) WITHOUT ROWID;
CREATE TABLE dataset_metrics(grp INTEGER, run INTEGER, dataset INTEGER, role TEXT, metrics BLOB,
                             PRIMARY KEY(grp, run, dataset)) WITHOUT ROWID;
CREATE TABLE sensitivity(grp INTEGER PRIMARY KEY, dataset INTEGER, S BLOB, SP BLOB);
CREATE TABLE identifiability(grp INTEGER PRIMARY KEY, samples INTEGER, std_error BLOB, relative_error BLOB,
                             correlation BLOB, flags TEXT);
)sql";

const char* const kGroupColumns =
    "grp, part, split, fitset, model, optimizer, metric, runs, task_key, status, message, wall_time_s, "
    "candidate_samples, evaluations, dampbench_version, build_flags, spec_hash, dataset_hash, finished_at, laws";

std::string metric_list() {
  std::string s;
  for (Metric m : kAllMetrics) {
    if (!s.empty()) s += ',';
    s += metric_name(m);
  }
  return s;
}

std::string now_utc() {
  const auto t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

long long count(const std::string& text, std::string_view key) {
  if (text.empty()) return 0;
  // Readers size arrays by these counts; 10^8 groups would be a store of about 100 GB.
  constexpr std::uint64_t kMaxCount = 100'000'000;
  const std::uint64_t n = stored_integer(text, 10, key);
  if (n > kMaxCount)
    throw StoreError(fmt::format("store: {} holds {}, more than any store holds (10^8; a damaged store?)", key, n));
  return static_cast<long long>(n);
}

std::uint64_t stored_integer(const std::string& text, int base, std::string_view what) {
  std::uint64_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value, base);
  if (error != std::errc{} || end != text.data() + text.size() || text.empty())
    throw StoreError(fmt::format("store: {} holds '{}', not a base-{} integer (a damaged store?)", what, text, base));
  return value;
}

std::vector<double> trace_blob(const std::vector<TracePoint>& trace) {
  std::vector<double> v;
  v.reserve(2 * trace.size());
  for (const auto& p : trace) {
    v.push_back(std::bit_cast<double>(static_cast<std::uint64_t>(p.evaluations)));
    v.push_back(p.value);
  }
  return v;
}

std::vector<TracePoint> trace_points(const std::vector<double>& v) {
  std::vector<TracePoint> t(v.size() / 2);
  for (std::size_t i = 0; i < t.size(); ++i)
    t[i] = {static_cast<long long>(std::bit_cast<std::uint64_t>(v[2 * i])), v[2 * i + 1]};
  return t;
}

}  // namespace dampbench::sweep::store_db
