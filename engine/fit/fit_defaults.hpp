#pragma once
// What `fit` runs when the command line names no optimizer, budget or run count: defaults per model class that
// converge on real data (fit_defaults.cpp says why each value).
#include <optional>
#include <string>

namespace dampbench {

class Model;

struct FitPlan {
  std::string optimizer;
  int population = 0;
  int iterations = 0;
  int runs = 0;
  std::string why;  ///< one line for the output when a class default was used ("" when all four were given)
};

/// The plan for `model`: each of optimizer, population, iterations and runs the user gave, the rest from the
/// model's class. Population and iterations come from the class only with its optimizer: with another
/// --optimizer they default to 50 and 100.
FitPlan fit_plan(const Model& model, const std::optional<std::string>& optimizer, std::optional<int> population,
                 std::optional<int> iterations, std::optional<int> runs);

}  // namespace dampbench
