#include "engine/export/c_export.hpp"

#include <algorithm>
#include <utility>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/model/law_model.hpp"

namespace dampbench::exporting {
namespace {

/// A base model in C: its states, the right-hand side (fills dy[] from p[], x, v, y[]) and the force (returns it
/// from the same). The same arithmetic, in the same order, as the Law structs of models/mrd.cpp, so that the export
/// agrees with `simulate --fixed-step` to rounding (tests/unit/export: 1e-9 relative).
struct CModel {
  const char* id;
  int states;
  const char* rhs;
  const char* force;
};

constexpr CModel kModels[] = {
    {"mrd.bouc_wen", 1,
     "  dy[0] = dbm_bouc_wen_rate(y[0], dbm_abs_pow(y[0], p[7]), v, p[6], p[4], p[5]);\n",
     "  return p[0] * v + p[1] * (x - p[2]) + p[3] * y[0];\n"},
    {"mrd.spencer", 2,
     "  const double inv = 1.0 / (p[0] + p[1]);\n"
     "  dy[0] = (p[5] * y[1] + p[0] * v + p[2] * (x - y[0])) * inv;\n"
     "  dy[1] = dbm_bouc_wen_rate(y[1], dbm_abs_pow(y[1], p[9]), v - dy[0], p[8], p[6], p[7]);\n",
     "  const double inv = 1.0 / (p[0] + p[1]);\n"
     "  const double ydot = (p[5] * y[1] + p[0] * v + p[2] * (x - y[0])) * inv;\n"
     "  return p[1] * ydot + p[3] * (x - p[4]);\n"},
    {"mrd.magic_formula", 0, "",
     "  const double u = v + p[0] * fabs(x);\n"
     "  const double Bu = p[1] * u;\n"
     "  (void)y;\n"
     "  return p[3] * sin(p[2] * atan(Bu * (1.0 - p[4]) + p[4] * atan(Bu))) + p[5] * v + p[6] * x + p[7];\n"},
    {"mrd.bingham", 0, "", "  (void)x;\n  (void)y;\n  return p[0] * dbm_sign(v) + p[1] * v + p[2];\n"},
};

const CModel& c_model(const Model& base) {
  for (const auto& m : kModels)
    if (base.id() == m.id) return m;
  throw InputError(fmt::format("export: no C export of {} yet (covered: {})", base.id(), fmt::join(exported_models(), ", ")));
}

std::string number(double v) { return fmt::format("{:.17g}", v); }

/// One factor of a law as a C expression in the variable `x` (the C text of LawFactor::evaluate).
std::string factor_c(const LawFactor& f, const double* c, const std::string& x) {
  using F = LawFactor::Family;
  switch (f.family) {
    case F::poly: {  // Horner from 0.0, as LawFactor::evaluate
      std::string sum = "0.0";
      for (int k = f.degree; k >= 0; --k) sum = fmt::format("({} * {} + {})", sum, x, number(c[k]));
      return sum;
    }
    case F::power: return fmt::format("({} * pow({}, {}) + {})", number(c[0]), x, number(c[1]), number(c[2]));
    case F::gauss2:
      return fmt::format("dbm_gauss2({}, {}, {}, {}, {}, {}, {})", x, number(c[0]), number(c[1]), number(c[2]),
                         number(c[3]), number(c[4]), number(c[5]));
    case F::sat: return fmt::format("({} - {} * expm1(-{} / {}))", number(c[0]), number(c[1]), x, number(c[2]));
    case F::hill:
      return fmt::format("dbm_hill({}, {}, {}, {}, {})", x, number(c[0]), number(c[1]), number(c[2]),
                         number(f.exponent > 0 ? f.exponent : c[3]));
    case F::tanh:
      return fmt::format("({} + {} * (tanh(({} - {}) / {}) + tanh({} / {})))", number(c[0]), number(c[1]), x,
                         number(c[2]), number(c[3]), number(c[2]), number(c[3]));
    case F::mono: break;
  }
  throw InputError(fmt::format("export: no C export of a mono law ({}) yet", f.text()));
}

/// The body of dbm_parameters: p[] of the base model from vars[] (a law model) or constants (a base model).
std::string parameters_c(const Model& model, std::span<const double> params, const std::vector<std::string>& variables) {
  const auto* law = dynamic_cast<const LawModel*>(&model);
  std::string out;
  if (!law) {
    for (std::size_t j = 0; j < params.size(); ++j) out += fmt::format("  p[{}] = {};\n", j, number(params[j]));
    return out;
  }
  const auto var = [&](const std::string& name) {
    const auto i = std::find(variables.begin(), variables.end(), name) - variables.begin();
    return fmt::format("vars[{}]", i);
  };
  for (std::size_t j = 0; j < law->laws().size(); ++j) {
    const ParameterLaw& l = law->laws()[j];
    const double* c = params.data() + law->coefficient_offset(static_cast<int>(j));
    switch (l.kind) {
      case ParameterLaw::Kind::free: out += fmt::format("  p[{}] = {};\n", j, number(c[0])); break;
      case ParameterLaw::Kind::fixed: out += fmt::format("  p[{}] = {};\n", j, number(l.fixed_value)); break;
      case ParameterLaw::Kind::product: {
        out += "  prod = 1.0;\n";
        for (const auto& f : l.factors) {
          out += fmt::format("  prod *= {};\n", factor_c(f, c, var(f.variable)));
          c += f.size();
        }
        out += fmt::format("  p[{}] = prod;\n", j);
        break;
      }
    }
  }
  if (law->gauge_tied() >= 0) {  // the state gauge: the tied parameter is the sum, in the law model's order
    out += "  prod = 0.0;\n";
    for (int j : law->gauge_sum_of()) out += fmt::format("  prod += p[{}];\n", j);
    out += fmt::format("  p[{}] = prod;\n", law->gauge_tied());
  }
  return out;
}

/// Helper functions, written out only where the model uses them (-Wunused-function): name, C text.
constexpr std::pair<const char*, const char*> kHelpers[] = {
    {"dbm_sign(", "static double dbm_sign(double v) { return (double)(v > 0.0) - (double)(v < 0.0); }\n"},
    {"dbm_abs_pow(", "static double dbm_abs_pow(double z, double n) { return exp(n * log(fabs(z) + 1e-100)); }\n"},
    {"dbm_bouc_wen_rate(",
     "static double dbm_bouc_wen_rate(double z, double zn, double u, double A, double beta, double gamma) {\n"
     "  return -gamma * fabs(u) * dbm_sign(z) * zn - beta * u * zn + A * u;\n}\n"},
    {"dbm_gauss2(",
     "static double dbm_gauss2(double x, double a1, double b1, double c1, double a2, double b2, double c2) {\n"
     "  const double g1 = (x - b1) / c1, g2 = (x - b2) / c2;\n  return a1 * exp(-g1 * g1) + a2 * exp(-g2 * g2);\n}\n"},
    {"dbm_hill(",
     "static double dbm_hill(double x, double a, double b, double h, double p) {\n  if (x <= 0) return a;\n"
     "  return a + b / (1 + pow(h / x, p));\n}\n"},
};

/// The helpers `body` calls (dbm_sign too where dbm_bouc_wen_rate is).
std::string helpers_for(const std::string& body) {
  std::string out;
  const bool rate = body.find("dbm_bouc_wen_rate(") != std::string::npos;
  for (const auto& [name, text] : kHelpers)
    if (body.find(name) != std::string::npos || (rate && std::string(name) == "dbm_sign(")) out += text;
  return out;
}

/// RK4 over an interval in n sub-steps (the arithmetic of OdeLawStepper::advance), dbm_step without and with driver
/// lags (LawStepper::advance: u exact over each sub-step, the laws at its middle), dbm_init and dbm_force.
constexpr const char* kStep = R"c(
static void dbm_advance(const double *p, double x0, double v0, double x1, double v1, double dt, int n, double *y) {
  const double inv = 1.0 / n, h = dt * inv, dx = x1 - x0, dv = v1 - v0;
  double t[DBM_NSTATES], k1[DBM_NSTATES], k2[DBM_NSTATES], k3[DBM_NSTATES], k4[DBM_NSTATES];
  int i, j;
  for (i = 0; i < n && DBM_MODEL_STATES > 0; ++i) {
    const double a = i * inv, m = (i + 0.5) * inv, b = (i + 1) * inv;
    dbm_rhs(p, x0 + a * dx, v0 + a * dv, y, k1);
    for (j = 0; j < DBM_MODEL_STATES; ++j) t[j] = y[j] + 0.5 * h * k1[j];
    dbm_rhs(p, x0 + m * dx, v0 + m * dv, t, k2);
    for (j = 0; j < DBM_MODEL_STATES; ++j) t[j] = y[j] + 0.5 * h * k2[j];
    dbm_rhs(p, x0 + m * dx, v0 + m * dv, t, k3);
    for (j = 0; j < DBM_MODEL_STATES; ++j) t[j] = y[j] + h * k3[j];
    dbm_rhs(p, x0 + b * dx, v0 + b * dv, t, k4);
    for (j = 0; j < DBM_MODEL_STATES; ++j) y[j] += (h / 6.0) * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j]);
  }
}

