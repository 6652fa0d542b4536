#pragma once
// The HTML report: one self-contained file that opens offline in any browser. The numbers are
// computed here, in C++, and embedded as one JSON document; the page draws them with D3 (Debian's libjs-d3,
// inlined at build time) into SVG:
//   - per condition and record: force–displacement and force–velocity loops, measured against the best fit of
//     each model (simulated from its stored parameters by Model::simulate, the kernels the fit used), and the
//     residual over time; records longer than `max_points` samples are drawn at every k-th sample;
//   - per held-out record (held-out evaluation, grouped by fold): the same loops and residual, measured against the
//     force predicted by the fold's model and best parameters, titled with the fold, the metric and its ratio to
//     the record's own per-file fit when known;
//   - per condition and model: best-so-far metric against evaluations, each run, and per optimizer the median
//     and interquartile band over runs (sweep::convergence_band);
//   - per model: the final metric of every run per condition and optimizer (box and points; relative to the
//     best run when the runs agree to more digits than an axis label holds, one line when they agree to 1e-9);
//   - where a split compares optimizers, fixed-target runtime ECDFs and the runtime tables they come from (success,
//     ERT in evaluations and in seconds);
//   - identified parameters against operating variables with the fitted law drawn through them;
//   - the sweep's tables and the store's fingerprint.
#include <string>

#include <nlohmann/json.hpp>

#include "engine/report/report_input.hpp"

namespace dampbench::report {

struct HtmlOptions {
  int max_points = 2500;  ///< samples per record drawn (every k-th sample of longer records)
};

/// Every number the page draws, as the JSON document embedded in it (element id "dampbench-data").
nlohmann::ordered_json report_data(const ReportInput& input, const HtmlOptions& options = {});

/// The whole HTML document.
std::string render_html(const ReportInput& input, const HtmlOptions& options = {});

}  // namespace dampbench::report
