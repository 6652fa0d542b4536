#pragma once
// docs/extending.md, example 1: a new model in 22 lines. A smooth Bingham law,
// F = f_c·tanh(v / v_ref) + c0·v, written as a Law for the algebraic lane kernel.
#include <cmath>

#include "engine/kernels/algebraic_kernel.hpp"

namespace dampbench::example {

struct TanhBingham {
  static constexpr int kParams = 3;
  static const ModelInfo& info() {
    static const ModelInfo i{"example.tanh_bingham", "docs/extending.md", "F = f_c*tanh(v/v_ref) + c0*v",
                             {{"f_c", "N", 0.0, 5e3, "N"}, {"v_ref", "m/s", 1e-4, 0.1, "m/s"}, {"c0", "N*s/m", 0.0, 1e5, "N*s/m"}}};
    return i;
  }
  struct Sample { double v; };  // per-sample values shared by every candidate lane
  static Sample prepare(const Signals& s, std::size_t k) { return {s.v_m_s[k]}; }
  template <class P>  // p.p[j][lane] is parameter j of the candidate in that lane
  static double force(const P& p, int lane, const Sample& s) {
    return p.p[0][lane] * std::tanh(s.v / p.p[1][lane]) + p.p[2][lane] * s.v;
  }
};

}  // namespace dampbench::example
