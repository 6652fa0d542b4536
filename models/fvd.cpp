// Fluid viscous damper family (fvd paper, 003_c8ee1dc8d3676469: "Mechanical models", eqs. 1, 2, 5, 6;
// docs/models.md (fvd)). The paper writes the law as m·ÿ + (damper force) = p, the force p applied by the
// actuator; the model force is therefore F = m·a + C·sgn(v)|v|^α + K1·x + K2·x².
//
// Units: SI inside (kg, N/(m/s)^α, N/m, N/m²); the paper's tables use kN/(mm/s)^α, kN/mm and kN/mm²,
// produced by to_paper_units. Default bounds cover a 750 kN device (Table 1: 750 kN at 460 mm/s).
#include <cmath>

#include "engine/kernels/algebraic_kernel.hpp"
#include "models/registry.hpp"

namespace dampbench::fvd {
namespace {

/// Per-sample quantities shared by every candidate lane, in the lanes' real type R (the laws run float32 lanes
/// too: engine/kernels/lane_kernel.hpp, Float32).
template <class R = double>
struct SampleOf {
  R x, x2, v, a, sgn_v, log_abs_v;
};
using Sample = SampleOf<double>;

template <class R = double>
SampleOf<R> prepare_sample(const Signals& s, std::size_t k) {
  const double x = s.x_m[k];
  return {static_cast<R>(x), static_cast<R>(x * x), static_cast<R>(s.v_m_s[k]), static_cast<R>(s.a_m_s2[k]),
          static_cast<R>(s.sgn_v[k]), static_cast<R>(s.log_abs_v[k])};
}

/// The generalized viscous laws write |v|^α = exp(α·log|v|), their one vector exp: each gives the exp's argument
/// (exp_argument) and its force from e = |v|^α (force_with_exp), and AlgebraicKernel runs the exps of 16 samples
/// back to back (engine/kernels/algebraic_kernel.hpp). α·log|v|:
template <class P, class R = typename P::Real>
R abs_v_pow_argument(const P& p, int l, int ialpha, const SampleOf<R>& s) {
  return p.p[ialpha][l] * s.log_abs_v;
}
/// C·sgn(v)|v|^α from e = |v|^α.
template <class P, class R = typename P::Real>
R generalized_viscous_force(const P& p, int l, int iC, const SampleOf<R>& s, R e) {
  return p.p[iC][l] * s.sgn_v * e;
}

// Parameter descriptions shared by the four laws.
const ParameterInfo kMass{"m", "kg", 0.0, 2000.0, "kg"};
const ParameterInfo kAlpha{"alpha", "1", 0.0, 1.0, "1"};
const ParameterInfo kK1{"K1", "N/m", 0.0, 1e8, "kN/mm"};
const ParameterInfo kK2{"K2", "N/m^2", 0.0, 1e9, "kN/mm^2"};
const ParameterInfo kCgen{"C", "N/(m/s)^alpha", 0.0, 1e7, "kN/(mm/s)^alpha"};

/// SI → paper units: C [N/(m/s)^α] → kN/(mm/s)^α is ÷(10³·10^(3α)); K1 ÷10⁶; K2 ÷10⁹.
std::vector<double> paper_units(std::span<const double> p, int iC, int ialpha, int iK1, int iK2) {
  std::vector<double> out(p.begin(), p.end());
  const double alpha = ialpha >= 0 ? p[ialpha] : 1.0;
  out[iC] = p[iC] / (1e3 * std::pow(1e3, alpha));
  if (iK1 >= 0) out[iK1] = p[iK1] / 1e6;
  if (iK2 >= 0) out[iK2] = p[iK2] / 1e9;
  return out;
}

/// What the four laws share: their samples, in any lane real type (float32 lanes too).
struct FvdLaw {
  using Sample = fvd::Sample;
  static constexpr bool kFloat32Lanes = true;
  template <class R = double>
  static SampleOf<R> prepare(const Signals& s, std::size_t k) { return prepare_sample<R>(s, k); }
};

/// The generalized viscous laws' one exp: α·log|v| with α in slot 2.
struct GeneralizedViscousLaw : FvdLaw {
  template <class P, class R = typename P::Real>
  static R exp_argument(const P& p, int l, const SampleOf<R>& s) { return abs_v_pow_argument(p, l, 2, s); }
};

/// fvd eq. 1, linear viscous: F = m·a + C·v.
struct LinearViscous : FvdLaw {
  static constexpr int kParams = 2;
  static const ModelInfo& info() {
    static const ModelInfo i{"fvd.linear_viscous", "fvd eq. 1", "F = m*a + C*v",
                             {kMass, {"C", "N*s/m", 0.0, 2e7, "kN/(mm/s)"}}};
    return i;
  }
  template <class P, class R = typename P::Real>
  static R force(const P& p, int l, const SampleOf<R>& s) {
    return p.p[0][l] * s.a + p.p[1][l] * s.v;
  }
  static std::vector<double> to_paper_units(std::span<const double> p) { return paper_units(p, 1, -1, -1, -1); }
};

/// fvd eq. 2, generalized viscous (Constantinou): F = m·a + C·sgn(v)|v|^α.
struct GeneralizedViscous : GeneralizedViscousLaw {
  static constexpr int kParams = 3;
  static const ModelInfo& info() {
    static const ModelInfo i{"fvd.generalized_viscous", "fvd eq. 2", "F = m*a + C*sgn(v)*|v|^alpha",
                             {kMass, kCgen, kAlpha}};
    return i;
  }
  template <class P, class R = typename P::Real>
  static R force_with_exp(const P& p, int l, const SampleOf<R>& s, R e) {
    return p.p[0][l] * s.a + generalized_viscous_force(p, l, 1, s, e);
  }
  static std::vector<double> to_paper_units(std::span<const double> p) { return paper_units(p, 1, 2, -1, -1); }
};

/// fvd eq. 5, generalized viscous – linear elastic (generalized Kelvin–Voigt): F = m·a + C·sgn(v)|v|^α + K1·x.
struct GvLinearElastic : GeneralizedViscousLaw {
  static constexpr int kParams = 4;
  static const ModelInfo& info() {
    static const ModelInfo i{"fvd.gv_linear_elastic", "fvd eq. 5", "F = m*a + C*sgn(v)*|v|^alpha + K1*x",
                             {kMass, kCgen, kAlpha, kK1}};
    return i;
  }
  template <class P, class R = typename P::Real>
  static R force_with_exp(const P& p, int l, const SampleOf<R>& s, R e) {
    return p.p[0][l] * s.a + generalized_viscous_force(p, l, 1, s, e) + p.p[3][l] * s.x;
  }
  static std::vector<double> to_paper_units(std::span<const double> p) { return paper_units(p, 1, 2, 3, -1); }
};

/// fvd eq. 6, generalized viscous – quadratic elastic (eq. 4 without K0):
/// F = m·a + C·sgn(v)|v|^α + K1·x + K2·x².
struct GvQuadraticElastic : GeneralizedViscousLaw {
  static constexpr int kParams = 5;
  static const ModelInfo& info() {
    static const ModelInfo i{"fvd.gv_quadratic_elastic", "fvd eq. 6",
                             "F = m*a + C*sgn(v)*|v|^alpha + K1*x + K2*x^2", {kMass, kCgen, kAlpha, kK1, kK2}};
    return i;
  }
  template <class P, class R = typename P::Real>
  static R force_with_exp(const P& p, int l, const SampleOf<R>& s, R e) {
    return p.p[0][l] * s.a + generalized_viscous_force(p, l, 1, s, e) + p.p[3][l] * s.x + p.p[4][l] * s.x2;
  }
  static std::vector<double> to_paper_units(std::span<const double> p) { return paper_units(p, 1, 2, 3, 4); }
};

}  // namespace
}  // namespace dampbench::fvd

namespace dampbench {

std::vector<std::unique_ptr<Model>> make_fvd_models() {
  std::vector<std::unique_ptr<Model>> models;
  models.push_back(std::make_unique<AlgebraicModel<fvd::LinearViscous>>());
  models.push_back(std::make_unique<AlgebraicModel<fvd::GeneralizedViscous>>());
  models.push_back(std::make_unique<AlgebraicModel<fvd::GvLinearElastic>>());
  models.push_back(std::make_unique<AlgebraicModel<fvd::GvQuadraticElastic>>());
  return models;
}

}  // namespace dampbench