#if DBM_NLAGS > 0
/* vars with each lagged variable at u[] */
static void dbm_lagged(const double *vars, const double *u, double *seen) {
  int j;
  for (j = 0; j < DBM_NVARS; ++j) seen[j] = vars[j];
  for (j = 0; j < DBM_NLAGS; ++j) seen[dbm_lag_var[j]] = u[j];
}
#endif

double dbm_step(dbm_state *st, double x, double v, const double *vars, double dt) {
  double p[DBM_NPARAMS];
  const double x0 = st->s[DBM_NSTATES - 2], v0 = st->s[DBM_NSTATES - 1];
#if DBM_NLAGS > 0
  const double inv = 1.0 / DBM_SUBSTEPS, h = dt * inv, dx = x - x0, dv = v - v0;
  double *u = st->s + DBM_MODEL_STATES, middle[DBM_NLAGS], seen[DBM_NVARS];
  int i, j;
  for (i = 0; i < DBM_SUBSTEPS; ++i) {
    const double a = i * inv, b = (i + 1) * inv;
    for (j = 0; j < DBM_NLAGS; ++j) {
      const double c = vars[dbm_lag_var[j]];
      middle[j] = c + (u[j] - c) * exp(-(0.5 * h) / dbm_lag_tau[j]);
      u[j] = c + (u[j] - c) * exp(-h / dbm_lag_tau[j]);
    }
    dbm_lagged(vars, middle, seen);
    dbm_parameters(seen, p);
    dbm_advance(p, x0 + a * dx, v0 + a * dv, x0 + b * dx, v0 + b * dv, h, 1, st->s);
  }
  dbm_lagged(vars, u, seen);
  dbm_parameters(seen, p);
#else
  dbm_parameters(vars, p);
  dbm_advance(p, x0, v0, x, v, dt, DBM_SUBSTEPS, st->s);
#endif
  st->s[DBM_NSTATES - 2] = x;
  st->s[DBM_NSTATES - 1] = v;
  return dbm_model_force(p, x, v, st->s);
}

