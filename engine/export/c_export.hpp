#pragma once
// An identified model as a dependency-free C99 pair (dampbench_model.h, dampbench_model.c) for a controller, a
// Simulink S-function or a real-time target: the coefficients built in, the laws evaluated from the operating
// variables at every step, the model's equations stepped by the scheme of `simulate --fixed-step` (fixed RK4
// sub-steps, inputs linear over the step), so that the two agree to rounding. The API:
//   #define DBM_NVARS, DBM_VAR_NAMES, DBM_NSTATES, DBM_SUBSTEPS
//   typedef struct { double s[DBM_NSTATES]; } dbm_state;
//   void   dbm_init(dbm_state *st, double x, double v, const double *vars);
//   double dbm_step(dbm_state *st, double x, double v, const double *vars, double dt);   force [N] at the step's end
//   double dbm_force(const dbm_state *st, double x, double v, const double *vars);      force [N] now (at dbm_init)
// vars[] in the order of DBM_VAR_NAMES hold over the step just ended (a command's zero-order hold).
#include <string>

#include "engine/model/model.hpp"

namespace dampbench::exporting {

struct CSource {
  std::string header, source;
};

/// The C pair of `model` at `params` with `substeps` RK4 sub-steps per dbm_step; `description` (where the model
/// came from) and `step_statement` (the dt checked, fixed_step_statement) go into the files' head comment.
/// InputError naming what the exporter does not cover: a base model other than mrd.bouc_wen, mrd.spencer,
/// mrd.magic_formula and mrd.bingham, a mono law, a law over a law.
CSource export_c(const Model& model, std::span<const double> params, int substeps, const std::string& description,
                 const std::string& step_statement);

/// InputError, as export_c gives it, for a model the exporter does not cover.
void require_exportable(const Model& model);

/// The base models the exporter writes.
std::vector<std::string> exported_models();

}  // namespace dampbench::exporting
