// mfm test grid (docs/models.md (mfm)): 4 amplitudes × 4 frequencies × 7 currents, 3 cycles each.
// Truth: the Spencer model with the mfm Table 3 laws in I (fixture mfm.table3), so the magic formula
// (and any other candidate) has a structural error; 1 % force noise.
#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "datasets/synthetic/synthetic.hpp"
#include "models/fixtures.hpp"

namespace dampbench::synthetic {

void write_mfm(const std::filesystem::path& dir, std::uint64_t seed) {
  const auto truth = make_fixture_model(find_fixture("mfm.table3"));
  constexpr int kCycles = 3, kSamplesPerCycle = 200;
  for (double amp : {0.005, 0.01, 0.015, 0.02})
    for (double f : {0.5, 1.0, 1.5, 2.0})
      for (int i = 0; i <= 6; ++i) {
        const double I = 0.5 * i;
        Record r;
        r.file = fmt::format("amp{:g}mm_f{}Hz_I{}A.csv", amp * 1e3, fmt::format("{:g}", f), fmt::format("{:g}", I));
        std::replace(r.file.begin(), r.file.end(), '.', 'p');
        r.file.replace(r.file.size() - 4, 4, ".csv");
        r.description = fmt::format(
            "Synthetic mfm record: {:g} mm, {:g} Hz, {:g} A, {} cycles; truth Spencer model with mfm Table 3 laws, 1 % "
            "noise (datasets/README.md)",
            amp * 1e3, f, I, kCycles);
        r.operating = {{"I", I}, {"amp", amp}, {"freq", f}};
        const Dataset d = sine_record(amp, f, kCycles, kSamplesPerCycle, r);
        r.F = truth.model->simulate(truth.coefficients, prepare_signals(d));
        add_noise(r.F, 0.01, seed, r.file);
        write_record(dir, r);
      }
}

}  // namespace dampbench::synthetic
