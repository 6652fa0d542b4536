#include "engine/kernels/cvode_integrator.hpp"

#include <memory>
#include <stdexcept>
#include <string>

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

namespace dampbench {
namespace {

void check(int flag, const char* call) {
  if (flag < 0) throw std::runtime_error(std::string("CVODE: ") + call + " failed with flag " + std::to_string(flag));
}

int rhs_adapter(sunrealtype t, N_Vector y, N_Vector ydot, void* user_data) {
  const auto& rhs = *static_cast<const OdeRhs*>(user_data);
  const auto n = static_cast<std::size_t>(N_VGetLength_Serial(y));
  rhs(t, std::span<const double>(N_VGetArrayPointer_Serial(y), n), std::span<double>(N_VGetArrayPointer_Serial(ydot), n));
  return 0;
}

/// Owns the SUNDIALS objects of one integration and frees them in the right order.
struct CvodeSession {
  SUNContext ctx = nullptr;
  N_Vector y = nullptr;
  SUNMatrix A = nullptr;
  SUNLinearSolver LS = nullptr;
  void* mem = nullptr;
  ~CvodeSession() {
    if (mem) CVodeFree(&mem);
    if (LS) SUNLinSolFree(LS);
    if (A) SUNMatDestroy(A);
    if (y) N_VDestroy(y);
    if (ctx) SUNContext_Free(&ctx);
  }
};

}  // namespace

std::vector<std::vector<double>> integrate_cvode(const OdeRhs& rhs, std::vector<double> y0,
                                                 std::span<const double> times, const CvodeSettings& settings) {
  const auto n = static_cast<sunindextype>(y0.size());
  CvodeSession s;
  check(SUNContext_Create(nullptr, &s.ctx), "SUNContext_Create");
  s.y = N_VNew_Serial(n, s.ctx);
  for (sunindextype i = 0; i < n; ++i) NV_Ith_S(s.y, i) = y0[i];
  s.mem = CVodeCreate(CV_BDF, s.ctx);
  if (!s.mem) throw std::runtime_error("CVODE: CVodeCreate failed");
  check(CVodeInit(s.mem, rhs_adapter, times.empty() ? 0.0 : times[0], s.y), "CVodeInit");
  check(CVodeSetUserData(s.mem, const_cast<OdeRhs*>(&rhs)), "CVodeSetUserData");
  check(CVodeSStolerances(s.mem, settings.relative_tolerance, settings.absolute_tolerance), "CVodeSStolerances");
  check(CVodeSetMaxNumSteps(s.mem, settings.max_steps_per_output), "CVodeSetMaxNumSteps");
  s.A = SUNDenseMatrix(n, n, s.ctx);
  s.LS = SUNLinSol_Dense(s.y, s.A, s.ctx);
  check(CVodeSetLinearSolver(s.mem, s.LS, s.A), "CVodeSetLinearSolver");

  std::vector<std::vector<double>> out;
  out.reserve(times.size());
  for (std::size_t k = 0; k < times.size(); ++k) {
    if (k > 0) {
      // Stop at every output time: the inputs are piecewise linear with kinks there, and a step that
      // crosses them can skip a whole half cycle of a hysteretic state when the states at both ends of the
      // step are at rest (a saturated Bouc–Wen z before and after a reversal), with a tiny error estimate.
      if (settings.stop_at_each_time) check(CVodeSetStopTime(s.mem, times[k]), "CVodeSetStopTime");
      sunrealtype t_reached = 0;
      check(CVode(s.mem, times[k], s.y, &t_reached, CV_NORMAL), "CVode");
    }
    const double* y = N_VGetArrayPointer_Serial(s.y);
    out.emplace_back(y, y + n);
  }
  return out;
}

}  // namespace dampbench
