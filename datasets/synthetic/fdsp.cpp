// fdsp tests (docs/models.md (fdsp)): 6.35 mm at 1.5–5 Hz in 0.5 Hz steps, 0 V, 3 cycles each, 1 % force noise.
// Two truths on the same conditions and file names (datasets/README.md):
//   fdsp          the frequency-dependent Spencer model with the fdsp eqs. 13–14 laws and Table 2 (fixture
//                 fdsp.eqs13_14): one side of Table 3, so a comparison on it is a recovery check;
//   fdsp-neutral  an MR valve damper at 0 V, whose shear-thinning valve and compliant oil column make its loops
//                 change with frequency in a way neither compared model has (datasets/synthetic/neutral_truths.hpp).
#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>

#include <fmt/format.h>

#include "datasets/synthetic/neutral_truths.hpp"
#include "datasets/synthetic/synthetic.hpp"
#include "models/fixtures.hpp"

namespace dampbench::synthetic {
namespace {

/// The force of a grid's truth on record `d` at amplitude and frequency.
using FdspTruth = std::function<std::vector<double>(double amp_m, double freq_hz, const Dataset& d)>;

void write_fdsp_grid(const std::filesystem::path& dir, std::uint64_t seed, std::string_view truth_words,
                     const FdspTruth& force) {
  constexpr double kAmp = 0.00635;
  constexpr int kCycles = 3, kFdspSamplesPerCycle = 400;
  for (int i = 0; i <= 7; ++i) {
    const double f = 1.5 + 0.5 * i;
    Record r;
    r.file = fmt::format("f{}Hz.csv", fmt::format("{:g}", f));
    std::replace(r.file.begin(), r.file.end(), '.', 'p');
    r.file.replace(r.file.size() - 4, 4, ".csv");
    r.description = fmt::format("Synthetic fdsp record: 6.35 mm, {:g} Hz, 0 V, {} cycles; {}, 1 % noise (datasets/README.md)",
                                f, kCycles, truth_words);
    r.operating = {{"V", 0.0}, {"amp", kAmp}, {"freq", f}};
    const Dataset d = sine_record(kAmp, f, kCycles, kFdspSamplesPerCycle, r);
    r.F = force(kAmp, f, d);
    add_noise(r.F, 0.01, seed, r.file);
    write_record(dir, r);
  }
}

}  // namespace

void write_fdsp(const std::filesystem::path& dir, std::uint64_t seed) {
  const auto truth = make_fixture_model(find_fixture("fdsp.eqs13_14"));
  write_fdsp_grid(dir, seed, "truth frequency-dependent Spencer model (fdsp eqs. 13-14, Table 2)",
                  [&](double, double, const Dataset& d) {
                    return truth.model->simulate(truth.coefficients, prepare_signals(d));
                  });
}

void write_fdsp_neutral(const std::filesystem::path& dir, std::uint64_t seed) {
  write_fdsp_grid(dir, seed, "neutral truth: MR valve damper at 0 V (shear-thinning valve behind the oil column's stiffness)",
                  [](double amp, double f, const Dataset& d) {
                    return mr_valve_force(fdsp_valve_damper(), sine_motion(amp, f), d.t_s);
                  });
}

}  // namespace dampbench::synthetic
