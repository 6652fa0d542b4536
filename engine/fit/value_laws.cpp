#include "engine/fit/value_laws.hpp"

#include <cmath>

#include <fmt/format.h>

namespace dampbench {
namespace {

double variable(const std::map<std::string, double>& v, const std::string& name) {
  const auto it = v.find(name);
  return it == v.end() ? std::nan("") : it->second;
}

/// g(I) of F = a + b·g(I); h is the shape's current scale [A].
double shape(ValueLaw::Shape s, double current, double h) {
  switch (s) {
    case ValueLaw::Shape::constant: return 0.0;
    case ValueLaw::Shape::linear: return current;
    case ValueLaw::Shape::hill2: return current * current / (h * h + current * current);
    case ValueLaw::Shape::saturating: return 1.0 - std::exp(-current / h);
  }
  return 0.0;
}

bool has_scale(ValueLaw::Shape s) { return s == ValueLaw::Shape::hill2 || s == ValueLaw::Shape::saturating; }

/// The setting factor is k·v^p + c rather than q0 + q1·v.
bool power_factor(const ValueLaw& law) { return law.factor == ValueLaw::Factor::power; }
bool has_factor(const ValueLaw& law) { return law.factor != ValueLaw::Factor::none; }

/// The setting factor's value from its coefficients q at the record's variables.
double factor_value(const ValueLaw& law, const double* q, const std::map<std::string, double>& variables) {
  const double x = variable(variables, law.setting);
  return power_factor(law) ? q[0] * std::pow(x, q[1]) + q[2] : q[0] + q[1] * x;
}

/// F(I)·(1 + k·v) in its own terms.
struct Fitted {
  double a = 0, b = 0, h = 1, c = 1, k = 0, p = 1, rss = 0;  ///< G = c + k·v (c = 1 but for power(vamp), p its exponent)
};

/// (a, b) by least squares for a fixed h and k, with b ≥ 0 (b = 0: a alone).
void fit_levels(const ValueLaw& law, const std::vector<double>& g, const std::vector<double>& G,
                const std::vector<double>& y, Fitted& f) {
  double s11 = 0, s12 = 0, s22 = 0, r1 = 0, r2 = 0;
  for (std::size_t i = 0; i < y.size(); ++i) {
    const double u1 = G[i], u2 = g[i] * G[i];
    s11 += u1 * u1, s12 += u1 * u2, s22 += u2 * u2, r1 += u1 * y[i], r2 += u2 * y[i];
  }
  const double det = s11 * s22 - s12 * s12;
  f.b = 0;
  f.a = s11 > 0 ? r1 / s11 : 0;
  if (law.current != ValueLaw::Shape::constant && det > 1e-12 * s11 * s22) {
    const double b = (s11 * r2 - s12 * r1) / det;
    if (b > 0) f.a = (r1 * s22 - r2 * s12) / det, f.b = b;
  }
}

/// F(I)·G(v) for one shape scale h: alternating least squares in (a, b) and k.
Fitted fit_at_scale(const ValueLaw& law, double h, const std::vector<double>& I, const std::vector<double>& v,
                    const std::vector<double>& y) {
  const std::size_t n = y.size();
  std::vector<double> g(n), G(n, 1.0);
  for (std::size_t i = 0; i < n; ++i) g[i] = shape(law.current, I[i], h);
  Fitted f;
  f.h = h;
  const auto factor = [&](std::size_t i) { return !has_factor(law) ? 1.0 : f.c + f.k * v[i]; };
  for (int pass = 0; pass < (has_factor(law) ? 40 : 1); ++pass) {
    for (std::size_t i = 0; i < n; ++i) G[i] = factor(i);
    fit_levels(law, g, G, y, f);
    if (!has_factor(law)) break;
    if (!power_factor(law)) {  // G = 1 + k·v: k by least squares
      double num = 0, den = 0;
      for (std::size_t i = 0; i < n; ++i) {
        const double F = f.a + f.b * g[i];
        num += F * v[i] * (y[i] - F), den += F * v[i] * F * v[i];
      }
      f.k = den > 0 ? num / den : 0.0;
      continue;
    }
    // G = c + k·u by least squares, scaled to max(|c|, |k|) = 1: a pure power (c → 0) stays in reach
    double s11 = 0, s12 = 0, s22 = 0, r1 = 0, r2 = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const double F = f.a + f.b * g[i], w = F * v[i];
      s11 += F * F, s12 += F * w, s22 += w * w, r1 += F * y[i], r2 += w * y[i];
    }
    const double det = s11 * s22 - s12 * s12;
    if (!(det > 1e-12 * s11 * s22)) break;
    const double c = (r1 * s22 - r2 * s12) / det, k = (s11 * r2 - s12 * r1) / det, m = std::max(std::fabs(c), std::fabs(k));
    f.c = c / m, f.k = k / m;
  }
  for (std::size_t i = 0; i < n; ++i) {
    const double e = (f.a + f.b * g[i]) * factor(i) - y[i];
    f.rss += e * e;
  }
  return f;
}

/// The least-squares minimum over `steps` points of [lo, hi] (inclusive) refined by golden-section search between
/// the best point's neighbours; `at(x)` fits at x.
template <class At>
Fitted grid_then_golden(double lo, double hi, int steps, At at) {
  const auto x = [&](double s) { return steps == 1 ? lo : lo + (hi - lo) * s / (steps - 1.0); };
  Fitted best;
  best.rss = std::numeric_limits<double>::infinity();
  int best_s = 0;
  for (int s = 0; s < steps; ++s) {
    const Fitted f = at(x(s));
    if (f.rss < best.rss) best = f, best_s = s;
  }
  if (steps == 1) return best;
  double a_lo = std::max(0.0, best_s - 1.0), a_hi = std::min(steps - 1.0, best_s + 1.0);
  const double r = (std::sqrt(5.0) - 1) / 2;
  for (int it = 0; it < 40; ++it) {
    const double a = a_hi - r * (a_hi - a_lo), b = a_lo + r * (a_hi - a_lo);
    const Fitted fa = at(x(a)), fb = at(x(b));
    if (fa.rss < best.rss) best = fa;
    if (fb.rss < best.rss) best = fb;
    (fa.rss < fb.rss ? a_hi : a_lo) = fa.rss < fb.rss ? b : a;
  }
  return best;
}

/// F(I)·(1 + k·u) over the shape's scale h (a grid over 0.05–2 A in log steps, then golden section).
Fitted fit_over_scales(const ValueLaw& law, const std::vector<double>& I, const std::vector<double>& u,
                       const std::vector<double>& y) {
  const int scales = has_scale(law.current) ? 40 : 1;
  return grid_then_golden(0.0, 1.0, scales, [&](double s) {
    return fit_at_scale(law, scales == 1 ? 1.0 : 0.05 * std::pow(40.0, s), I, u, y);  // 0.05 … 2 A
  });
}

}  // namespace

