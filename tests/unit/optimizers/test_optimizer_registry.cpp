// Optimizer registry (optimizers/registry): names, settings parsing and messages, presets and variants;
// plus the shared optimizer test support (standard functions, the retry helper).
#include "optimizers/registry.hpp"

#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "optimizer_test_support.hpp"
#include "test_support.hpp"

namespace dampbench {
namespace {

using testing::error_of;

/// Everything a run asks, on a 3-D sphere, for the spec's optimizer.
std::vector<double> history_of(const OptimizerFactory& make, std::uint64_t seed = 1) {
  return testing::minimize(make, testing::sphere, testing::box(3, -5, 5), seed, true).history;
}

std::string spec_error(const OptimizerSpec& spec) {
  return error_of([&] { (void)make_optimizer_factory(spec); });
}

// A case no optimizer can pass: one generation (random sampling of 10 points) cannot reach 1e-10 on Rastrigin.
const testing::SuccessCase kImpossible{testing::kRastrigin, 5, 10, 1, 1e-10, 1, 5};
OptimizerFactory make_de(int population, int iterations) { return make_optimizer_factory({"de", population, iterations}); }

}  // namespace

// ---- names ------------------------------------------------------------------------------------------

TEST(OptimizerRegistry, ListsEveryOptimizer) {
  EXPECT_EQ(optimizer_names(), (std::vector<std::string>{"pso", "ga", "aga", "de", "cmaes", "ga-sqp", "ga-lm"}));
}

TEST(OptimizerRegistry, EveryNameConstructsAndRuns) {
  for (const std::string& name : optimizer_names()) {
    const OptimizerFactory make = make_optimizer_factory({name, 10, 4});
    const auto opt = make(testing::box(2, -1, 1), 7);
    ASSERT_NE(opt, nullptr) << name;
    EXPECT_EQ(opt->batch_size(), 10) << name;
    const auto run = testing::minimize(*opt, testing::sphere, 2);
    EXPECT_EQ(run.evaluations, 40) << name;
    EXPECT_TRUE(std::isfinite(run.best_value)) << name;
  }
}

TEST(OptimizerRegistry, DefaultSpecIsTheFvdPaperPso) {
  const OptimizerSpec spec;
  EXPECT_EQ(spec.name, "pso");
  EXPECT_EQ(spec.population, 50);
  EXPECT_EQ(spec.iterations, 100);
  EXPECT_TRUE(spec.settings.empty());
  PsoSettings s;
  s.population = 50;
  s.iterations = 100;
  EXPECT_EQ(history_of(make_optimizer_factory(spec)), history_of(testing::factory_of<Pso>(s)));
}

TEST(OptimizerRegistry, RejectsUnknownNames) {
  EXPECT_EQ(spec_error({"sa", 50, 100}), "unknown optimizer 'sa' (known: pso, ga, aga, de, cmaes, ga-sqp, ga-lm)");
  EXPECT_EQ(spec_error({"GA", 50, 100}), "unknown optimizer 'GA' (known: pso, ga, aga, de, cmaes, ga-sqp, ga-lm)");
  EXPECT_EQ(spec_error({"", 50, 100}), "unknown optimizer '' (known: pso, ga, aga, de, cmaes, ga-sqp, ga-lm)");
}

TEST(OptimizerRegistry, ValidatesPopulationAndIterations) {
  EXPECT_EQ(spec_error({"pso", 1, 100}), "pso: population must be at least 2, got 1");
  EXPECT_EQ(spec_error({"ga", 2, 100}), "ga: population must be at least 4, got 2");
  EXPECT_EQ(spec_error({"aga", 50, 0}), "aga: iterations (generations) must be at least 1, got 0");
  EXPECT_EQ(spec_error({"de", 3, 100}), "de: population must be at least 4, got 3");
}

// ---- settings ---------------------------------------------------------------------------------------

TEST(OptimizerRegistry, RejectsUnknownSettingKeys) {
  EXPECT_EQ(spec_error({"ga", 50, 100, {{"pk", "0.6"}}}),
            "ga: unknown setting 'pk' (known: preset, pc, pm, eta_c, eta_m, tournament, elites)");
  EXPECT_EQ(spec_error({"pso", 50, 100, {{"w", "0.5"}}}),
            "pso: unknown setting 'w' (known: variant, inertia, inertia_end, cognitive, social, vmax_fraction)");
  EXPECT_EQ(spec_error({"aga", 50, 100, {{"pc", "0.5"}}}),
            "aga: unknown setting 'pc' (known: k1, k2, k3, k4, pm_min, eta_c, eta_m, tournament, elites)");
  EXPECT_EQ(spec_error({"de", 50, 100, {{"f", "0.5"}}}), "de: unknown setting 'f' (known: strategy, F, CR)");
  // population and iterations are spec fields, not settings
  EXPECT_EQ(spec_error({"de", 50, 100, {{"population", "20"}}}),
            "de: unknown setting 'population' (known: strategy, F, CR)");
}

TEST(OptimizerRegistry, ParsesNumbersStrictly) {
  EXPECT_EQ(spec_error({"ga", 50, 100, {{"pc", "abc"}}}), "ga: setting 'pc': expected a number, got 'abc'");
  EXPECT_EQ(spec_error({"ga", 50, 100, {{"pc", "0.6x"}}}), "ga: setting 'pc': expected a number, got '0.6x'");
  EXPECT_EQ(spec_error({"ga", 50, 100, {{"pm", ""}}}), "ga: setting 'pm': expected a number, got ''");
  EXPECT_EQ(spec_error({"de", 50, 100, {{"F", "nan"}}}), "de: setting 'F': expected a finite number, got 'nan'");
  EXPECT_EQ(spec_error({"pso", 50, 100, {{"inertia", "1e999"}}}),
            "pso: setting 'inertia': number out of range, got '1e999'");
  EXPECT_EQ(spec_error({"ga", 50, 100, {{"tournament", "2.5"}}}),
            "ga: setting 'tournament': expected a whole number, got '2.5'");
  EXPECT_EQ(spec_error({"aga", 50, 100, {{"elites", "1e10"}}}),
            "aga: setting 'elites': expected a whole number, got '1e10'");
  EXPECT_EQ(spec_error({"ga", 50, 100, {{"pc", " 0.6 "}}}), "no error");  // surrounding blanks are trimmed
}

TEST(OptimizerRegistry, RejectsBadValuesWithTheOptimizersMessages) {
  EXPECT_EQ(spec_error({"ga", 50, 100, {{"pc", "1.5"}}}), "ga: pc must be in [0, 1], got 1.5");
  EXPECT_EQ(spec_error({"de", 50, 100, {{"F", "0"}}}), "de: F must be in (0, 2], got 0");
  EXPECT_EQ(spec_error({"aga", 50, 100, {{"k1", "2"}}}), "aga: k1 must be in [0, 1], got 2");
  EXPECT_EQ(spec_error({"ga", 50, 100, {{"tournament", "1"}}}), "ga: tournament must be at least 2, got 1");
  EXPECT_EQ(spec_error({"pso", 50, 100, {{"vmax_fraction", "-1"}}}), "pso: vmax_fraction must be a finite number > 0, got -1");
  EXPECT_EQ(spec_error({"de", 50, 100, {{"strategy", "rand2bin"}}}),
            "de: unknown strategy 'rand2bin' (known: rand1bin, best1bin, currenttobest1bin)");
  EXPECT_EQ(spec_error({"pso", 50, 100, {{"variant", "ring"}}}),
            "pso: unknown variant 'ring' (known: inertia, constriction, linear_inertia)");
  EXPECT_EQ(spec_error({"ga", 50, 100, {{"preset", "fvd"}}}), "ga: unknown preset 'fvd' (known: lssvm)");
}

/// A value the listed range refuses: above a closed upper end, at an open lower end, below a closed one.
std::string outside(const std::string& allowed) {
  double a = 0, b = 0;
  char open = 0;
  if (std::sscanf(allowed.c_str(), "in %c%lf, %lf", &open, &a, &b) == 3) return fmt::format("{:g}", b + 1);
  if (std::sscanf(allowed.c_str(), "a finite number >= %lf", &a) == 1) return fmt::format("{:g}", a - 1);
  if (std::sscanf(allowed.c_str(), "a finite number > %lf", &a) == 1) return fmt::format("{:g}", a);
  if (std::sscanf(allowed.c_str(), "at least %lf", &a) == 1) return fmt::format("{:g}", a - 1);
  if (std::sscanf(allowed.c_str(), "%lf or %lf", &a, &b) == 2) return fmt::format("{:g}", b + 1);
  return "";
}

// The listed table is the one the registry reads: in the order the parser knows the keys (a hybrid's cmaes rows
// apply with global = cmaes), each number setting's default is accepted when given explicitly, a value outside its
// listed range is refused with the setting's name and that range, and every name of a choice is accepted.
TEST(OptimizerRegistry, ListedSettingsAreTheOnesReadAndTheirRangesAreChecked) {
  for (const std::string& name : optimizer_names()) {
    std::vector<std::string> read_with_default_global;
    for (const SettingRow& row : optimizer_setting_rows(name)) {
      const bool cmaes_phase = row.meaning.starts_with("with global = cmaes");
      if (!cmaes_phase) read_with_default_global.push_back(row.key);
      const auto spec = [&](const std::string& value) {
        OptimizerSpec s{name, 50, 100, {{row.key, value}}};
        if (cmaes_phase) s.settings["global"] = "cmaes";
        return s;
      };
      const std::string where = name + " " + row.key;
      if (row.type == "choice") {
        for (std::string rest = row.allowed; !rest.empty();) {
          const std::size_t comma = rest.find(", ");
          const std::string choice = rest.substr(0, comma);
          EXPECT_EQ(spec_error(spec(choice)), "no error") << where << " = " << choice;
          rest = comma == std::string::npos ? "" : rest.substr(comma + 2);
        }
        continue;
      }
      char* end = nullptr;
      std::strtod(row.default_value.c_str(), &end);
      if (!row.default_value.empty() && *end == 0) {
        EXPECT_EQ(spec_error(spec(row.default_value)), "no error") << where << " = its default " << row.default_value;
      }
      const std::string bad = outside(row.allowed);
      if (bad.empty()) continue;  // ga-sqp's constraint: a number > 0 or off, checked by its own message
      EXPECT_NE(spec_error(spec(bad)).find(row.key + " must be " + row.allowed), std::string::npos)
          << where << " = " << bad << ": " << spec_error(spec(bad));
    }
    EXPECT_EQ(read_with_default_global, optimizer_settings(name)) << name;
  }
}

TEST(OptimizerRegistry, SettingsReachTheOptimizer) {
  GaSettings ga;
  ga.population = 12;
  ga.generations = 6;
  ga.pc = 0.6;
  ga.pm = 0.2;
  ga.eta_c = 5;
  ga.eta_m = 30;
  ga.tournament = 3;
  ga.elites = 2;
  EXPECT_EQ(history_of(make_optimizer_factory({"ga", 12, 6, {{"pc", "0.6"}, {"pm", "0.2"}, {"eta_c", "5"},
                                                             {"eta_m", "30"}, {"tournament", "3"}, {"elites", "2"}}})),
            history_of(testing::factory_of<Ga>(ga)));
  EXPECT_NE(history_of(make_optimizer_factory({"ga", 12, 6, {{"pc", "0.7"}}})), history_of(testing::factory_of<Ga>(ga)));

  AgaSettings aga;
  aga.population = 12;
  aga.generations = 6;
  aga.k1 = 0.9;
  aga.k2 = 0.4;
  aga.k3 = 0.8;
  aga.k4 = 0.3;
  aga.pm_min = 0.01;
  EXPECT_EQ(history_of(make_optimizer_factory(
                {"aga", 12, 6, {{"k1", "0.9"}, {"k2", "0.4"}, {"k3", "0.8"}, {"k4", "0.3"}, {"pm_min", "0.01"}}})),
            history_of(testing::factory_of<Aga>(aga)));

  DeSettings de;
  de.population = 12;
  de.generations = 6;
  de.strategy = DeStrategy::currenttobest1bin;
  de.F = 0.7;
  de.CR = 0.3;
  EXPECT_EQ(history_of(make_optimizer_factory(
                {"de", 12, 6, {{"strategy", "currenttobest1bin"}, {"F", "0.7"}, {"CR", "0.3"}}})),
            history_of(testing::factory_of<De>(de)));

  PsoSettings pso;
  pso.population = 12;
  pso.iterations = 6;
  pso.inertia = 0.8;
  pso.inertia_end = 0.3;
  pso.cognitive = 1.2;
  pso.social = 1.7;
  pso.vmax_fraction = 0.25;
  EXPECT_EQ(history_of(make_optimizer_factory({"pso", 12, 6,
                                               {{"inertia", "0.8"}, {"inertia_end", "0.3"}, {"cognitive", "1.2"},
                                                {"social", "1.7"}, {"vmax_fraction", "0.25"}}})),
            history_of(testing::factory_of<Pso>(pso)));
}

// ---- presets and variants ----------------------------------------------------------------------------

// preset=lssvm sets pc 0.6, pm 0.03, population 50 and 500 generations (SBX η_c 15, one elite); its population and generations
// replace the spec's fields (which always hold the command line's values), explicit settings override its rates.
TEST(OptimizerRegistry, LssvmPresetApplies) {
  const OptimizerFactory make = make_optimizer_factory({"ga", 20, 10, {{"preset", "lssvm"}}});
  const auto opt = make(testing::box(1, -1, 1), 1);
  EXPECT_EQ(opt->batch_size(), 50);
  const auto run = testing::minimize(*opt, testing::sphere, 1);
  EXPECT_EQ(run.evaluations, 50 * 500);

  GaSettings paper;
  paper.pc = 0.6;
  paper.pm = 0.03;
  paper.population = 50;
  paper.generations = 500;
  paper.eta_c = 15;
  paper.elites = 1;
  EXPECT_EQ(history_of(make, 3), history_of(testing::factory_of<Ga>(paper), 3));

  GaSettings overridden = paper;
  overridden.pc = 0.8;
  EXPECT_EQ(history_of(make_optimizer_factory({"ga", 50, 100, {{"preset", "lssvm"}, {"pc", "0.8"}}}), 3),
            history_of(testing::factory_of<Ga>(overridden), 3));
}

TEST(OptimizerRegistry, PsoVariantsApply) {
  PsoSettings c = PsoSettings::constriction();
  c.population = 12;
  c.iterations = 8;
  EXPECT_EQ(history_of(make_optimizer_factory({"pso", 12, 8, {{"variant", "constriction"}}})),
            history_of(testing::factory_of<Pso>(c)));

  PsoSettings l = PsoSettings::linear_inertia();
  l.population = 12;
  l.iterations = 8;
  EXPECT_EQ(history_of(make_optimizer_factory({"pso", 12, 8, {{"variant", "linear_inertia"}}})),
            history_of(testing::factory_of<Pso>(l)));

  PsoSettings d;
  d.population = 12;
  d.iterations = 8;
  EXPECT_EQ(history_of(make_optimizer_factory({"pso", 12, 8, {{"variant", "inertia"}}})),
            history_of(testing::factory_of<Pso>(d)));

  // The variant's coefficients, then explicit settings over them: φ = 2.1 + 2.1 > 4 is still valid.
  c.cognitive = c.social = 2.1;
  EXPECT_EQ(history_of(make_optimizer_factory(
                {"pso", 12, 8, {{"variant", "constriction"}, {"cognitive", "2.1"}, {"social", "2.1"}}})),
            history_of(testing::factory_of<Pso>(c)));
  EXPECT_EQ(spec_error({"pso", 12, 8, {{"variant", "constriction"}, {"cognitive", "1"}}}),
            "pso: the constriction variant needs phi = cognitive + social > 4 (Clerc & Kennedy 2002), got 3.05");
}

// ---- test support ---------------------------------------------------------------------------------------

// Values worked by hand from the definitions.
TEST(OptimizerTestSupport, StandardFunctionsHaveTheirKnownValues) {
  using namespace testing;
  const std::vector<double> zero(5, 0.0), ones(5, 1.0);
  EXPECT_EQ(sphere(zero), 0.0);
  EXPECT_EQ(sphere(std::vector<double>{1, 2}), 5.0);
  EXPECT_EQ(rosenbrock(ones), 0.0);
  EXPECT_EQ(rosenbrock(std::vector<double>{0, 0}), 1.0);
  EXPECT_EQ(rosenbrock(std::vector<double>{-1, 1}), 4.0);
  EXPECT_EQ(rastrigin(zero), 0.0);
  EXPECT_NEAR(rastrigin(std::vector<double>{1, 1}), 2.0, 1e-12);    // cos 2π = 1: each term 1 − 10 + 10
  EXPECT_NEAR(rastrigin(std::vector<double>{0.5}), 20.25, 1e-12);   // 10 + 0.25 + 10
  EXPECT_NEAR(ackley(zero), 0.0, 1e-15);
  // at (1, 1): √(mean x²) = 1 and exp(mean cos 2πx) = e, so 20 − 20·e^(−0.2)
  EXPECT_NEAR(ackley(std::vector<double>{1, 1}), 20 - 20 * std::exp(-0.2), 1e-12);
  EXPECT_NEAR(griewank(zero), 0.0, 1e-15);
  EXPECT_NEAR(griewank(std::vector<double>{std::numbers::pi / 2}), 1 + std::pow(std::numbers::pi / 2, 2) / 4000, 1e-12);
  for (const auto& f : {kSphere, kRosenbrock, kRastrigin, kAckley, kGriewank}) EXPECT_LT(f.lower, f.upper) << f.name;
}

TEST(OptimizerTestSupport, RetryStopsAtTheFirstSuccess) {
  std::vector<int> attempts;
  EXPECT_EQ(testing::retry(5, [&](int a) {
              attempts.push_back(a);
              return a == 1 ? ::testing::AssertionSuccess() : ::testing::AssertionFailure();
            }),
            2);
  EXPECT_EQ(attempts, (std::vector<int>{0, 1}));
}

// The retry helper must be able to fail: a trial that never succeeds fails the test on its last attempt.
TEST(OptimizerTestSupport, RetryFailsWhenEveryAttemptFails) {
  EXPECT_NONFATAL_FAILURE(testing::retry(3, [](int a) { return ::testing::AssertionFailure() << "attempt " << a; }),
                          "attempt 2");
}

TEST(OptimizerTestSupport, SuccessRateCanFail) {
  EXPECT_FALSE(testing::reaches_target(kImpossible, make_de, 1));
  EXPECT_NONFATAL_FAILURE(testing::expect_success_rate(kImpossible, make_de), "rastrigin5: 0/5 runs below 1e-10");
}

}  // namespace dampbench
