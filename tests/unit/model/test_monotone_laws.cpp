// Monotone law families for MR dampers (sat, hill, tanh, mono) and products of any single-variable laws
// (engine/model/parameter_law.cpp; their default bounds in engine/model/law_model.cpp): hand-computed values,
// monotone by construction inside the default bounds, text round trips, refused input, law models.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>

#include "engine/evaluation/batch_evaluator.hpp"
#include "engine/model/law_model.hpp"
#include "engine/model/parameter_law.hpp"
#include "engine/record/excitation.hpp"
#include "models/registry.hpp"
#include "tests/test_support.hpp"

namespace dampbench {
namespace {

using testing::error_of;

double at(const ParameterLaw& law, std::vector<double> c, double I, std::map<std::string, double> more = {}) {
  more["I"] = I;
  return law.evaluate(c.data(), more);
}

double at(std::string_view text, std::vector<double> c, double I) { return at(parse_law(text, "t"), std::move(c), I); }

}  // namespace

TEST(MonotoneLaws, HillKnownValues) {
  // a = 1, b = 2, h = 0.5: at I = h the law is halfway, a + b/2 = 2; at I = 1: 1 + 2/(1 + 0.5²) = 2.6.
  EXPECT_EQ(at("hill(I,2)", {1, 2, 0.5}, 0.5), 2.0);
  EXPECT_DOUBLE_EQ(at("hill(I,2)", {1, 2, 0.5}, 1.0), 2.6);
  EXPECT_EQ(at("hill(I,2)", {1, 2, 0.5}, 0.0), 1.0);   // 0^p: a, not NaN
  EXPECT_EQ(at("hill(I,2)", {1, 2, 0.5}, -0.3), 1.0);  // flat at a below 0
  EXPECT_EQ(at("hill(I,2)", {1, 2, 0.5}, 1e300), 3.0);  // x^p overflows: a + b, not inf/inf
  // fitted exponent p = 3: 1 + 2/(1 + 0.5³) = 1 + 16/9
  EXPECT_DOUBLE_EQ(at("hill(I)", {1, 2, 0.5, 3}, 1.0), 1.0 + 16.0 / 9.0);
  EXPECT_DOUBLE_EQ(at("hill(I,2.5)", {0, 1, 1}, 4.0), 32.0 / 33.0);  // 4^2.5 = 32
}

TEST(MonotoneLaws, SatAndTanhKnownValues) {
  // sat: a + b(1 − e^(−I/x0)); half the rise at I = x0·ln 2
  EXPECT_EQ(at("sat(I)", {10, 4, 0.5}, 0.0), 10.0);
  EXPECT_NEAR(at("sat(I)", {10, 4, 0.5}, 0.5 * std::log(2.0)), 12.0, 1e-14);
  EXPECT_DOUBLE_EQ(at("sat(I)", {10, 4, 0.5}, 1.0), 10.0 + 4.0 * (1.0 - std::exp(-2.0)));
  // tanh: exactly a at I = 0; a + b·tanh(x1/w) at I = x1; a + b(1 + tanh(x1/w)) far above
  EXPECT_EQ(at("tanh(I)", {1, 2, 0.4, 0.2}, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(at("tanh(I)", {1, 2, 0.4, 0.2}, 0.4), 1.0 + 2.0 * std::tanh(2.0));
  EXPECT_DOUBLE_EQ(at("tanh(I)", {1, 2, 0.4, 0.2}, 100.0), 1.0 + 2.0 * (1.0 + std::tanh(2.0)));
}

TEST(MonotoneLaws, MonoThroughCollinearKnotsIsTheLine) {
  // Values 1, 3, 5 at 0, 0.5, 1: every PCHIP slope is the common secant 4, so the law is 1 + 4I everywhere,
  // extrapolated linearly on both sides.
  const auto law = parse_law("mono(I,0,0.5,1)", "t");
  for (double I : {-0.5, 0.0, 0.1, 0.25, 0.5, 0.8, 1.0, 1.5}) EXPECT_NEAR(at(law, {1, 2, 2}, I), 1 + 4 * I, 1e-14) << I;
  EXPECT_EQ(at(law, {1, 2, 2}, 1.5), 7.0);
  EXPECT_EQ(at(law, {1, 2, 2}, -0.5), -1.0);
}

TEST(MonotoneLaws, MonoHandComputedPlateau) {
  // Values 0, 1, 1 at knots 0, 1, 2. Secants 1 and 0: the interior slope is 0 (a flat secant), the left end
  // slope ((2·1 + 1)·1 − 1·0)/2 = 1.5, the right end slope (3·0 − 1·1)/2 = −0.5 points against its secant → 0.
  // At I = 0.5 (t = ½): ½·0 + ½·1 + (⅛·1.5 − ⅛·0) = 0.6875; the plateau stays at 1; the left line has slope 1.5.
  const auto law = parse_law("mono(I,0,1,2)", "t");
  EXPECT_DOUBLE_EQ(at(law, {0, 1, 0}, 0.5), 0.6875);
  EXPECT_EQ(at(law, {0, 1, 0}, 1.5), 1.0);
  EXPECT_EQ(at(law, {0, 1, 0}, 3.0), 1.0);
  EXPECT_EQ(at(law, {0, 1, 0}, -1.0), -1.5);
  for (double I = 0; I <= 2; I += 0.01) EXPECT_LE(at(law, {0, 1, 0}, I), 1.0) << I;  // no overshoot
}

TEST(MonotoneLaws, MonoHandComputedSlopes) {
  // Values 0, 1, 5 at knots 0, 1, 3: secants 1 and 2. Interior slope (w1 + w2)/(w1/1 + w2/2) with w1 = 2·2 + 1,
  // w2 = 2 + 2·1: 9/7. End slopes ((2·1 + 2)·1 − 1·2)/3 = 2/3 and ((2·2 + 1)·2 − 2·1)/3 = 8/3.
  // Hermite at t = ½: rise = ½·Δ + h(⅛·m_k − ⅛·m_k+1).
  const auto law = parse_law("mono(I,0,1,3)", "t");
  const std::vector<double> c{0, 1, 4};
  EXPECT_NEAR(at(law, c, 0.5), 0.5 + (2.0 / 3.0 - 9.0 / 7.0) / 8.0, 1e-15);
  EXPECT_NEAR(at(law, c, 2.0), 1.0 + 2.0 + 2.0 * (9.0 / 7.0 - 8.0 / 3.0) / 8.0, 1e-15);
  EXPECT_NEAR(at(law, c, -1.0), -2.0 / 3.0, 1e-15);
  EXPECT_NEAR(at(law, c, 4.0), 5.0 + 8.0 / 3.0, 1e-15);
}

TEST(MonotoneLaws, MonoReproducesKnotValuesAndDoesNotOvershoot) {
  const std::vector<double> K{0.0, 0.1, 0.25, 0.5, 0.75, 1.0};
  const auto law = parse_law("mono(I,0,0.1,0.25,0.5,0.75,1)", "t");
  std::mt19937_64 rng(34);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<double> c{u(rng) * 1e4};
    for (std::size_t k = 1; k < K.size(); ++k) c.push_back(trial % 4 == 0 && k == 3 ? 0.0 : u(rng) * u(rng) * 1e5);
    std::vector<double> y{c[0]};
    for (std::size_t k = 1; k < K.size(); ++k) y.push_back(y.back() + c[k]);
    for (std::size_t k = 0; k < K.size(); ++k) ASSERT_EQ(at(law, c, K[k]), y[k]) << trial << " knot " << k;
    for (std::size_t k = 0; k + 1 < K.size(); ++k)
      for (int i = 0; i <= 50; ++i) {
        const double I = K[k] + (K[k + 1] - K[k]) * i / 50.0, v = at(law, c, I);
        ASSERT_GE(v, y[k]) << trial << " at " << I;  // between its knots' values: no overshoot
        ASSERT_LE(v, y[k + 1]) << trial << " at " << I;
      }
    // beyond the ends: straight lines with the end slopes
    const double left = at(law, c, -0.1), right = at(law, c, 1.1);
    EXPECT_NEAR(at(law, c, -0.2) - left, left - y[0], 1e-9 * y.back());
    EXPECT_NEAR(at(law, c, 1.2) - right, right - y.back(), 1e-9 * y.back());
  }
}

TEST(MonotoneLaws, MonotoneAndAboveTheLevelInsideTheDefaultBounds) {
  // The "by construction" claim: any coefficients inside the default bounds give a law that equals a at
  // I = 0, never drops below it and never decreases (here c1 of mrd.spencer, bounds [0, 1e6]).
  const Model& spencer = find_model("mrd.spencer");
  std::mt19937_64 rng(7);
  for (const char* text : {"sat(I)", "hill(I)", "hill(I,2)", "hill(I,1.5)", "tanh(I)", "mono(I,0,0.25,0.5,1)",
                           "prod(hill(I,2),sat(freq))", "prod(tanh(I),mono(amp,0,0.01,0.02))"}) {
    const ParameterLaw law = parse_law(text, "t");
    const LawModel m(spencer, {{"c1", law}});
    const int first = m.parameter_index("c1_Ia");
    const int count = static_cast<int>(law.coefficient_names("c1").size());
    for (int trial = 0; trial < 300; ++trial) {
      std::vector<double> c;
      for (int j = first; j < first + count; ++j) {
        const ParameterInfo& b = m.parameters()[static_cast<std::size_t>(j)];
        c.push_back(std::uniform_real_distribution<double>(b.lower, b.upper)(rng));
      }
      const std::map<std::string, double> others{{"freq", 2.5}, {"amp", 0.013}};
      const double at0 = at(law, c, 0.0, others);
      if (law.factors.size() == 1) {
        ASSERT_EQ(at0, c[0]) << text;
      }
      ASSERT_GE(at0, 0.0) << text;
      double previous = at0;
      for (int i = 1; i <= 300; ++i) {
        const double v = at(law, c, 0.01 * i, others);
        ASSERT_GE(v, previous) << text << " trial " << trial << " at I = " << 0.01 * i;
        previous = v;
      }
    }
  }
}

TEST(MonotoneLaws, DefaultBounds) {
  const Model& spencer = find_model("mrd.spencer");  // c1 in [0, 1e6] N·s/m, c0 in [0, 5e4]
  auto bounds = [&](const LawModel& m, const char* name) {
    const ParameterInfo& p = m.parameters()[static_cast<std::size_t>(m.parameter_index(name))];
    return std::pair{p.lower, p.upper};
  };
  const LawModel hill(spencer, parse_laws("c1=hill(I);c0=prod(hill(I,2),sat(freq),poly(amp,1))", "t"));
  EXPECT_EQ(bounds(hill, "c1_Ia"), std::pair(0.0, 1e6));
  EXPECT_EQ(bounds(hill, "c1_Ib"), std::pair(0.0, 2e6));
  EXPECT_EQ(bounds(hill, "c1_Ih"), std::pair(0.05, 2.0));
  EXPECT_EQ(bounds(hill, "c1_Ip"), std::pair(1.0, 4.0));
  // later factors stay near 1: levels and rises in [0, 2]; bends over freq's 5 Hz span
  EXPECT_EQ(bounds(hill, "c0_Ia"), std::pair(0.0, 5e4));
  EXPECT_EQ(bounds(hill, "c0_freqa"), std::pair(0.0, 2.0));
  EXPECT_EQ(bounds(hill, "c0_freqb"), std::pair(0.0, 2.0));
  EXPECT_EQ(bounds(hill, "c0_freqx0"), std::pair(0.05 * 5.0, 15.0));
  EXPECT_EQ(bounds(hill, "c0_amp0"), std::pair(0.0, 2.0));  // as for poly factors before
  EXPECT_EQ(bounds(hill, "c0_amp1"), std::pair(-2.0 / 0.02, 2.0 / 0.02));
  // units: levels and rises in the parameter's, bends in the variable's, exponents and later factors' levels pure
  auto unit = [&](const LawModel& m, const char* name) { return m.parameters()[static_cast<std::size_t>(m.parameter_index(name))].unit; };
  EXPECT_EQ(unit(hill, "c1_Ia"), "N*s/m");
  EXPECT_EQ(unit(hill, "c1_Ib"), "N*s/m");
  EXPECT_EQ(unit(hill, "c1_Ih"), "A");
  EXPECT_EQ(unit(hill, "c1_Ip"), "1");
  EXPECT_EQ(unit(hill, "c0_freqb"), "1");
  EXPECT_EQ(unit(hill, "c0_freqx0"), "Hz");
  EXPECT_EQ(unit(hill, "c0_amp1"), "N*s/m");  // poly keeps its labels
  const LawModel rest(spencer, parse_laws("c1=sat(I);c0=tanh(I);alpha=mono(I,0,0.5,1)", "t"));
  EXPECT_EQ(bounds(rest, "c1_Ix0"), std::pair(0.05, 3.0));
  EXPECT_EQ(bounds(rest, "c0_Ib"), std::pair(0.0, 5e4));  // tanh's bracket reaches 2: b up to M
  EXPECT_EQ(bounds(rest, "c0_Ix1"), std::pair(0.0, 2.0));
  EXPECT_EQ(bounds(rest, "c0_Iw"), std::pair(0.05, 2.0));
  EXPECT_EQ(bounds(rest, "alpha_Id2"), std::pair(0.0, 2e5));  // alpha in [0, 1e5]
  // poly keeps its bounds: the constant term [lo, hi], degree k ±2M/3^k in I
  const LawModel poly(spencer, parse_laws("c0=poly(I,2)", "t"));
  EXPECT_EQ(bounds(poly, "c0_I0"), std::pair(0.0, 5e4));
  EXPECT_EQ(bounds(poly, "c0_I2"), std::pair(-1e5 / std::pow(3.0, 2), 1e5 / std::pow(3.0, 2)));
}

TEST(MonotoneLaws, CoefficientNames) {
  auto names = [](const char* text) { return parse_law(text, "t").coefficient_names("c1"); };
  using V = std::vector<std::string>;
  EXPECT_EQ(names("hill(I)"), (V{"c1_Ia", "c1_Ib", "c1_Ih", "c1_Ip"}));
  EXPECT_EQ(names("hill(I,2)"), (V{"c1_Ia", "c1_Ib", "c1_Ih"}));
  EXPECT_EQ(names("sat(I)"), (V{"c1_Ia", "c1_Ib", "c1_Ix0"}));
  EXPECT_EQ(names("tanh(I)"), (V{"c1_Ia", "c1_Ib", "c1_Ix1", "c1_Iw"}));
  EXPECT_EQ(names("mono(I,0,0.5,1)"), (V{"c1_Ia", "c1_Id1", "c1_Id2"}));
  EXPECT_EQ(names("prod(hill(I,2),poly(amp,1))"), (V{"c1_Ia", "c1_Ib", "c1_Ih", "c1_amp0", "c1_amp1"}));
  // a lone power or gauss2 keeps its published names; in a product it names its variable
  EXPECT_EQ(names("power(freq)"), (V{"c1_k", "c1_p", "c1_c"}));
  EXPECT_EQ(names("prod(sat(I),power(freq))"), (V{"c1_Ia", "c1_Ib", "c1_Ix0", "c1_freqk", "c1_freqp", "c1_freqc"}));
}

TEST(MonotoneLaws, ProductsOfAnyFactors) {
  // hill(I,2) at I = h gives 2; (1 + 50·amp) at amp = 0.01 gives 1.5
  const auto law = parse_law("prod(hill(I,2),poly(amp,1))", "t");
  EXPECT_DOUBLE_EQ(at(law, {1, 2, 0.5, 1, 50}, 0.5, {{"amp", 0.01}}), 3.0);
  const auto three = parse_law("prod(sat(I), power(freq), mono(amp,0,0.02))", "t");
  const double s = 10 + 4 * (1 - std::exp(-2.0)), p = 2 * std::sqrt(1.5) - 1, m = 1 + 0.5 * (0.01 / 0.02);
  EXPECT_NEAR(at(three, {10, 4, 0.5, 2, 0.5, -1, 1, 0.5}, 1.0, {{"freq", 1.5}, {"amp", 0.01}}), s * p * m, 1e-12);
  EXPECT_TRUE(std::isnan(at(law, {1, 2, 0.5, 1, 50}, 0.5)));  // amp missing
}

TEST(MonotoneLaws, TextRoundTrips) {
  for (const char* text : {"hill(I,2)", "hill(I,2.5)", "hill(I)", "sat(amp)", "tanh(I)", "mono(I,0,0.25,0.5,1)",
                           "mono(I,0.001,0.1,0.30000000000000004)", "prod(hill(I,2),poly(amp,1),sat(freq))",
                           "prod(mono(I,-1,0.5,1e+20),power(freq))", "prod(poly(I,2),poly(amp,1),poly(freq,1))"}) {
    const auto law = parse_law(text, "t");
    EXPECT_EQ(law.text(), text);
    EXPECT_EQ(parse_law(law.text(), "t").text(), law.text());
  }
  EXPECT_EQ(parse_law(" prod( hill( I , 2 ) , mono(amp, 0, 0.02) )", "t").text(), "prod(hill(I,2),mono(amp,0,0.02))");
  EXPECT_EQ(parse_law("mono(I,0.001,0.1,0.30000000000000004)", "t").factors[0].knots[2], 0.1 + 0.2);
  EXPECT_EQ(parse_law("hill(I,2.5)", "t").factors[0].exponent, 2.5);
}

TEST(MonotoneLaws, BadInputIsReported) {
  const char* known = "(known: poly, prod, power, gauss2, sat, hill, tanh, mono, free, or a number)";
  EXPECT_EQ(error_of([] { parse_law("logistic(I)", "--laws c1"); }), std::string("--laws c1: unknown law 'logistic' ") + known);
  EXPECT_EQ(error_of([] { parse_law("prod(hill(I,2),spline(amp))", "--laws c1"); }),
            std::string("--laws c1: unknown law 'spline' ") + known);
  EXPECT_EQ(error_of([] { parse_law("hill(I,0)", "--laws c1"); }),
            "--laws c1: hill exponent must be above 0 and at most 8, got '0'");
  EXPECT_EQ(error_of([] { parse_law("hill(I,-2)", "--laws c1"); }),
            "--laws c1: hill exponent must be above 0 and at most 8, got '-2'");
  EXPECT_EQ(error_of([] { parse_law("hill(I,2,3)", "--laws c1"); }),
            "--laws c1: expected hill(VAR) or hill(VAR,P), got 'hill(I,2,3)'");
  EXPECT_EQ(error_of([] { parse_law("sat(I,1)", "--laws c1"); }), "--laws c1: expected sat(VAR), got 'sat(I,1)'");
  EXPECT_EQ(error_of([] { parse_law("tanh(T)", "--laws c1"); }),
            "--laws c1: unknown operating variable 'T' (known: I, V, phi, amp, freq, w, vamp)");
  EXPECT_EQ(error_of([] { parse_law("mono(I,0,1,0.5)", "--laws c1"); }),
            "--laws c1: mono knots must be strictly increasing (no repeats), got 0.5 after 1 in 'mono(I,0,1,0.5)'");
  EXPECT_EQ(error_of([] { parse_law("mono(I,0,0.5,0.5)", "--laws c1"); }),
            "--laws c1: mono knots must be strictly increasing (no repeats), got 0.5 after 0.5 in 'mono(I,0,0.5,0.5)'");
  EXPECT_EQ(error_of([] { parse_law("mono(I,0)", "--laws c1"); }),
            "--laws c1: expected mono(VAR,K1,K2,...,Kn) with 2 to 16 knots, got 'mono(I,0)'");
  EXPECT_NE(error_of([] { parse_law("mono(I,0,x)", "--laws c1"); }).find("--laws c1: mono knot 2"), std::string::npos);
  EXPECT_EQ(error_of([] { parse_law("prod(hill(I,2),poly(I,1))", "--laws c1"); }),
            "--laws c1: 'prod(hill(I,2),poly(I,1))' has two factors in I (each factor of a prod takes its own variable)");
  EXPECT_EQ(error_of([] { parse_law("prod(prod(poly(I,1)),poly(amp,1))", "--laws c1"); }),
            "--laws c1: a prod cannot hold another prod, got 'prod(poly(I,1))'");
  EXPECT_EQ(error_of([] { parse_law("prod(2,poly(I,1))", "--laws c1"); }),
            "--laws c1: a factor of prod must be a single-variable law such as poly(VAR,DEGREE) or hill(VAR,P), got '2'");
}

TEST(MonotoneLaws, SpencerWithHillLawEvaluatesLikeTheBaseModelAtTheLawsValue) {
  // mfm Table 3 at I = 0.5 A, with c1 = hill(I,2): a = 1.727e5, b = 2.815e5, h = 0.5 gives c1 = a + b/2.
  const Model& base = find_model("mrd.spencer");  // c0, c1, k0, k1, x0, alpha, beta, gamma, A, n
  // A=free: mfm Table 3's parametrization (A given), not the state gauge (docs/models.md)
  const LawModel law(base, parse_laws("c1=hill(I,2);A=free", "--laws"));
  const std::vector<double> coefficients{2990, 1.727e5, 2.815e5, 0.5, 42.83, 561.2, -6.678e-2, 118.725, 6079, 10830, 48760, 0.9929};
  const std::vector<double> params{2990, 1.727e5 + 2.815e5 / 2, 42.83, 561.2, -6.678e-2, 118.725, 6079, 10830, 48760, 0.9929};
  ASSERT_EQ(law.dim(), 12);
  const Signals sine = testing::sine_signals(0.01, 1, 2, 1000, {{"I", 0.5}});
  EXPECT_EQ(law.base_parameters(coefficients, sine), params);
  EXPECT_EQ(law.simulate(coefficients, sine), base.simulate(params, sine));
  // A record measured with c1 halved: the law model's metrics are the base model's, bit for bit.
  Dataset d;
  d.name = "I0.5";
  d.t_s = sine.t_s;
  d.x_m = sine.x_m;
  d.v_m_s = sine.v_m_s;
  d.a_m_s2 = sine.a_m_s2;
  d.operating = sine.operating;
  std::vector<double> measured = params;
  measured[1] *= 0.5;
  d.F_N = base.simulate(measured, sine);
  const Signals data = prepare_signals(d);
  CandidateBatch lb(law.dim(), 1), bb(base.dim(), 1);
  lb.set_candidate(0, coefficients);
  bb.set_candidate(0, params);
  std::vector<MetricRow> lr(1), br(1);
  BatchEvaluator(law, data).evaluate_all(lb, lr);
  BatchEvaluator(base, data).evaluate_all(bb, br);
  EXPECT_GT(lr[0][static_cast<std::size_t>(Metric::nrmse)], 0.003);
  for (std::size_t k = 0; k < lr[0].size(); ++k)
    EXPECT_EQ(std::bit_cast<std::uint64_t>(lr[0][k]), std::bit_cast<std::uint64_t>(br[0][k])) << k;
}

}  // namespace dampbench
