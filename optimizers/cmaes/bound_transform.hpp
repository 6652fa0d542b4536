#pragma once
// CMA-ES's bound handling: pycma's boundary transformation (`BoundTransform`, class
// BoxConstraintsLinQuadTransformation of Hansen's pycma), on the unit interval. CMA-ES samples and adapts an
// unbounded genotype g; the candidate asked is the phenotype y = T(g) ∈ [0, 1], and the update uses the
// genotypes (the unrepaired samples). With a = 0.05 (pycma's min((ub − lb)/20, (1 + |lb|)/20) for [0, 1]):
//   1. g is shifted by a multiple of the period 2·(1 + 2a) into [−a − 1/2 − a, 1 + a + 1/2 + a) and then
//      mirrored into [−a, 1 + a] (about −a below it, about 1 + a above it);
//   2. T is the identity on [a, 1 − a], and quadratic towards the bounds: T(g) = (g + a)²/(4a) on [−a, a),
//      T(g) = 1 − (g − 1 − a)²/(4a) on (1 − a, 1 + a]; continuous with a continuous first derivative.
// So every genotype maps into the box, the interior is not distorted, and a bound is reached at the genotype
// −a (or 1 + a) where T is flat: an optimum on a bound is approached like an interior one, without piling
// samples on the bound (what clipping does) or biasing the step-size (what a penalty does).
#include <span>

namespace dampbench {

inline constexpr double kBoundTransformMargin = 0.05;  ///< a, on the unit interval

/// T(g) ∈ [0, 1]; a non-finite g (only after a step size overflow, which a stopping test ends) maps to 1/2.
double to_phenotype(double g);

/// y[i] = to_phenotype(g[i]) for every i (y.size() ≥ g.size()), several at a time.
void to_phenotypes(std::span<const double> g, std::span<double> y);

/// A genotype g with T(g) = y for y ∈ [0, 1] (the one in [−a, 1 + a]); y is clamped to [0, 1] first.
double to_genotype(double y);

}  // namespace dampbench
