#pragma once
// `dampbench run SWEEP.toml`: presets (datasets/presets/*.toml) are sweep files (format in
// engine/sweep/spec.hpp). The run loads and checks the whole file, loads every dataset,
// opens (or resumes) the SQLite store, runs the task groups not yet stored, and writes the tables.
#include "engine/cli/commands.hpp"
#include "engine/sweep/plan.hpp"

namespace dampbench::cli {

/// Reads sweep records with the command line's loader (load_data: units, columns, slider-crank transform,
/// cycle averaging, UTFSM conditions, --set).
sweep::Loader sweep_loader();

}  // namespace dampbench::cli
