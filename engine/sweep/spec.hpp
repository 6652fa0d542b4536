#pragma once
// Sweep files (`dampbench run SWEEP.toml`): which models to identify on which datasets with which optimizers,
// how often, on which conditions to fit and which to predict, and which tables to write. The presets in
// datasets/presets/*.toml are sweep files.
//
// A file is read whole and validated before anything runs: every error names the file, the line, the key
// and what was expected ("crfd.toml:12: key 'models': unknown model 'crfd.x' (known: ...)"); unknown keys
// are errors. A file may instead `include` other sweep files; each included file is one part of the sweep
// with its own models, datasets and tables (all.toml runs every paper's preset in one store).
//
// Format (TOML; defaults in brackets):
//   name = "mfm"                          required; title = "..."
//   seed = 1 [1]   runs = 10 [50]         runs per task group (an optimizer's `runs` overrides)
//   metric = "nrmse" [of_abs]             or metrics = ["nrmse", "rmse"]: each optimized in its own tasks
//   models = ["mrd.bingham", ...]         ids (or law fixtures), or [[models]] tables:
//       name, model | fixture, laws = "c0=poly(I,1);n=2" | "auto", bounds = "c0=0:1e4,...", optimizers = ["ga"],
//       start = "per-file"; laws = "auto" chooses each group's laws as `fit --laws auto` does (engine/fit/law_selection.hpp);
//       narrow = { rounds = 3, from = "default" | "wide" }: the box of the mfm paper's bound narrowing over the group's
//       records (engine/fit/record_narrowing.hpp)
//   [bounds] "model name" = "p=lo:hi,..." (the fvd preset's form)
//   [optimizer] or [[optimizers]]:         label [name], name [pso], population [50], iterations [100],
//       runs, settings = { pc = 0.6 }, max_evaluations, target, stall_iterations
//   [[datasets]]: name (required), one of file = "a.csv" | files = [...] | glob = "dir/*.csv" (wildcards in the
//       file name), label, units, columns, transform ("slider-crank"), average ("cycles=10,drop=3"),
//       conditions ("utfsm"), set ("I=1"), required [true]. Paths are relative to the file; "@generated/"
//       names the synthetic grids, generated on first use (generated_dir), "@shared/" the shared real data
//       (shared_data_dir).
//       A glob's records are named by file stem.
//   [[splits]] (default: one split fitting every dataset alone): name, datasets (entry names), models,
//       optimizers, fit = { I = [0, 0.5], amp = 0.01 } or an array of such tables (any of), predict = {...},
//       by = "each" | "all" | ["I"], folds = "leave-setting" | "leave-one:I" (held-out folds of the fit datasets),
//       sensitivity = true | { points, range, objective, normalized, where }
//   tables = "fvd" [fvd] | ["runs", ...] | [[tables]] with kind, name, title, paper, split (name or list), models,
//       optimizers, metric, role (fit | predict), where, target_rel   (kinds: engine/sweep/tables.hpp)
//   [[regressions]]: name, model, split, optimizer, laws = "c_r=poly(phi,3)", where, paper
//   include = ["fvd.toml", ...]            (a file of parts: only name, title, include and include_optional,
//       parts whose missing data files are skipped with a note instead of refused)
//   extends = "mfm.toml"                  a part made of another file of the same folder: its keys, each replaced
//       whole by this file's (mfm_neutral.toml: the mfm preset's models, splits and tables on another grid)
// The spec hash covers everything but title, labels, tables and regressions, which may change on a resume.
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "engine/fit/record_narrowing.hpp"
#include "engine/fit/resolve_model.hpp"
#include "engine/model/bounds.hpp"
#include "engine/identification/identification.hpp"
#include "engine/model/metrics.hpp"
#include "engine/model/model.hpp"
#include "engine/record/record_options.hpp"
#include "optimizers/registry.hpp"

