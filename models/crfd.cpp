// Controllable rotary fluid damper family (crfd paper, 000_54961175bc72b7db; docs/models.md (crfd)). Rotary
// records: x holds the rotation angle θ [rad], v = θ̇ [rad/s], a = θ̈ [rad/s²], F the torque T [N·m].
//   crfd.gvnem           eq. 3.6   generalized viscous – nonlinear elastic model     algebraic
//   crfd.gvnem_modified  eq. 4.4   GV–NEM with J, α, β, T_f, ξ fixed                  algebraic
//   crfd.kwok            eq. 7.1   Kwok model                                        algebraic
//   crfd.maxwell         eqs. 7.3–7.4 generalized Maxwell (spring and dashpot in series)  ODE in θ_k
#include <cmath>

#include "engine/kernels/algebraic_kernel.hpp"
#include "engine/kernels/ode_kernel.hpp"
#include "models/registry.hpp"

namespace dampbench::crfd {
namespace {

/// Per-sample quantities shared by the lanes.
struct Sample {
  double th, dth, ddth, sgn_th, sgn_dth, log_th, log_dth;
};
Sample prepare_sample(const Signals& s, std::size_t k) {
  return {s.x_m[k], s.v_m_s[k], s.a_m_s2[k], s.sgn_x[k], s.sgn_v[k], s.log_abs_x[k], s.log_abs_v[k]};
}

/// eq. 3.6: T = J·θ̈ + c_r·sgn(θ̇)|θ̇|^α + k_r·sgn(θ)|θ|^β + T_f·sgn(θ̇) + η·tanh(½(μ·θ̇ + ξ·θ)).
struct Gvnem {
  static constexpr int kParams = 9;
  using Sample = crfd::Sample;
  static const ModelInfo& info() {
    static const ModelInfo i{
        "crfd.gvnem", "crfd eq. 3.6",
        "T = J a + c_r sgn(v)|v|^alpha + k_r sgn(x)|x|^beta + T_f sgn(v) + eta tanh((mu v + xi x)/2)",
        {{"J", "kg*m^2", 0.0, 0.05, "kg*m^2"},
         {"c_r", "N*m/(rad/s)^alpha", 0.0, 30.0, "N*m/(rad/s)^alpha"},
         {"alpha", "1", 0.5, 1.2, "1"},
         {"k_r", "N*m/rad^beta", 0.0, 60.0, "N*m/rad^beta"},
         {"beta", "1", 0.5, 1.2, "1"},
         {"T_f", "N*m", 0.0, 0.2, "N*m"},
         {"eta", "N*m", 0.0, 2.0, "N*m"},
         {"mu", "s/rad", 0.0, 20.0, "s/rad"},
         {"xi", "1/rad", 0.0, 100.0, "1/rad"}}};
    return i;
  }
  static Sample prepare(const Signals& s, std::size_t k) { return prepare_sample(s, k); }
  template <class P>
  static double force(const P& p, int l, const Sample& s) {
    return p.p[0][l] * s.ddth + p.p[1][l] * s.sgn_dth * std::exp(p.p[2][l] * s.log_dth) +
           p.p[3][l] * s.sgn_th * std::exp(p.p[4][l] * s.log_th) + p.p[5][l] * s.sgn_dth +
           p.p[6][l] * std::tanh(0.5 * (p.p[7][l] * s.dth + p.p[8][l] * s.th));
  }
};

/// eq. 4.4: the GV–NEM with the low-sensitivity parameters fixed at their averages (J = 0.011,
/// α = 0.867, β = 0.880, T_f = 0.024, ξ = 48.786); the shared terms are computed once per sample.
struct GvnemModified {
  static constexpr int kParams = 4;
  static constexpr double kJ = 0.011, kAlpha = 0.867, kBeta = 0.880, kTf = 0.024, kXi = 48.786;
  struct Sample {
    double fixed_torque, viscous, elastic, dth, xi_th;
  };
  static const ModelInfo& info() {
    static const ModelInfo i{"crfd.gvnem_modified", "crfd eq. 4.4",
                             "T = 0.011 a + c_r sgn(v)|v|^0.867 + k_r sgn(x)|x|^0.880 + 0.024 sgn(v) + "
                             "eta tanh((mu v + 48.786 x)/2)",
                             {{"c_r", "N*m/(rad/s)^0.867", 0.0, 30.0, "N*m/(rad/s)^0.867"},
                              {"k_r", "N*m/rad^0.880", 0.0, 60.0, "N*m/rad^0.880"},
                              {"eta", "N*m", 0.0, 2.0, "N*m"},
                              {"mu", "s/rad", 0.0, 20.0, "s/rad"}}};
    return i;
  }
  static Sample prepare(const Signals& s, std::size_t k) {
    const auto q = prepare_sample(s, k);
    return {kJ * q.ddth + kTf * q.sgn_dth, q.sgn_dth * std::exp(kAlpha * q.log_dth),
            q.sgn_th * std::exp(kBeta * q.log_th), q.dth, kXi * q.th};
  }
  template <class P>
  static double force(const P& p, int l, const Sample& s) {
    return s.fixed_torque + p.p[0][l] * s.viscous + p.p[1][l] * s.elastic +
           p.p[2][l] * std::tanh(0.5 * (p.p[3][l] * s.dth + s.xi_th));
  }
};

/// eq. 7.1: T = c_r·θ̇ + k_r·θ + η·tanh(μ(θ̇ + ξ·sgn θ)) + T_r.
struct Kwok {
  static constexpr int kParams = 6;
  using Sample = crfd::Sample;
  static const ModelInfo& info() {
    static const ModelInfo i{"crfd.kwok", "crfd eq. 7.1 (Kwok et al. 2006)",
                             "T = c_r v + k_r x + eta tanh(mu (v + xi sgn(x))) + T_r",
                             {{"c_r", "N*m*s/rad", 0.0, 30.0, "N*m*s/rad"},
                              {"k_r", "N*m/rad", 0.0, 100.0, "N*m/rad"},
                              {"eta", "N*m", 0.0, 3.0, "N*m"},
                              {"mu", "s/rad", 0.0, 100.0, "s/rad"},
                              {"xi", "rad/s", -100.0, 100.0, "rad/s"},
                              {"T_r", "N*m", -1.0, 1.0, "N*m"}}};
    return i;
  }
  static Sample prepare(const Signals& s, std::size_t k) { return prepare_sample(s, k); }
  template <class P>
  static double force(const P& p, int l, const Sample& s) {
    return p.p[0][l] * s.dth + p.p[1][l] * s.th + p.p[2][l] * std::tanh(p.p[3][l] * (s.dth + p.p[4][l] * s.sgn_th)) +
           p.p[5][l];
  }
};

/// eqs. 7.3–7.4: spring k_r·sgn(θ_k)|θ_k|^β in series with dashpot c_r·sgn(θ̇_c)|θ̇_c|^α, θ = θ_c + θ_k.
/// The state is the spring deflection θ_k: dθ_k/dt = θ̇ − sgn(T)(|T|/c_r)^(1/α), T = k_r·sgn(θ_k)|θ_k|^β.
/// Stiff for small c_r or α (docs/models.md (numerical traps)): more sub-steps per stroke than the MR models.
struct Maxwell {
  static constexpr int kParams = 4, kStates = 1;
  static constexpr double kSubstepsPerStroke = 600;  // 2.1e-5 vs CVODE (tests/unit/kernels/test_ode_models.cpp); 1/400: 6.7e-5
  struct Context {};
  static const ModelInfo& info() {
    static const ModelInfo i{"crfd.maxwell", "crfd eqs. 7.3-7.4 (generalized Maxwell model)",
                             "T = k_r sgn(x_k)|x_k|^beta; dx_k/dt = v - sgn(T)(|T|/c_r)^(1/alpha)",
                             {{"c_r", "N*m/(rad/s)^alpha", 0.5, 30.0, "N*m/(rad/s)^alpha"},
                              {"k_r", "N*m/rad^beta", 1.0, 150.0, "N*m/rad^beta"},
                              {"alpha", "1", 0.3, 1.5, "1"},
                              {"beta", "1", 0.2, 1.5, "1"}}};
    return i;
  }
  static Context context(const Signals&) { return {}; }
  // (|T|/c_r)^(1/α) = exp((β/α)·log|θ_k| + (log k_r − log c_r)/α); sgn(T) = sgn(θ_k) for k_r > 0. The two
  // per-candidate factors are lane invariants, computed once per block.
  static constexpr int kLaneInvariants = 2, kBetaOverAlpha = 4, kLogRatioOverAlpha = 5;
  template <class P>
  static void lane_invariants(P& p) {
    for (std::size_t l = 0; l < std::size(p.p[0]); ++l) {
      p.p[kBetaOverAlpha][l] = p.p[3][l] / p.p[2][l];
      p.p[kLogRatioOverAlpha][l] = (std::log(p.p[1][l]) - std::log(p.p[0][l])) / p.p[2][l];
    }
  }
  template <class P, class Y, class DY>
  static void rhs(const P& p, int l, const Context&, double, double v, const Y& y, DY&& dy) {
    dy[0] = v - sign(y[0]) * std::exp(p.p[kBetaOverAlpha][l] * log_abs_for_pow(y[0]) + p.p[kLogRatioOverAlpha][l]);
  }
  template <class P, class Y>
  static double force(const P& p, int l, const Context&, double, double, const Y& y) {
    return p.p[1][l] * sign(y[0]) * abs_pow(y[0], p.p[3][l]);
  }
};

}  // namespace
}  // namespace dampbench::crfd

namespace dampbench {

std::vector<std::unique_ptr<Model>> make_crfd_models() {
  std::vector<std::unique_ptr<Model>> models;
  models.push_back(std::make_unique<AlgebraicModel<crfd::Gvnem>>());
  models.push_back(std::make_unique<AlgebraicModel<crfd::GvnemModified>>());
  models.push_back(std::make_unique<AlgebraicModel<crfd::Kwok>>());
  models.push_back(std::make_unique<OdeModel<crfd::Maxwell>>());
  return models;
}

}  // namespace dampbench
