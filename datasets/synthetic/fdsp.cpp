// fdsp tests (docs/models.md (fdsp)): 6.35 mm at 1.5–5 Hz in 0.5 Hz steps, 0 V, 3 cycles each.
// Truth: the frequency-dependent Spencer model with the fdsp eqs. 13–14 laws and Table 2 (fixture
// fdsp.eqs13_14); 1 % force noise.
#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "datasets/synthetic/synthetic.hpp"
#include "models/fixtures.hpp"

namespace dampbench::synthetic {

void write_fdsp(const std::filesystem::path& dir, std::uint64_t seed) {
  const auto truth = make_fixture_model(find_fixture("fdsp.eqs13_14"));
  constexpr double kAmp = 0.00635;
  constexpr int kCycles = 3, kSamplesPerCycle = 400;
  for (int i = 0; i <= 7; ++i) {
    const double f = 1.5 + 0.5 * i;
    Record r;
    r.file = fmt::format("f{}Hz.csv", fmt::format("{:g}", f));
    std::replace(r.file.begin(), r.file.end(), '.', 'p');
    r.file.replace(r.file.size() - 4, 4, ".csv");
    r.description = fmt::format(
        "Synthetic fdsp record: 6.35 mm, {:g} Hz, 0 V, {} cycles; truth frequency-dependent Spencer model (fdsp eqs. "
        "13-14, Table 2), 1 % noise (datasets/README.md)",
        f, kCycles);
    r.operating = {{"V", 0.0}, {"amp", kAmp}, {"freq", f}};
    const Dataset d = sine_record(kAmp, f, kCycles, kSamplesPerCycle, r);
    r.F = truth.model->simulate(truth.coefficients, prepare_signals(d));
    add_noise(r.F, 0.01, seed, r.file);
    write_record(dir, r);
  }
}

}  // namespace dampbench::synthetic