namespace dampbench::sweep {

struct DatasetSpec {
  std::string name;        ///< unique in the part: the entry's name (one file) or the file stem (files, glob)
  std::string collection;  ///< name of the [[datasets]] entry it came from
  std::string label;       ///< longer description for tables
  RecordOptions load;
};

/// A model to identify (engine/fit/resolve_model.hpp); its name is its label, unique in the part (default: the
/// model id).
/// A model fitted from another's fit (fdsp §5.2, step 2 of its identification): every parameter but `free` is held at
/// the best fit of model `from` in split `split` (its one fit set; the lowest of its optimizers' groups), and each
/// free parameter searches ±`first` (a fraction) around that fit's value. With `next` > 0 the fit sets of this
/// model's split are fitted in the ascending order of the law variable `order`, each within ±`next` around the fit
/// before it as well (engine/sweep/held_fit.hpp). With `mean`, the held values are the means over every fit set of
/// `split` (each its lowest group), as the crfd paper's eq. 4.4 takes its modified model's constants from its fits
/// of Tables 2–3, and the free parameters search their own bounds.
struct HoldSpec {
  std::string laws;  ///< the entry's own laws, as written (ModelSpec::laws adds the held parameters to them)
  std::string from, split;
  std::vector<std::string> free;
  double first = 0.4, next = 0;
  std::string order;
  bool mean = false;
};

struct ModelSpec : ModelChoice {
  std::vector<std::string> optimizers;  ///< optimizer labels this model is identified with (empty: all)
  /// "per-file": a law model's search starts from the laws fitted to each fit record's own fit, as `fit --start
  /// per-file` (engine/fit/record_start.hpp); "" from the box.
  std::string start;
  /// Parameters held at another model's fit; `laws` then also fixes them, at placeholders (the middle of their
  /// default bounds) that each group replaces by the fit's values (GroupRecord::laws keeps them).
  std::optional<HoldSpec> hold;
  /// `narrow = { rounds = 3, from = "default" }`: the law model searches the box of the mfm paper's bound narrowing
  /// over the group's records, from the laws fitted to its last round (engine/fit/record_narrowing.hpp).
  std::optional<NarrowingSpec> narrow;
};

struct OptimizerEntry {
  std::string label;  ///< unique in the part (default: the optimizer name)
  OptimizerSpec spec;
  Budget budget;      ///< max_evaluations, target, stall_iterations (no wall-time rule: it is not reproducible)
  int runs = 0;       ///< runs per task group (0: the part's runs)
  /// Restarts until the runs converge (engine/fit/auto_budget.hpp): `budget = "auto"`, or no budget key given.
  bool auto_budget = false;
  long long max_total_evaluations = 0;  ///< the automatic budget's cap (0: its default)
  /// `precision`: "mixed" (default), the population search in float32 lanes (IdentificationSettings::search_precision),
  /// or "double"; the key is in the spec's canonical text and its default in the hash's salt, so a store's spec hash
  /// tells the two apart.
  Precision search_precision = Precision::float32;
};

/// One condition: every listed variable takes one of its values and the dataset name is one of `names`
/// (when given). Values match with a relative tolerance of 1e-9.
struct Condition {
  std::vector<std::pair<std::string, std::vector<double>>> variables;
  std::vector<std::string> names;
};

/// A set of datasets: those matching any of the conditions (no condition: every dataset).
struct Selection {
  std::vector<Condition> any;
  [[nodiscard]] bool everything() const { return any.empty(); }
  [[nodiscard]] bool matches(const std::string& name, const std::map<std::string, double>& variables) const;
};

/// Differential sensitivity (crfd eqs. 4.1–4.3) of each identified parameter set of a split.
struct SensitivitySpec {
  bool enabled = false;
  int points = 21;
  double range = 0.5;
  std::string objective = "rms";  ///< rms or a metric name
  bool normalized = false;
  Selection where;                ///< conditions (fit datasets) it is computed on
};

/// Which tasks a part runs. Fit datasets (`fit` within `collections`) are grouped `by`: each dataset alone
/// (per-condition identification), all together (one law model over every condition), or by the values of
/// some operating variables (one fit per current, say). Each fit predicts the `predict` datasets that share
/// its values of the `by` variables (all of them for by = "each" or "all").
struct SplitSpec {
  enum class By { each, all, variables };
  std::string name;
  std::vector<std::string> collections, models, optimizers;  ///< empty: all
  Selection fit;
  std::optional<Selection> predict;
  By by = By::each;
  std::vector<std::string> by_variables;
  /// Held-out folds of the fit datasets (engine/fit/held_out.hpp make_folds): "leave-setting" or "leave-one:VAR";
  /// one fit set per fold, fitted on the other folds' datasets and predicting its own with the `predict` datasets of
  /// the value it leaves out. "" for none; implies by = "all".
  std::string folds;
  SensitivitySpec sensitivity;
};

/// A table the sweep writes (kinds: engine/sweep/tables.hpp).
struct TableSpec {
  std::string kind;
  std::string name;    ///< file stem replacing the kind in the tables' ids (optional)
  std::string title;   ///< optional replacement title
  std::string paper;   ///< the paper's table it reproduces, for summary.md ("crfd Table 8")
  std::vector<std::string> splits;  ///< restrict to these splits (empty: all)
  std::vector<std::string> models, optimizers;  ///< restrict (empty: all)
  std::string metric;  ///< metric shown (empty: the optimized metric)
  std::string role;    ///< errors: "fit", "predict" or "" (both)
  Selection where;     ///< restrict conditions
  double target_rel = 0.01;  ///< runtime: target = best known + max(target_rel·|best known|, 1e-12)
  std::vector<std::string> params;  ///< landscape: the two parameters varied
  double range = 0.4;               ///< landscape: ±range (a fraction) around the best run's values
  int points = 11;                  ///< landscape: grid points per parameter (odd: the best run at the centre)
};

/// Regression of identified per-condition parameters on operating variables (crfd Tables 5–7, mfm eqs. 5–11,
/// fdsp eqs. 13–14): each law's coefficients fitted by least squares.
struct RegressionSpec {
  std::string name;
  std::string model;      ///< model label whose per-condition fits are regressed
  std::string split;      ///< only fits of this split (empty: any)
  std::string optimizer;  ///< only this optimizer's fits (empty: any; the lowest metric per condition wins)
  std::string laws;       ///< "c_r=poly(phi,3);..." (engine/model/parameter_law.hpp)
  std::string paper;
  Selection where;
};

/// `[reproduction]`: the published numbers a part's tables stand beside (engine/sweep/reproduction.hpp), and what
/// its records are, which decides what a verdict on them shows.
struct ReproductionSpec {
  std::string published;  ///< the paper's numbers as printed (datasets/papers/*.toml), resolved
  std::string data;       ///< "real" or "synthetic"
  std::string truth;      ///< synthetic: what made the records (a model, a documented generator)
  bool truth_is_compared_model = false;  ///< the truth is one of the models compared: verdicts are recovery checks
  /// Why none of the paper's numbers can be set against ours (records of another damper than the paper's, such as
  /// a neutral truth's grid): every table is judged by its ranking alone, as a paper file's `numbers_not_comparable`.
  std::string numbers_not_comparable;
  /// The records are not at the paper's conditions (the papers' protocols on the real damper): each claim is judged on
  /// every row of our tables, in the order the claim states (`rows = "ours"`), and no number is set against the paper's.
  bool claims_on_our_rows = false;
  /// Our tables (by id) whose numbers cannot be set against the paper's, each with the reason, beside a judged rest:
  /// a command that knows its records sets it (errors in N of another damper than the paper's, where its relative
  /// errors are judged).
  std::vector<std::pair<std::string, std::string>> tables_not_comparable = {};
};

struct PartSpec {
  std::string path;    ///< file the part came from
  std::string source;  ///< its text (stored with the results; tables are re-read from it)
  std::string name, title;
  std::uint64_t seed = 1;
  int runs = 50;
  std::vector<Metric> metrics{Metric::of_abs};  ///< each metric is optimized in its own tasks
  std::vector<ModelSpec> models;
  std::vector<OptimizerEntry> optimizers;
  std::vector<DatasetSpec> datasets;
  std::vector<std::string> collections;  ///< [[datasets]] entry names, in order
  std::vector<SplitSpec> splits;         ///< at least one (default: every dataset, by = "each")
  std::vector<TableSpec> tables;
  std::vector<RegressionSpec> regressions;
  std::optional<ReproductionSpec> reproduction;
  std::string canonical;  ///< canonical JSON of what determines results (hashed)

