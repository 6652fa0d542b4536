#include "engine/cli/fit_report.hpp"

#include <stdexcept>

#include <fmt/format.h>

#include "engine/cli/fit_held_out.hpp"
#include "engine/common/text_file.hpp"
#include "engine/report/html_report.hpp"
#include "engine/sweep/store/records.hpp"

namespace dampbench::cli {

namespace {

/// The held-out records of `fit` (each fold's, drawn against the fold's prediction) and the held-out tables.
void add_held_out(report::ReportInput& in, const FitReport& fit) {
  const HeldOut& h = *fit.held_out;
  for (const Table& t : held_out_tables(h, fit.fold_rule, per_file_model(*fit.model).id())) in.tables.push_back(t);
  const auto index_of = [&](const Signals* s) {  // a record already drawn (a fitted one) is not added twice
    for (std::size_t i = 0; i < in.records.size(); ++i)
      if (in.records[i].signals == s) return static_cast<int>(i);
    in.records.push_back({s->name, s->source, s, ""});
    return static_cast<int>(in.records.size()) - 1;
  };
  std::size_t row = 0;  // h.held_out lists each fold's predicted records in the folds' order
  for (const FoldFit& f : h.folds) {
    std::string fitted_on;
    for (const auto& n : f.fit_names) fitted_on += (fitted_on.empty() ? "" : ", ") + n;
    for (std::size_t k = 0; k < f.predicted.size(); ++k, ++row) {
      const RecordError& e = h.held_out.at(row);
      if (e.fold != f.fold.name || e.record != f.predict_names[k])
        throw std::logic_error("held-out rows out of the folds' order at " + e.fold + "/" + e.record);
      in.predictions.push_back({index_of(f.predicted[k]), f.fold.name, fitted_on, f.model_id, fit.optimizer, h.metric,
                                e.metric, e.per_file, f.best_params, &f.predicted_force[k]});
    }
  }
}

}  // namespace

void write_fit_report(const std::string& path, const FitReport& fit) {
  report::ReportInput in;
  report::FitInput f;
  std::string names;
  for (const Signals* s : fit.records) {
    f.fit.push_back(static_cast<int>(in.records.size()));
    in.records.push_back({s->name, s->source, s, ""});
    names += (names.empty() ? "" : " + ") + s->name;
  }
  in.title = fmt::format("dampbench fit — {} on {}", fit.model->id(), names);
  in.fingerprint = {{"dampbench", fit.fingerprint}, {"model", std::string(fit.model->id())}, {"optimizer", fit.optimizer}};
  for (const Signals* s : fit.records) in.fingerprint.emplace_back("data " + s->name, s->source);
  f.condition = names;
  f.model_name = std::string(fit.model->id());
  f.optimizer = fit.optimizer;
  f.model = fit.model;
  f.metric = fit.metric;
  f.unconfirmed = fit.unconfirmed;
  for (std::size_t r = 0; r < fit.identification->runs.size(); ++r)
    f.runs.push_back(sweep::run_record(static_cast<int>(r), fit.identification->runs[r]));
  in.fits.push_back(std::move(f));
  in.tables = fit.tables;
  if (fit.held_out) add_held_out(in, fit);
  write_text_file(path, report::render_html(in));
}

}  // namespace dampbench::cli
