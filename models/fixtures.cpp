#include "models/fixtures.hpp"

#include <cmath>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "models/registry.hpp"

namespace dampbench {
namespace {

/// Coefficients name_v0..name_v3 of a cubic in variable v.
std::vector<std::pair<std::string, double>> cubic(const std::string& name, const std::string& v, double c0, double c1,
                                                  double c2, double c3) {
  return {{name + "_" + v + "0", c0}, {name + "_" + v + "1", c1}, {name + "_" + v + "2", c2}, {name + "_" + v + "3", c3}};
}

std::vector<std::pair<std::string, double>> join(std::initializer_list<std::vector<std::pair<std::string, double>>> parts) {
  std::vector<std::pair<std::string, double>> out;
  for (const auto& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

std::vector<LawFixture> make_fixtures() {
  std::vector<LawFixture> f;
  f.push_back({"crfd.table5", "crfd eq. 5.1, Table 5", "crfd.gvnem_modified",
               "c_r=poly(phi,3);k_r=poly(phi,3);eta=poly(phi,3);mu=poly(phi,3)",
               join({cubic("c_r", "phi", 1.270, 0.104, -6.937e-4, 2.264e-6),
                     cubic("k_r", "phi", 7.739, 0.190, -8.880e-4, 4.305e-6),
                     cubic("eta", "phi", 0.337, 2.065e-3, 2.529e-5, -8.745e-8),
                     cubic("mu", "phi", 5.987, 3.568e-2, -3.408e-4, 1.488e-6)})});
  f.push_back({"crfd.table6", "crfd eq. 7.2, Table 6 (xi as printed: it explodes at 180 deg)", "crfd.kwok",
               "c_r=poly(phi,3);k_r=poly(phi,3);eta=poly(phi,3);mu=poly(phi,3);xi=poly(phi,3)",
               join({cubic("c_r", "phi", 0.915, 0.071, -3.581e-5, -2.407e-7),
                     cubic("k_r", "phi", 10.670, 0.234, 1.192e-5, 1.644e-6),
                     cubic("eta", "phi", 0.362, 0.013, -1.688e-4, 4.702e-7),
                     cubic("mu", "phi", 5.083, 0.315, -6.399e-3, 2.880e-5),
                     cubic("xi", "phi", 9.784, -31.540, 9.919, -0.334), {{"T_r", 0.011}}})});
  f.push_back({"crfd.table7", "crfd eq. 7.5, Table 7", "crfd.maxwell",
               "c_r=poly(phi,3);k_r=poly(phi,3);alpha=poly(phi,3);beta=poly(phi,3)",
               join({cubic("c_r", "phi", 2.184, 0.103, -1.938e-4, 8.497e-8),
                     cubic("k_r", "phi", 53.24, -0.367, 6.789e-3, -2.822e-5),
                     cubic("alpha", "phi", 0.843, 1.288e-4, 1.688e-5, -8.569e-8),
                     cubic("beta", "phi", 0.943, -1.471e-2, 1.546e-4, -5.089e-7)})});
  // mfm eq. 10's factor 1e-3 is folded into the current polynomial of A.
  f.push_back({"mfm.eqs4_11", "mfm eqs. 4-11", "mrd.magic_formula",
               "C=poly(I,1);D=poly(I,1);E=poly(I,1);k_c=poly(I,1);k=poly(I,1);"
               "A=prod(poly(I,2),poly(amp,1),poly(freq,1));B=prod(poly(I,2),poly(amp,2),poly(freq,2))",
               {{"A_I0", 6.578e-3}, {"A_I1", 0.914e-3}, {"A_I2", -0.205e-3}, {"A_amp0", 0.457}, {"A_amp1", 49.042},
                {"A_freq0", -0.058}, {"A_freq1", 1.042},
                {"B_I0", 201.140}, {"B_I1", -43.804}, {"B_I2", 8.450}, {"B_amp0", 2.0}, {"B_amp1", -120.920},
                {"B_amp2", 2976.1}, {"B_freq0", 3.310}, {"B_freq1", -2.978}, {"B_freq2", 0.804},
                {"C_I0", 1.061}, {"C_I1", -0.023}, {"D_I0", 208.694}, {"D_I1", 318.463}, {"E_I0", -1.469},
                {"E_I1", -0.445}, {"k_c_I0", 1241.836}, {"k_c_I1", 296.411}, {"k_I0", 1180.632}, {"k_I1", 143.369},
                {"f0", -2.36}}});
  f.push_back({"mfm.table3", "mfm Table 3", "mrd.spencer", "c0=poly(I,1);c1=poly(I,1);alpha=poly(I,1);A=poly(I,1)",
               {{"c0_I0", 1.870e3}, {"c0_I1", 2.240e3}, {"c1_I0", 1.727e5}, {"c1_I1", 2.815e5}, {"k0", 42.83},
                {"k1", 561.2}, {"x0", -6.678e-2}, {"alpha_I0", 71.44}, {"alpha_I1", 94.57}, {"beta", 6.079e3},
                {"gamma", 1.083e4}, {"A_I0", 4.731e4}, {"A_I1", 0.29e4}, {"n", 0.9929}}});
  f.push_back({"fdsp.eqs13_14", "fdsp eqs. 13-14 (minus signs restored), Table 2, Table 1 for b_c0, b_c1, b_alpha, eta",
               "mrd.spencer_freq", "",
               {{"K0", 3361.58}, {"K1", 420.0}, {"a_c0_k", 1410.71}, {"a_c0_p", -0.102}, {"a_c0_c", -0.6182},
                {"a_c1_a1", 7087}, {"a_c1_b1", 4.282}, {"a_c1_c1", 1.197}, {"a_c1_a2", 18520}, {"a_c1_b2", 1.783},
                {"a_c1_c2", 3.25}, {"b_c0", 1803}, {"b_c1", 34622}, {"a_alpha", 6515.13}, {"b_alpha", 38430},
                {"A", 87}, {"beta", 307269.41}, {"gamma", 182842.99}, {"n", 2}, {"eta", 190}, {"Z0", 0.01225}}});
  return f;
}

}  // namespace

std::span<const LawFixture> law_fixtures() {
  static const std::vector<LawFixture> fixtures = make_fixtures();
  return fixtures;
}

const LawFixture& find_fixture(std::string_view name) {
  std::string known;
  for (const auto& f : law_fixtures()) {
    if (f.name == name) return f;
    known += (known.empty() ? "" : ", ") + f.name;
  }
  throw InputError(fmt::format("unknown fixture '{}' (known: {})", name, known));
}

FixtureModel make_fixture_model(const LawFixture& fixture) {
  FixtureModel out;
  out.model = std::make_unique<LawModel>(find_model(fixture.base_model), parse_laws(fixture.laws, fixture.name),
                                         fixture.name, fixture.citation);
  const LawModel& m = *out.model;
  out.coefficients.assign(m.dim(), std::nan(""));
  for (const auto& [name, value] : fixture.coefficients) out.coefficients[m.parameter_index(name)] = value;
  for (int j = 0; j < m.dim(); ++j)
    if (std::isnan(out.coefficients[j]))
      throw std::logic_error(fmt::format("fixture {} lacks coefficient {}", fixture.name, m.parameters()[j].name));
  return out;
}

}  // namespace dampbench
