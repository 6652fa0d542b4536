// mfm test grids (docs/models.md (mfm)): 4 amplitudes × 4 frequencies × 7 currents, 3 cycles each, 1 % force noise.
// Two truths on the same conditions and file names (datasets/README.md):
//   mfm          the Spencer model with the mfm Table 3 laws in I (fixture mfm.table3): a compared model, so a
//                comparison on it is a recovery check;
//   mfm-neutral  an MR valve damper none of the compared models is (datasets/synthetic/neutral_truths.hpp).
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

/// The force of a grid's truth on record `d` at amplitude, frequency and current.
using GridTruth = std::function<std::vector<double>(double amp_m, double freq_hz, double current_A, const Dataset& d)>;

void write_mfm_grid(const std::filesystem::path& dir, std::uint64_t seed, std::string_view truth_words,
                    const GridTruth& force) {
  constexpr int kMfmCycles = 3, kMfmSamplesPerCycle = 200;
  for (double amp : {0.005, 0.01, 0.015, 0.02})
    for (double f : {0.5, 1.0, 1.5, 2.0})
      for (int i = 0; i <= 6; ++i) {
        const double I = 0.5 * i;
        Record r;
        r.file = fmt::format("amp{:g}mm_f{}Hz_I{}A.csv", amp * 1e3, fmt::format("{:g}", f), fmt::format("{:g}", I));
        std::replace(r.file.begin(), r.file.end(), '.', 'p');
        r.file.replace(r.file.size() - 4, 4, ".csv");
        r.description = fmt::format("Synthetic mfm record: {:g} mm, {:g} Hz, {:g} A, {} cycles; {}, 1 % noise "
                                    "(datasets/README.md)",
                                    amp * 1e3, f, I, kMfmCycles, truth_words);
        r.operating = {{"I", I}, {"amp", amp}, {"freq", f}};
        const Dataset d = sine_record(amp, f, kMfmCycles, kMfmSamplesPerCycle, r);
        r.F = force(amp, f, I, d);
        add_noise(r.F, 0.01, seed, r.file);
        write_record(dir, r);
      }
}

}  // namespace

void write_mfm(const std::filesystem::path& dir, std::uint64_t seed) {
  const auto truth = make_fixture_model(find_fixture("mfm.table3"));
  write_mfm_grid(dir, seed, "truth Spencer model with mfm Table 3 laws", [&](double, double, double, const Dataset& d) {
    return truth.model->simulate(truth.coefficients, prepare_signals(d));
  });
}

void write_mfm_neutral(const std::filesystem::path& dir, std::uint64_t seed) {
  write_mfm_grid(dir, seed, "neutral truth: MR valve damper (Herschel-Bulkley valve behind the oil column's stiffness)",
                 [](double amp, double f, double I, const Dataset& d) {
                   return mr_valve_force(mfm_valve_damper(I), sine_motion(amp, f), d.t_s);
                 });
}

}  // namespace dampbench::synthetic
