// The HTML report of the fvd preset (its targets: under 10 s on 2 cores and under 20 MB). Setup runs the fvd
// preset once into a temporary store (about 5 s on 2 cores); the benchmark times `store_report_html` on it —
// re-reading the four records, simulating each model's best run, the tables and the page — and reports the
// document's size in bytes (counter "bytes").
#include <benchmark/benchmark.h>

#include <filesystem>
#include <memory>
#include <string>

#include "engine/record/record_options.hpp"
#include "engine/report/store_report.hpp"
#include "engine/sweep/plan.hpp"
#include "engine/sweep/runner.hpp"
#include "engine/sweep/spec.hpp"

namespace {

using namespace dampbench;

const sweep::Loader kLoader = [](const RecordOptions& o) { return load_record(o, true); };

/// The fvd preset's store, written once per process into a temporary folder.
const sweep::Store& fvd_store() {
  static const std::unique_ptr<sweep::Store> store = [] {
    const auto dir = std::filesystem::temp_directory_path() / "dampbench_bench_report";
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    const std::string spec_path = std::string(DAMPBENCH_SOURCE_DIR) + "/datasets/presets/fvd.toml";
    const sweep::Plan plan(sweep::load_sweep(spec_path), kLoader);
    auto s = std::make_unique<sweep::Store>(
        sweep::Store::create_or_resume((dir / "store.sqlite").string(), sweep::make_store_header(plan, spec_path)));
    sweep::run_sweep(plan, *s);
    return s;
  }();
  return *store;
}

void BM_FvdPresetReport(benchmark::State& state) {
  const sweep::Store& store = fvd_store();
  std::size_t bytes = 0;
  for (auto _ : state) {
    const std::string html = report::store_report_html(store, kLoader);
    bytes = html.size();
    benchmark::DoNotOptimize(html.data());
  }
  state.counters["bytes"] = static_cast<double>(bytes);
}
BENCHMARK(BM_FvdPresetReport)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
