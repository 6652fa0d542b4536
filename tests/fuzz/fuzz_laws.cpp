// libFuzzer target: parameter-law strings (engine/model/parameter_law.hpp, `--laws`, sweep `laws`), parsed,
// printed and parsed again, and evaluated with coefficients 1.5 at fixed operating variables. Bad input must end
// in an InputError; text() of a law must parse back to the same text.
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "engine/common/error.hpp"
#include "engine/model/parameter_law.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const auto laws = dampbench::parse_laws(text, "fuzz");
    const std::map<std::string, double> variables{{"I", 0.5}, {"V", 2}, {"phi", 90}, {"amp", 0.01}, {"freq", 2}, {"w", 12.6}};
    for (const auto& [name, law] : laws) {
      const std::vector<double> coefficients(law.coefficient_names(name).size(), 1.5);
      (void)law.evaluate(coefficients.data(), variables);
      if (dampbench::parse_law(law.text(), "again").text() != law.text()) std::abort();  // a round trip that changes
    }
  } catch (const dampbench::InputError&) {
  }
  return 0;
}