std::string ValueLaw::text() const {
  const char* shapes[] = {"", "mono(I,0,1)", "hill(I,2)", "sat(I)"};
  const std::string f = shapes[static_cast<int>(current)];
  if (!has_factor(*this)) return f.empty() ? "free" : f;
  const std::string g = power_factor(*this) ? fmt::format("power({})", setting) : fmt::format("poly({},1)", setting);
  return f.empty() ? g : fmt::format("prod({},{})", f, g);
}

int ValueLaw::coefficients() const {
  const int f = current == Shape::constant ? 1 : has_scale(current) ? 3 : 2;
  const int g = power_factor(*this) ? 3 : 2;
  return !has_factor(*this) ? f : current == Shape::constant ? g : f + g;
}

std::vector<ValueLaw> value_law_candidates() {
  std::vector<ValueLaw> out;
  for (auto s : {ValueLaw::Shape::constant, ValueLaw::Shape::linear, ValueLaw::Shape::hill2, ValueLaw::Shape::saturating})
    for (const auto& [g, v] : {std::pair{ValueLaw::Factor::none, ""}, {ValueLaw::Factor::linear, "amp"},
                               {ValueLaw::Factor::linear, "freq"}, {ValueLaw::Factor::power, "vamp"},
                               {ValueLaw::Factor::power, "amp"}, {ValueLaw::Factor::power, "freq"}})
      out.push_back({s, g, v});
  return out;
}

double ValueFit::predict(const ValueLaw& law, const std::map<std::string, double>& variables) const {
  const auto& c = coefficients;
  if (law.current == ValueLaw::Shape::constant)
    return has_factor(law) ? factor_value(law, c.data(), variables) : c[0];
  const bool scaled = has_scale(law.current);
  const double F = c[0] + c[1] * shape(law.current, variable(variables, "I"), scaled ? c[2] : 1.0);
  if (!has_factor(law)) return F;
  return F * factor_value(law, c.data() + (scaled ? 3 : 2), variables);
}

ValueFit fit_value_law(const ValueLaw& law, const std::vector<std::map<std::string, double>>& variables,
                       const std::vector<double>& values) {
  const std::size_t n = values.size();
  std::vector<double> I(n, 0.0), v(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    if (law.current != ValueLaw::Shape::constant) I[i] = variable(variables[i], "I");
    if (has_factor(law)) v[i] = variable(variables[i], law.setting);
  }
  Fitted best;
  if (!power_factor(law)) {
    best = fit_over_scales(law, I, v, values);
  } else {
    best = grid_then_golden(-2.0, 2.0, 17, [&](double p) {
      std::vector<double> u(n);
      for (std::size_t i = 0; i < n; ++i) u[i] = std::pow(v[i], p);
      Fitted f = fit_over_scales(law, I, u, values);
      f.p = p;
      return f;
    });
  }
  ValueFit out;
  out.rss = best.rss;
  if (law.current == ValueLaw::Shape::constant) {
    if (!has_factor(law)) out.coefficients = {best.a};
    else if (power_factor(law)) out.coefficients = {best.a * best.k, best.p, best.a * best.c};
    else out.coefficients = {best.a, best.a * best.k};
    return out;
  }
  // A power factor as a later factor: scaled to 1 at the records' geometric-mean v, so that F(I) is the parameter
  // there and k, c stay well inside their ±1 bounds (a pure 1/v has k ≈ v there, c ≈ 0); kept at
  // max(|k|, |c|) = 1 when that scaling would leave them.
  double scale = 1;
  if (power_factor(law)) {
    double log_sum = 0;
    for (double x : v) log_sum += std::log(x);
    const double at_mean = best.c + best.k * std::pow(std::exp(log_sum / static_cast<double>(n)), best.p);
    if (at_mean > 0 && std::max(std::fabs(best.c), std::fabs(best.k)) / at_mean <= 1) scale = at_mean;
  }
  out.coefficients = {best.a * scale, best.b * scale};
  if (has_scale(law.current)) out.coefficients.push_back(best.h);
  if (power_factor(law)) out.coefficients.insert(out.coefficients.end(), {best.k / scale, best.p, best.c / scale});
  else if (has_factor(law)) out.coefficients.insert(out.coefficients.end(), {1.0, best.k});
  return out;
}

}  // namespace dampbench
