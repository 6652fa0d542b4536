#include "engine/cli/bench_real_records.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <tbb/task_arena.h>

#include "engine/cli/bench_rate.hpp"
#include "engine/common/error.hpp"
#include "engine/common/key_values.hpp"
#include "engine/common/random.hpp"
#include "engine/common/table.hpp"
#include "engine/evaluation/batch_evaluator.hpp"
#include "engine/kernels/isa.hpp"
#include "engine/model/bounds.hpp"
#include "engine/model/law_model.hpp"
#include "engine/record/record_options.hpp"
#include "engine/sweep/spec.hpp"
#include "models/registry.hpp"

namespace dampbench::cli {
namespace {

constexpr int kCandidates = 256;  // the slowest row takes about 3 s per evaluation of them
constexpr std::uint64_t kSeed = 2024;
constexpr const char* kRecords[] = {"10mm1Hz1A", "2mm5Hz1A"};
constexpr const char* kModels[] = {"mrd.bouc_wen", "mrd.spencer"};

CandidateBatch uniform_in(const Model& model, const Bounds& box, std::uint64_t key) {
  CandidateBatch batch(model.dim(), kCandidates);
  RandomStream rng(key);
  for (int i = 0; i < kCandidates; ++i)
    for (int j = 0; j < model.dim(); ++j) batch.at(i, j) = rng.uniform(box.lower[j], box.upper[j]);
  return batch;
}

Signals load_utfsm(const std::string& dir, const std::string& name) {
  const std::string path = (std::filesystem::path(dir) / (name + ".txt")).string();
  if (!std::filesystem::exists(path))
    throw InputError(fmt::format("--workload real-records: no record {} (the UTFSM MR-damper tests; --data-dir, or the "
                                 "shared data folder DAMPBENCH_SHARED_DATA_DIR + /utfsm-mr-damper)",
                                 path));
  RecordOptions o;
  o.path = path;
  o.columns = "t,x,v,F";
  o.units = "x=mm,v=mm/s";
  o.conditions = "utfsm";
  return prepare_signals(load_record(o, true));
}

}  // namespace

int bench_real_records(const BenchOptions& o) {
  const std::string dir = o.data_dir.empty() ? sweep::shared_data_dir() + "/utfsm-mr-damper" : o.data_dir;
  std::vector<Signals> records;
  for (const char* name : kRecords) records.push_back(load_utfsm(dir, name));
  const Precision precision = o.lanes == "float32" ? Precision::float32 : Precision::float64;
  std::vector<std::string> wanted = o.models.empty() ? std::vector<std::string>(std::begin(kModels), std::end(kModels))
                                                     : split_list(o.models, "--models");

  nlohmann::ordered_json j;
  Table t{"bench_real_records",
          "Candidate-samples per second on measured records (dampbench bench --workload real-records, docs/performance.md)",
          {"model", "box", "record", "lanes", "2 threads", "masked"}, {}};
  tbb::task_arena two_threads(2);
  for (const std::string& id : wanted) {
    const Model& base = find_model(id);
    const LawModel gauged(base, {});
    if (!gauged.applied_gauge())
      throw InputError(fmt::format("--workload real-records: {} has no state gauge (models: {})", id,
                                   fmt::join(kModels, ", ")));
    const Signals* both[] = {&records[0], &records[1]};
    const Bounds joint = default_bounds(gauged, both), hull = default_bounds(gauged, both, RecordBox::hull);
    for (std::size_t r = 0; r < records.size(); ++r) {
      const Signals* one[] = {&records[r]};
      struct Case {
        const char* box;
        const Model& model;
        Bounds bounds;
      };
      for (const Case& c : {Case{"own", base, default_bounds(base, one)}, Case{"gauged, both", gauged, joint},
                            Case{"gauged, hull", gauged, hull}}) {
        const CandidateBatch batch =
            uniform_in(c.model, c.bounds, hash_key({kSeed, hash_name(c.model.id()), hash_name(c.box)}));
        const BatchEvaluator evaluator(c.model, records[r], 1, precision);
        std::vector<double> out(kCandidates);
        const double items = kCandidates * static_cast<double>(records[r].size());
        double two_rate = 0;
        for (int trial = 0; trial < o.trials; ++trial) {
          two_rate = std::max(two_rate, two_threads.execute([&] {
            return rate(items, o.min_time_s, [&] { evaluator.evaluate(batch, Metric::of_abs, out); });
          }));
        }
        const double masked =
            static_cast<double>(std::count_if(out.begin(), out.end(), [](double m) { return !std::isfinite(m); })) /
            kCandidates;
        const char* lanes = precision == Precision::float32 && c.model.has_float32_lanes() ? "float32" : "float64";
        j["rows"].push_back({{"model", id},
                             {"box", c.box},
                             {"record", kRecords[r]},
                             {"lanes", lanes},
                             {"cand_samples_per_s_2t", two_rate},
                             {"masked_share", masked}});
        t.rows.push_back({id, c.box, kRecords[r], lanes, fmt::format("{:.3g}", two_rate),
                          fmt::format("{:.0f} %", 100 * masked)});
        if (o.format == "md") std::cerr << fmt::format("  {}, {}, {} done\n", id, c.box, kRecords[r]);
      }
    }
  }
  j["machine"] = {{"vector_isa", std::string(isa_name(active_isa()))}, {"build", DAMPBENCH_BUILD_FLAGS}};
  if (o.format == "json") std::cout << j.dump(2) << "\n";
  else std::cout << t.to_markdown() << fmt::format("\nbuild {}; vector kernels {}\n", DAMPBENCH_BUILD_FLAGS, isa_summary());
  return 0;
}

}  // namespace dampbench::cli
