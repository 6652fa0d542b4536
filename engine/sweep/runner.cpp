#include "engine/sweep/runner.hpp"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <exception>
#include <filesystem>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

#include "engine/evaluation/batch_evaluator.hpp"
#include "engine/common/error.hpp"
#include "engine/evaluation/sensitivity.hpp"
#include "engine/fit/fit.hpp"
#include "engine/fit/law_selection.hpp"
#include "engine/fit/record_start.hpp"
#include "engine/sweep/fingerprint.hpp"
#include "engine/sweep/progress.hpp"

namespace dampbench::sweep {

namespace {

/// The records of a group, each loaded and checked against the model: the fit datasets, then the predicted ones.
std::vector<const Signals*> group_records(const PartPlan& part, const FitSet& fs, const Model& model) {
  auto checked = [&](int d) -> const Signals& {
    const LoadedDataset& ld = part.datasets[d];
    if (!ld.ok()) throw InputError(fmt::format("dataset '{}': {}", ld.signals.name, ld.error));
    check_record(model, ld.signals);
    return ld.signals;
  };
  std::vector<const Signals*> fit;
  for (int d : fs.fit) fit.push_back(&checked(d));
  for (int d : fs.predict) (void)checked(d);
  return fit;
}

/// Every metric of each run's best parameters on each fit dataset of a joint fit, and on each predicted dataset.
void dataset_metrics(const PartPlan& part, const FitSet& fs, const Model& model, const Identification& id,
                     GroupRecord& rec) {
  const int runs = static_cast<int>(id.runs.size());
  CandidateBatch best(model.dim(), runs);
  for (int r = 0; r < runs; ++r) best.set_candidate(r, id.runs[r].best_params);
  std::vector<std::pair<int, bool>> singles;
  if (fs.fit.size() > 1)
    for (int d : fs.fit) singles.emplace_back(d, false);
  for (int d : fs.predict) singles.emplace_back(d, true);
  std::vector<MetricRow> rows(runs);
  for (const auto& [d, predicted] : singles) {
    BatchEvaluator(model, part.datasets[d].signals).evaluate_all(best, rows);
    for (int r = 0; r < runs; ++r) rec.dataset_metrics.push_back({r, d, predicted, rows[r]});
  }
  sort_dataset_metrics(rec.dataset_metrics);
}

/// The split's differential sensitivity at the best run, when it asks for one on this (single) fit dataset.
std::optional<SensitivityRecord> group_sensitivity(const PartPlan& part, const GroupRef& g, const FitSet& fs,
                                                   const Model& model, const FitOutcome& fit) {
  const SensitivitySpec& sens = part.spec->splits[g.split].sensitivity;
  if (!sens.enabled || fs.fit.size() != 1) return std::nullopt;
  const Signals& record = part.datasets[fs.fit[0]].signals;
  if (!sens.where.matches(record.name, record.law_variables)) return std::nullopt;
  SensitivitySettings ss;
  ss.points = sens.points;
  ss.range = sens.range;
  ss.normalized = sens.normalized;
  if (sens.objective != "rms") ss.metric = parse_metric(sens.objective);
  const Sensitivity s = differential_sensitivity(model, fit.best().best_params, record, ss);
  return SensitivityRecord{fs.fit[0], s.S, s.SP};
}

/// A group's fit, and the law model its parameters belong to when the group chose its laws.
struct GroupFit {
  FitOutcome outcome;
  ResolvedModel chosen;  ///< laws = "auto": the chosen law model (engine/fit/law_selection.hpp); else empty
  std::string laws;      ///< its laws (GroupRecord::laws)
  /// laws = "auto", start = "per-file" or narrow: what the records' own fits (and the choice) cost before the joint fit
  PreFitEffort pre_fit;
  std::string note;  ///< narrow: what the narrowing did (GroupRecord::message)
  [[nodiscard]] const Model& model(const Model& part_model) const { return chosen.model ? *chosen.model : part_model; }
};

/// The caches the groups of one process share: records' own fits and groups' best runs.
struct Caches {
  RecordFitCache* record_fits = nullptr;
  GroupFitCache* group_fits = nullptr;
};

GroupFit fit_group(const Plan& plan, const GroupRef& g, const std::vector<const Signals*>& records, const Caches& caches);

constexpr std::string_view kHeldFitFailed = "the fit it holds to";

/// HeldValues of group `index`: a group made them before, or they are fitted here (and kept for the others).
HeldValues held_values(const Plan& plan, long long index, const Caches& caches) {
  if (auto found = caches.group_fits->find(index)) return *found;
  const GroupRef g = plan.group(index);
  const PartPlan& part = plan.parts()[g.part];
  const Model& model = *part.models[g.model].model;
  const auto records = group_records(part, part.splits[g.split].fitsets[g.fitset], model);
  try {
    const GroupFit fit = fit_group(plan, g, records, caches);
    HeldValues v = held_values_of(fit.model(model), fit.outcome.best(), *records.front());
    caches.group_fits->store(index, v);
    return v;
  } catch (const std::exception& e) {
    const std::string what = e.what();
    if (what.starts_with(kHeldFitFailed)) throw;  // a fit further down the chain: its message names it
    throw InputError(fmt::format("{}, {}: {}", kHeldFitFailed, plan.describe(g), what));
  }
}

/// The fit of a group (engine/fit): its model, fit datasets, optimizer and budget, keyed by the group's task key.
GroupFit fit_group(const Plan& plan, const GroupRef& g, const std::vector<const Signals*>& records, const Caches& caches) {
  const PartPlan& part = plan.parts()[g.part];
  const OptimizerEntry& opt = part.spec->optimizers[g.optimizer];
  FitRequest request;
  request.model = &part.models[g.model];
  request.records = records;
  request.optimizer = &part.factories[g.optimizer];
  request.settings.runs = g.runs;
  request.settings.seed = part.spec->seed;
  request.settings.task_key = g.task_key;
  request.settings.metric = g.metric;
  request.settings.budget = opt.budget;
  request.settings.search_precision = opt.search_precision;
  if (opt.auto_budget) request.auto_budget = AutoBudget{opt.spec, opt.max_total_evaluations, 0};
  const ModelSpec& entry = part.spec->models[g.model];
  GroupFit out;
  if (chooses_laws(entry)) {  // as `fit --laws auto`, at the entry's fixed budget (the spec refuses another)
    LawSearch search = law_search(request, *request.model->model, opt.spec.name);
    search.label = fmt::format("model '{}' (laws = \"auto\")", entry.name);
    search.record_fits = caches.record_fits;
    LawSelection selection;
    out.outcome = fit_with_auto_laws(search, out.chosen, selection);
    out.laws = chosen_laws_text(selection);
    out.pre_fit = selection.effort;
    return out;
  }
  if (entry.start == "per-file") {  // as `fit --start per-file`: from the laws fitted to each record's own fit
    LawSearch search = law_search(request, *request.model->model, opt.spec.name);
    search.record_fits = caches.record_fits;
    request.start = start_from_record_fits(search, entry, *request.model->model, &out.pre_fit);
  }
  if (entry.narrow) {  // the mfm paper's bound narrowing over the group's records (engine/fit/record_narrowing.hpp)
    NarrowedStart narrowed =
        narrowed_start(entry, *request.model->model, records, opt.spec, request.settings, *entry.narrow);
    request.box = std::move(narrowed.box);
    request.start = std::move(narrowed.start);
    out.pre_fit += narrowed.effort;
    out.note = std::move(narrowed.summary);
  }
  if (entry.hold) {  // from another group's fit (engine/sweep/held_fit.hpp)
    out.chosen = held_model(plan, g, [&](long long i) { return held_values(plan, i, caches); }, out.laws);
    request.model = &out.chosen;
  }
  out.outcome = run_fit(request);
  return out;
}

}  // namespace

GroupRecord run_group(const Plan& plan, long long index, RecordFitCache* record_fits, GroupFitCache* group_fits) {
  GroupFitCache own_group_fits;  // without a shared one: the fits a held group needs are made for it alone
  const Caches caches{record_fits, group_fits ? group_fits : &own_group_fits};
  const GroupRef g = plan.group(index);
  const PartPlan& part = plan.parts()[g.part];
  const FitSet& fs = part.splits[g.split].fitsets[g.fitset];
  GroupRecord rec;
  static_cast<GroupRef&>(rec) = g;
  rec.dampbench_version = dampbench_version();
  rec.build_flags = build_flags();
  rec.spec_hash = plan.spec().hash;
  rec.dataset_hash = plan.group_dataset_hash(g);
  try {
    const auto records = group_records(part, fs, *part.models[g.model].model);
    const GroupFit group_fit = fit_group(plan, g, records, caches);
    const FitOutcome& fit = group_fit.outcome;
    const Model& model = group_fit.model(*part.models[g.model].model);
    if (part.holds_any && std::isfinite(fit.best().best_value))  // for the groups that hold to this one
      caches.group_fits->store(index, held_values_of(model, fit.best(), *records.front()));
    rec.laws = group_fit.laws;
    const Identification& id = fit.identification;
    rec.wall_time_s = id.wall_time_s + group_fit.pre_fit.wall_time_s;
    rec.candidate_samples = id.candidate_samples + group_fit.pre_fit.candidate_samples;
    rec.evaluations = group_fit.pre_fit.evaluations;
    if (fit.auto_budget) rec.message = fit.auto_budget->summary();
    if (!group_fit.note.empty()) rec.message += (rec.message.empty() ? "" : "; ") + group_fit.note;
    for (int r = 0; r < g.runs; ++r) {
      rec.evaluations += id.runs[r].evaluations;
      rec.run_results.push_back(run_record(r, id.runs[r]));
    }
    dataset_metrics(part, fs, model, id, rec);
    // Standard errors, correlations and flags at the best run (what the params and regression tables mark).
    rec.identifiability = fit.identifiability;
    rec.sensitivity = group_sensitivity(part, g, fs, model, fit);
  } catch (const std::exception& e) {
    rec.failed = true;
    rec.message = e.what();
    rec.run_results.clear();
    rec.laws.clear();
    rec.dataset_metrics.clear();
    rec.sensitivity.reset();
    rec.identifiability.reset();
    rec.evaluations = 0;
    rec.candidate_samples = 0;
  }
  return rec;
}

namespace {
/// Paths are stored absolute, so that `report` and `verify` find the files from any working directory.
std::string absolute_path(const std::string& path) {
  if (path.empty()) return path;
  std::error_code ec;
  const auto p = std::filesystem::absolute(path, ec);
  return ec ? path : p.lexically_normal().string();
}
}  // namespace

StoreHeader make_store_header(const Plan& plan, const std::string& spec_path) {
  StoreHeader h;
  h.name = plan.spec().name;
  h.spec_hash = plan.spec().hash;
  h.spec_path = spec_path;
  h.dampbench_version = dampbench_version();
  h.build_flags = build_flags();
  h.groups = plan.groups();
  h.tasks = plan.tasks();
  for (int p = 0; p < static_cast<int>(plan.parts().size()); ++p) {
    const PartPlan& part = plan.parts()[p];
    const PartSpec& s = *part.spec;
    h.parts.push_back({s.name, s.title, absolute_path(s.path), s.source, s.seed, s.runs});
    for (int m = 0; m < static_cast<int>(s.models.size()); ++m) {
      StoreModel sm{p, s.models[m].name, s.models[m].model, s.models[m].fixture, s.models[m].laws, s.models[m].bounds, {}};
      for (const auto& info : part.models[m].model->parameters()) sm.params.push_back(info.name);
      h.models.push_back(std::move(sm));
    }
    for (const auto& o : s.optimizers)
      h.optimizers.push_back({p, o.label, o.spec.name, o.spec.population, o.spec.iterations, o.spec.settings});
    for (const auto& sp : s.splits) h.splits.emplace_back(p, sp.name);
    for (int d = 0; d < static_cast<int>(s.datasets.size()); ++d) {
      const auto& ds = s.datasets[d];
      const auto& ld = part.datasets[d];
      h.datasets.push_back({p, ds.name, ds.collection, ds.label, absolute_path(ds.load.path), ld.hash, ld.error,
                            static_cast<long long>(ld.signals.size()), ld.signals.law_variables});
    }
    for (int sp = 0; sp < static_cast<int>(part.splits.size()); ++sp)
      for (const auto& f : part.splits[sp].fitsets) h.fitsets.push_back({p, sp, f.label, f.fit, f.predict});
  }
  return h;
}

GroupWriter::GroupWriter(const Plan& plan, Store& store, const RunnerOptions& options)
    : plan_(plan), store_(store), options_(options), start_(std::chrono::steady_clock::now()) {
  const std::vector<char> done = store.finished();
  const std::vector<char> mine = shard_groups(plan, options.shard);
  long long tasks_done = 0;
  for (long long i = 0; i < plan.groups(); ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (!mine[k]) continue;
    const int runs = plan.group(i).runs;
    ++summary_.groups;
    summary_.tasks += runs;
    if (done[k]) {
      ++summary_.stored_before;
      tasks_done += runs;
    }
  }
  todo_ = schedule(plan, done, options.shard);
  bar_.emplace(options.progress, summary_.tasks, tasks_done);
}

void GroupWriter::write(const GroupRecord& r) {
  store_.write(r);
  ++summary_.ran;
  summary_.ran_tasks += r.runs;
  summary_.failed += r.failed;
  summary_.evaluations += r.evaluations;
  summary_.candidate_samples += r.candidate_samples;
  if (r.failed) bar_->log(fmt::format("failed: {}: {}", plan_.describe(plan_.group(r.index)), r.message));
  if (options_.on_group) options_.on_group(r, plan_.describe(plan_.group(r.index)));
  bar_->advance(r.runs, r.evaluations);
}

RunnerSummary GroupWriter::finish() {
  bar_->finish();
  summary_.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (options_.stop && options_.stop->load() && summary_.stored_before + summary_.ran < summary_.groups)
    summary_.interrupted = true;
  return summary_;
}

RunnerSummary run_sweep(const Plan& plan, Store& store, const RunnerOptions& options) {
  GroupWriter writer(plan, store, options);
  const std::vector<long long>& todo = writer.todo();
  std::size_t next = 0;
  // A store that cannot be written (full disk, ...) stops the sweep: no new group starts, the groups in flight
  // finish unstored, and the error is rethrown after the pipeline (an exception thrown through it would drop
  // the records in flight without destroying them).
  std::exception_ptr write_error;
  std::atomic<bool> write_failed{false};
  const auto tokens = static_cast<std::size_t>(2 * std::max(1, tbb::this_task_arena::max_concurrency()));
  using Record = std::shared_ptr<GroupRecord>;
  RecordFitCache record_fits;  // groups that fit the same records alone share those fits
  GroupFitCache group_fits;    // and the groups that others hold to (held_fit.hpp), their best runs
  tbb::parallel_pipeline(
      tokens,
      tbb::make_filter<void, long long>(tbb::filter_mode::serial_in_order,
                                        [&](tbb::flow_control& fc) -> long long {
                                          if (next >= todo.size() || write_failed.load(std::memory_order_acquire) ||
                                              (options.stop && options.stop->load())) {
                                            fc.stop();
                                            return -1;
                                          }
                                          return todo[next++];
                                        }) &
          tbb::make_filter<long long, Record>(tbb::filter_mode::parallel,
                                              [&](long long i) { return std::make_shared<GroupRecord>(run_group(plan, i, &record_fits, &group_fits)); }) &
          tbb::make_filter<Record, void>(tbb::filter_mode::serial_out_of_order, [&](const Record& r) {
            if (write_error) return;
            try {
              writer.write(*r);
            } catch (...) {
              write_error = std::current_exception();
              write_failed.store(true, std::memory_order_release);
            }
          }));
  RunnerSummary sum = writer.finish();
  if (write_error) std::rethrow_exception(write_error);
  return sum;
}

namespace {

std::atomic<bool> g_interrupted{false};

extern "C" void on_stop_signal(int) {
  if (g_interrupted.exchange(true)) _exit(130);
  const char msg[] = "\ndampbench: interrupted: finishing the task groups in flight (Ctrl-C again to quit now)\n";
  const ssize_t ignored = write(STDERR_FILENO, msg, sizeof msg - 1);
  (void)ignored;
}

void set_stop_handler(void (*handler)(int)) {
  struct sigaction sa {};
  sa.sa_handler = handler;
  sigemptyset(&sa.sa_mask);
  for (int sig : {SIGINT, SIGTERM}) sigaction(sig, &sa, nullptr);
}

}  // namespace

std::atomic<bool>& interrupt_flag() { return g_interrupted; }

void install_interrupt_handler() { set_stop_handler(on_stop_signal); }

void restore_interrupt_handler() { set_stop_handler(SIG_DFL); }

}  // namespace dampbench::sweep