void dbm_init(dbm_state *st, double x, double v, const double *vars) {
  int j;
  (void)vars;
  for (j = 0; j < DBM_NSTATES; ++j) st->s[j] = 0.0;
#if DBM_NLAGS > 0
  for (j = 0; j < DBM_NLAGS; ++j) st->s[DBM_MODEL_STATES + j] = vars[dbm_lag_var[j]]; /* u(0) = c(0) */
#endif
  st->s[DBM_NSTATES - 2] = x;
  st->s[DBM_NSTATES - 1] = v;
}

double dbm_force(const dbm_state *st, double x, double v, const double *vars) {
  double p[DBM_NPARAMS];
#if DBM_NLAGS > 0
  double seen[DBM_NVARS];
  dbm_lagged(vars, st->s + DBM_MODEL_STATES, seen);
  dbm_parameters(seen, p);
#else
  dbm_parameters(vars, p);
#endif
  return dbm_model_force(p, x, v, st->s);
}
)c";

/// DBM_NLAGS and, with lags, the variable index and τ of each (the τ of a free lag is its fitted coefficient).
std::string lags_c(const LawModel* law, std::span<const double> params, const std::vector<std::string>& variables) {
  if (!law || law->lags().empty()) return "#define DBM_NLAGS 0\n\n";
  std::string index, tau;
  for (const auto& lag : law->lags()) {
    const auto i = std::find(variables.begin(), variables.end(), lag.variable) - variables.begin();
    index += fmt::format("{}{}", index.empty() ? "" : ", ", i);
    tau += fmt::format("{}{}", tau.empty() ? "" : ", ", number(law->lag_tau(lag, params)));
  }
  return fmt::format("#define DBM_NLAGS {}\nstatic const int dbm_lag_var[DBM_NLAGS] = {{ {} }};\n"
                     "static const double dbm_lag_tau[DBM_NLAGS] = {{ {} }}; /* s */\n\n",
                     law->lags().size(), index, tau);
}

}  // namespace

