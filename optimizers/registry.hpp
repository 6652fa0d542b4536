#pragma once
// Optimizers by name (`--optimizer NAME` and sweep files), with their settings as "key" → "value" strings, read
// through each optimizer's table of settings (setting_table.hpp; `dampbench optimizers` lists every one with its
// type, default, allowed values and meaning):
//   pso, ga, aga, de, cmaes                                 optimizers/<name>/<name>.hpp (ga and aga: ga/)
//   ga-sqp, ga-lm   `global` (ga | cmaes: the population phase), that phase's settings, then their own
//                                                           optimizers/hybrid/ga_sqp.hpp, ga_lm.hpp
// Bound narrowing over conditions (mfm §5.1) is a procedure, not an optimizer: narrow_bounds() in
// optimizers/narrowing/narrowing.hpp, with any of these as its inner optimizer.
//
// Order of application: the optimizer's defaults, then `population` and `iterations` of the spec, then
// the named bundle (`preset` for ga, `variant` for pso), then every other setting. So a preset's own
// population and generations (lssvm: 50 and 500) replace the spec's fields — which always hold a value,
// the command line's defaults 50/100 when the user gave none — and only when the preset is given;
// explicit settings then override the preset's rates. For ga, aga and de, `iterations` counts
// generations (the initial population included): every optimizer costs population × iterations
// evaluations; the hybrids add their local phase's evaluations on top (each header says how many).
// For cmaes, `population` is the initial λ₀ and the size of every ask (0 = Hansen's default 4 + ⌊3 ln n⌋, n
// the free parameters) and `iterations` counts asks: population × iterations evaluations, restarts included
// (restarts = none may stop sooner); a restart's larger λ spans several asks.
#include <map>
#include <string>
#include <vector>

#include "engine/identification/optimizer.hpp"
#include "optimizers/cmaes/cmaes.hpp"
#include "optimizers/de/de.hpp"
#include "optimizers/ga/aga.hpp"
#include "optimizers/ga/ga.hpp"
#include "optimizers/hybrid/ga_lm.hpp"
#include "optimizers/hybrid/ga_sqp.hpp"
#include "optimizers/pso/pso.hpp"
#include "optimizers/setting_table.hpp"

namespace dampbench {

/// What the command line and presets say about the optimizer.
struct OptimizerSpec {
  std::string name = "pso";
  int population = 50;  ///< fvd paper N
  int iterations = 100; ///< fvd paper L (generations for ga, aga, de)
  std::map<std::string, std::string> settings = {};  ///< algorithm settings, e.g. {"pc", "0.6"}, {"preset", "lssvm"}
};

/// The known optimizer names, in the order of the "known:" lists of messages: pso, ga, aga, de, cmaes, ga-sqp,
/// ga-lm.
std::vector<std::string> optimizer_names();

/// Whether `name` ends each run with a local stage from the population's best (the hybrids ga-sqp and ga-lm).
bool has_local_stage(const std::string& name);

/// Validates the spec and returns a factory that makes one run's optimizer from its bounds and run key.
/// InputError: unknown optimizer ("unknown optimizer 'sa' (known: pso, ga, aga, de, cmaes, ga-sqp, ga-lm)"),
/// unknown setting ("ga: unknown setting 'pk' (known: pc, pm, ...)"), a value that is not a number / whole number / known
/// name (the message names the setting), or settings that the optimizer's validate() rejects.
OptimizerFactory make_optimizer_factory(const OptimizerSpec& spec);

/// The settings of `name` as `dampbench optimizers` and the guide list them: key, type, default, allowed values and
/// meaning, from the optimizer's tables (setting_table.hpp); a hybrid's global stage's (ga's and cmaes's) before its
/// own. InputError for an unknown optimizer.
std::vector<SettingRow> optimizer_setting_rows(const std::string& name);

/// The settings `name` reads with its default choices (a hybrid's with global = ga), in the order of the "known:"
/// list of its messages. InputError for an unknown optimizer.
std::vector<std::string> optimizer_settings(const std::string& name);

}  // namespace dampbench