  [[nodiscard]] int model_index(std::string_view name) const;      ///< -1 if absent
  [[nodiscard]] int optimizer_index(std::string_view label) const; ///< -1 if absent
  [[nodiscard]] int split_index(std::string_view name) const;      ///< -1 if absent
  /// The (model, optimizer) index pairs a split identifies: those its lists and the model's optimizers allow.
  [[nodiscard]] std::vector<std::pair<int, int>> pairs(const SplitSpec& split) const;
};

struct SweepSpec {
  std::string path, name, title;
  std::vector<PartSpec> parts;
  std::string hash;  ///< 16 hex digits over the parts' canonical forms: a store belongs to one hash
  std::vector<std::string> notes;  ///< optional datasets skipped because their files are missing
};

struct SpecOptions {
  /// Check that files exist and expand globs. Off when re-reading a stored spec for its tables.
  bool check_files = true;
  /// Treat every dataset entry as `required = false` (parts listed in `include_optional`).
  bool datasets_optional = false;
};

/// Reads and validates a sweep file; InputError names file, line, key and what was expected.
SweepSpec load_sweep(const std::string& path, const SpecOptions& options = {});
/// Same from text; `path` names the file in messages and anchors relative paths.
SweepSpec parse_sweep(std::string_view text, const std::string& path, const SpecOptions& options = {});

/// "@generated/..." → the synthetic grids' folder (generated_dir), "@shared/..." → the shared data folder
/// (env DAMPBENCH_SHARED_DATA_DIR, else the compiled-in ../shared/data beside the source tree), a relative
/// path → relative to `folder`. Pure: generates nothing (ensure_generated does).
std::string resolve_path(std::string_view text, const std::string& folder);
/// Where "@generated/" grids live: env DAMPBENCH_GENERATED_DIR, else
/// $XDG_CACHE_HOME (or ~/.cache)/dampbench/generated-<hash of generator_identity()>.
std::string generated_dir();
std::string shared_data_dir();
/// The build that generates grids: "dampbench <version> (<build flags>)".
std::string generator_identity();
/// For a path "@generated/<grid>/...": makes sure the grid exists in generated_dir() as this build makes it
/// (datasets/synthetic/grids.hpp), adding a note when it had to generate it; other paths are left alone.
void ensure_generated(std::string_view text, std::vector<std::string>& notes);

}  // namespace dampbench::sweep