std::vector<std::string> exported_models() {
  std::vector<std::string> out;
  for (const auto& m : kModels) out.emplace_back(m.id);
  return out;
}

void require_exportable(const Model& model) {
  const auto* law = dynamic_cast<const LawModel*>(&model);
  if (law && dynamic_cast<const LawModel*>(&law->base()))
    throw InputError(fmt::format("export: {} is a law model over a law model, which the C export does not cover", model.id()));
  c_model(law ? law->base() : model);
}

CSource export_c(const Model& model, std::span<const double> params, int substeps, const std::string& description,
                 const std::string& step_statement) {
  if (substeps < 1) throw InputError(fmt::format("--substeps: expected a whole number >= 1, got {}", substeps));
  require_exportable(model);
  const auto* law = dynamic_cast<const LawModel*>(&model);
  const Model& base = law ? law->base() : model;
  const CModel& cm = c_model(base);
  if (static_cast<int>(params.size()) != model.dim())
    throw InputError(fmt::format("export: {} values for {} parameters", params.size(), model.dim()));
  const std::vector<std::string> variables = law ? law->law_variables() : std::vector<std::string>{};
  std::string names;
  for (const auto& v : variables) names += fmt::format("{}\"{}\"", names.empty() ? "" : ", ", v);
  const std::string head = fmt::format(
      "/* {}: {} ({}), written by dampbench export.\n"
      " * {}\n"
      " * Scheme: {} fixed RK4 sub-steps per dbm_step, x and v linear over the step (dampbench simulate --fixed-step {}).\n"
      "{} */\n",
      model.id(), base.law(), base.citation(), description, substeps, substeps, step_statement);
  CSource out;
  out.header = head + fmt::format(R"c(#ifndef DAMPBENCH_MODEL_H
#define DAMPBENCH_MODEL_H

#define DBM_NVARS {}
#define DBM_VAR_NAMES {{ {} }}
#define DBM_MODEL_STATES {}
#define DBM_NLAGGED {}
#define DBM_NSTATES (DBM_MODEL_STATES + DBM_NLAGGED + 2) /* the model's states, the lagged variables, x and v */
#define DBM_SUBSTEPS {}

typedef struct {{ double s[DBM_NSTATES]; }} dbm_state;

/* Resets the states to rest at (x [m], v [m/s]); vars[] in the order of DBM_VAR_NAMES. */
void dbm_init(dbm_state *st, double x, double v, const double *vars);
/* Advances by dt [s] to (x, v) with vars[] held over the step; returns the force [N] at its end. */
double dbm_step(dbm_state *st, double x, double v, const double *vars, double dt);
/* The force [N] at the current states (after dbm_init: the force at rest). */
double dbm_force(const dbm_state *st, double x, double v, const double *vars);

#endif
)c",
                                  variables.size(), names.empty() ? "0" : names, cm.states, law ? law->lags().size() : 0, substeps);
  const std::string body =
      "static void dbm_parameters(const double *vars, double *p) {\n  double prod = 1.0;\n  (void)vars;\n  (void)prod;\n" +
      parameters_c(model, params, variables) + "}\n\n" +
      "static void dbm_rhs(const double *p, double x, double v, const double *y, double *dy) {\n"
      "  (void)p;\n  (void)x;\n  (void)v;\n  (void)y;\n  (void)dy;\n" + cm.rhs + "}\n\n" +
      "static double dbm_model_force(const double *p, double x, double v, const double *y) {\n" + cm.force + "}\n" + kStep;
  out.source = head + "#include <math.h>\n\n#include \"dampbench_model.h\"\n\n" +
               fmt::format("#define DBM_NPARAMS {}\n", base.dim()) + lags_c(law, params, variables) + helpers_for(body) + "\n" +
               body;
  return out;
}

}  // namespace dampbench::exporting
