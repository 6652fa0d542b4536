#pragma once
// The published parameter laws as named fixtures: a base model, its laws and the printed coefficients.
//   crfd.table5     crfd eq. 5.1, Table 5: modified GV–NEM, cubic in φ
//   crfd.table6     crfd eq. 7.2, Table 6: Kwok, cubic in φ (ξ as printed: explodes at 180°, docs/models.md (crfd))
//   crfd.table7     crfd eq. 7.5, Table 7: generalized Maxwell, cubic in φ
//   mfm.eqs4_11     mfm eqs. 4–11: magic formula, linear in I; A and B products in I, amp, freq
//   mfm.table3      mfm Table 3: Spencer model, linear in I
//   fdsp.eqs13_14   fdsp eqs. 13–14 with Table 2 (2.5 Hz, 0 V; b-coefficients and η of Table 1)
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "engine/model/law_model.hpp"

namespace dampbench {

struct LawFixture {
  std::string name;
  std::string citation;
  std::string base_model;
  std::string laws;  ///< parse_laws text
  std::vector<std::pair<std::string, double>> coefficients;  ///< every coefficient of the law model, by name
};

std::span<const LawFixture> law_fixtures();
/// Throws InputError "unknown fixture 'x' (known: ...)".
const LawFixture& find_fixture(std::string_view name);

/// The law model of a fixture and its coefficient vector (in the model's parameter order).
struct FixtureModel {
  std::unique_ptr<LawModel> model;
  std::vector<double> coefficients;
};
FixtureModel make_fixture_model(const LawFixture& fixture);

}  // namespace dampbench
