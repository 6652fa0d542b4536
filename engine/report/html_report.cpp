#include "engine/report/html_report.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <tuple>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "engine/identification/convergence.hpp"
#include "engine/report/report_assets.hpp"
#include "engine/sweep/analysis.hpp"

namespace dampbench::report {
namespace {

using json = nlohmann::ordered_json;

/// NaN and ±inf have no JSON form: null (the page draws a gap).
json number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json numbers(const std::vector<double>& v, std::size_t stride = 1) {
  json out = json::array();
  for (std::size_t k = 0; k < v.size(); k += stride) out.push_back(number(v[k]));
  return out;
}

std::size_t best_run(const FitInput& f) {
  std::size_t best = 0;
  for (std::size_t r = 1; r < f.runs.size(); ++r)
    if (f.runs[r].best_value < f.runs[best].best_value) best = r;
  return best;
}
double best_value(const FitInput& f) {
  return f.runs.empty() ? std::numeric_limits<double>::infinity() : f.runs[best_run(f)].best_value;
}

/// Fits that share a condition (part, split, fit set label), in input order.
struct Condition {
  std::string part, split, label;
  std::vector<const FitInput*> fits;
  std::vector<std::pair<int, bool>> records;  ///< (record, predicted), fit records first
};

std::vector<Condition> conditions_of(const ReportInput& in) {
  std::vector<Condition> out;
  std::map<std::tuple<std::string, std::string, std::string>, std::size_t> index;
  for (const FitInput& f : in.fits) {
    if (f.runs.empty()) continue;
    const auto key = std::make_tuple(f.part, f.split, f.condition);
    auto [it, added] = index.try_emplace(key, out.size());
    if (added) out.push_back({f.part, f.split, f.condition, {}, {}});
    Condition& c = out[it->second];
    c.fits.push_back(&f);
    auto add = [&](int r, bool predicted) {
      if (std::none_of(c.records.begin(), c.records.end(), [&](const auto& x) { return x.first == r; }))
        c.records.emplace_back(r, predicted);
    };
    for (int r : f.fit) add(r, false);
    for (int r : f.predict) add(r, true);
  }
  return out;
}

/// The lowest-metric fit of each model in a condition, in order of first appearance.
std::vector<const FitInput*> best_per_model(const Condition& c) {
  std::vector<const FitInput*> out;
  for (const FitInput* f : c.fits) {
    auto it = std::find_if(out.begin(), out.end(), [&](const FitInput* g) { return g->model_name == f->model_name; });
    if (it == out.end())
      out.push_back(f);
    else if (best_value(*f) < best_value(**it))
      *it = f;
  }
  return out;
}

/// Every k-th sample is drawn so that at most max_points are.
std::size_t record_stride(const Signals& s, const HtmlOptions& options) {
  const std::size_t cap = static_cast<std::size_t>(std::max(2, options.max_points));
  return std::max<std::size_t>(1, (s.size() + cap - 1) / cap);
}

/// One model's force on a record as a loop draws it (at the record's stride); `runs` where the value is a best run's.
json model_force(const std::string& model, const std::string& optimizer, Metric metric, double value,
                 std::optional<std::size_t> runs, const std::vector<double>& params, const std::vector<double>& force,
                 std::size_t stride) {
  json j = {{"model", model}, {"optimizer", optimizer}, {"metric", metric_name(metric)}, {"value", number(value)}};
  if (runs) j["runs"] = *runs;
  j["params"] = numbers(params);
  j["F"] = numbers(force, stride);
  return j;
}

json record_figures(const ReportInput& in, const Condition& c, const HtmlOptions& options) {
  const std::vector<const FitInput*> models = best_per_model(c);
  // Every (record, model) force, simulated in parallel: each is one candidate on one record.
  std::vector<std::vector<std::vector<double>>> forces(c.records.size(), std::vector<std::vector<double>>(models.size()));
  tbb::parallel_for(std::size_t{0}, c.records.size() * models.size(), [&](std::size_t i) {
    const std::size_t r = i / models.size(), m = i % models.size();
    const RecordInput& record = in.records[static_cast<std::size_t>(c.records[r].first)];
    const FitInput& fit = *models[m];
    if (record.signals && fit.model) forces[r][m] = fit.model->simulate(fit.runs[best_run(fit)].params, *record.signals);
  });
  json out = json::array();
  for (std::size_t r = 0; r < c.records.size(); ++r) {
    const RecordInput& record = in.records[static_cast<std::size_t>(c.records[r].first)];
    json j = {{"record", c.records[r].first}, {"role", c.records[r].second ? "predicted" : "fitted"}};
    json list = json::array();
    if (record.signals)
      for (std::size_t m = 0; m < models.size(); ++m) {
        const FitInput& fit = *models[m];
        list.push_back(model_force(fit.model_name, fit.optimizer, fit.metric, best_value(fit), fit.runs.size(),
                                   fit.runs[best_run(fit)].params, forces[r][m], record_stride(*record.signals, options)));
      }
    j["models"] = std::move(list);
    out.push_back(std::move(j));
  }
  return out;
}

/// "rec held out by fold I=0.5: nrmse 0.0812, 1.42× its per-file fit (0.0572)".
std::string prediction_title(const RecordInput& record, const PredictionInput& p) {
  std::string title = fmt::format("{} held out by fold {}: {} {:.4g}", record.name, p.fold, metric_name(p.metric), p.value);
  if (p.per_file) title += fmt::format(", {:.3g}× its per-file fit ({:.4g})", p.value / *p.per_file, *p.per_file);
  return title;
}

/// The held-out records by fold, in the order of each fold's first record: loops as record_figures draws them, with
/// the fold's predicted force as the one model.
json prediction_figures(const ReportInput& in, const HtmlOptions& options) {
  json out = json::array();
  std::map<std::string, std::size_t> index;
  for (const PredictionInput& p : in.predictions) {
    auto [it, added] = index.try_emplace(p.fold, out.size());
    if (added) out.push_back({{"fold", p.fold}, {"fitted_on", p.fitted_on}, {"records", json::array()}});
    const RecordInput& record = in.records.at(static_cast<std::size_t>(p.record));
    json j = {{"record", p.record}, {"role", "predicted"}, {"title", prediction_title(record, p)},
              {"ratio", p.per_file ? number(p.value / *p.per_file) : json(nullptr)}, {"models", json::array()}};
    if (record.signals && p.force)
      j["models"].push_back(model_force(p.model_name, p.optimizer, p.metric, p.value, std::nullopt, p.params, *p.force,
                                        record_stride(*record.signals, options)));
    out[it->second]["records"].push_back(std::move(j));
  }
  return out;
}

/// The measured signals of every record, at the stride the loops are drawn at.
json records(const ReportInput& in, const HtmlOptions& options) {
  json out = json::array();
  for (const RecordInput& record : in.records) {
    json j = {{"name", record.name}, {"label", record.label}};
    if (!record.signals) {
      j["unavailable"] = record.unavailable;
      out.push_back(std::move(j));
      continue;
    }
    const Signals& s = *record.signals;
    const std::size_t stride = record_stride(s, options);
    j["samples"] = s.size();
    j["stride"] = stride;
    j["t"] = numbers(s.t_s, stride);
    j["x"] = numbers(s.x_m, stride);
    j["v"] = numbers(s.v_m_s, stride);
    j["F"] = numbers(s.F_N, stride);
    out.push_back(std::move(j));
  }
  return out;
}

json convergence_figures(const Condition& c) {
  json out = json::array();
  std::vector<std::string> models;
  for (const FitInput* f : c.fits)
    if (std::find(models.begin(), models.end(), f->model_name) == models.end()) models.push_back(f->model_name);
  for (const std::string& model : models) {
    json series = json::array();
    for (const FitInput* f : c.fits) {
      if (f->model_name != model) continue;
      std::vector<std::vector<TracePoint>> traces;
      std::vector<RunHistory> histories;
      json runs = json::array();
      for (const auto& run : f->runs) {
        traces.push_back(run.trace);
        histories.push_back({run.best_value, run.trace, run.at_local_optimum});
        json points = json::array();
        for (const auto& p : run.trace) points.push_back({p.evaluations, number(p.value)});
        runs.push_back(std::move(points));
      }
      const sweep::ConvergenceBand band = sweep::convergence_band(traces);
      const Convergence verdict = assess_convergence(histories, {}, f->unconfirmed);
      series.push_back({{"optimizer", f->optimizer},
                        {"metric", metric_name(f->metric)},
                        {"converged", verdict.converged},
                        {"verdict", verdict.verdict()},
                        {"runs", std::move(runs)},
                        {"band",
                         {{"evaluations", numbers(band.evaluations)},
                          {"median", numbers(band.median)},
                          {"q25", numbers(band.lower_quartile)},
                          {"q75", numbers(band.upper_quartile)}}}});
    }
    out.push_back({{"model", model}, {"optimizers", std::move(series)}});
  }
  return out;
}

/// Final metric of every run, per (part, split, model, metric): conditions × optimizers.
json distributions(const ReportInput& in) {
  json out = json::array();
  std::map<std::tuple<std::string, std::string, std::string, int>, std::size_t> index;
  std::vector<std::vector<const FitInput*>> groups;
  for (const FitInput& f : in.fits) {
    if (f.runs.empty()) continue;
    const auto key = std::make_tuple(f.part, f.split, f.model_name, static_cast<int>(f.metric));
    auto [it, added] = index.try_emplace(key, groups.size());
    if (added) groups.emplace_back();
    groups[it->second].push_back(&f);
  }
  for (const auto& fits : groups) {
    const FitInput& first = *fits.front();
    std::vector<std::string> conditions, optimizers;
    for (const FitInput* f : fits) {
      if (std::find(conditions.begin(), conditions.end(), f->condition) == conditions.end()) conditions.push_back(f->condition);
      if (std::find(optimizers.begin(), optimizers.end(), f->optimizer) == optimizers.end()) optimizers.push_back(f->optimizer);
    }
    json values = json::array();  // [optimizer][condition] → final metric of each run
    for (const std::string& o : optimizers) {
      json row = json::array();
      for (const std::string& c : conditions) {
        json runs = json::array();
        for (const FitInput* f : fits)
          if (f->optimizer == o && f->condition == c)
            for (const auto& run : f->runs) runs.push_back(number(run.best_value));
        row.push_back(std::move(runs));
      }
      values.push_back(std::move(row));
    }
    out.push_back({{"part", first.part},
                   {"split", first.split},
                   {"model", first.model_name},
                   {"metric", metric_name(first.metric)},
                   {"conditions", conditions},
                   {"optimizers", optimizers},
                   {"values", std::move(values)}});
  }
  return out;
}

json ecdf_figures(const ReportInput& in) {
  json out = json::array();
  for (const Table& r : in.ecdfs) {
    if (r.columns.size() < 2) continue;
    json budgets = json::array(), series = json::array();
    for (const auto& row : r.rows) budgets.push_back(number(row.at(0).value.value_or(NAN)));
    for (std::size_t k = 1; k < r.columns.size(); ++k) {
      json fraction = json::array();
      for (const auto& row : r.rows) fraction.push_back(number(row.at(k).value.value_or(NAN)));
      series.push_back({{"label", r.columns[k]}, {"fraction", std::move(fraction)}});
    }
    out.push_back({{"id", r.id}, {"title", r.title}, {"budgets", std::move(budgets)}, {"series", std::move(series)}});
  }
  return out;
}

/// The variable a law is drawn against: its first one.
std::string first_variable(const ParameterLaw& law) {
  return law.factors.empty() ? std::string() : law.factors.front().variable;
}

json law_figures(const ReportInput& in) {
  json out = json::array();
  for (const LawFigureInput& l : in.laws) {
    const std::string axis = first_variable(l.law.law);
    if (axis.empty() || l.conditions.empty()) continue;
    const sweep::RegressionFit& fit = l.law.fit;
    // Conditions that share the values of every other variable form one curve.
    std::map<std::vector<std::pair<std::string, double>>, std::vector<std::size_t>> curves;
    for (std::size_t i = 0; i < l.conditions.size(); ++i) {
      std::vector<std::pair<std::string, double>> others;
      for (const auto& f : l.law.law.factors)
        if (f.variable != axis) others.emplace_back(f.variable, l.variables[i].at(f.variable));
      curves[others].push_back(i);
    }
    json groups = json::array();
    for (const auto& [others, members] : curves) {
      std::string label;
      for (const auto& [variable, value] : others) label += fmt::format("{}{} = {:g}", label.empty() ? "" : ", ", variable, value);
      json points = json::array();
      double lo = std::numeric_limits<double>::infinity(), hi = -lo;
      for (std::size_t i : members) {
        const double x = l.variables[i].at(axis);
        lo = std::min(lo, x);
        hi = std::max(hi, x);
        points.push_back({{"condition", l.conditions[i]},
                          {"x", number(x)},
                          {"y", number(fit.fitted[i] + fit.residuals[i])},
                          {"fitted", number(fit.fitted[i])},
                          {"undetermined", l.law.undetermined.at(i)}});
      }
      json cx = json::array(), cy = json::array();
      std::map<std::string, double> at = l.variables[members.front()];
      const int n = lo < hi ? 80 : 1;
      for (int k = 0; k < n; ++k) {
        at[axis] = n == 1 ? lo : lo + (hi - lo) * k / (n - 1);
        cx.push_back(number(at[axis]));
        cy.push_back(number(l.law.law.evaluate(fit.coefficients.data(), at)));
      }
      groups.push_back({{"label", label}, {"points", std::move(points)}, {"curve", {{"x", std::move(cx)}, {"y", std::move(cy)}}}});
    }
    out.push_back({{"title", l.title},
                   {"parameter", l.law.parameter},
                   {"law", l.law.law.text()},
                   {"variable", axis},
                   {"r2", number(fit.r2)},
                   {"groups", std::move(groups)}});
  }
  return out;
}

/// Tables as text cells, as `dampbench table` prints them.
json tables(const std::vector<Table>& list) {
  json out = json::array();
  for (const Table& r : list) {
    json rows = json::array();
    for (const auto& row : r.rows) {
      json cells = json::array();
      for (const auto& cell : row) cells.push_back(cell.text);
      rows.push_back(std::move(cells));
    }
    out.push_back({{"id", r.id}, {"title", r.title}, {"paper", r.paper}, {"note", r.note}, {"columns", r.columns},
                   {"rows", std::move(rows)}});
  }
  return out;
}

std::string escape_html(const std::string& s) {
  std::string out;
  for (char ch : s) {
    switch (ch) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += ch;
    }
  }
  return out;
}

/// JSON inside <script>: "</" would end the element early.
std::string script_safe(std::string s) {
  for (std::size_t at = s.find("</"); at != std::string::npos; at = s.find("</", at + 3)) s.replace(at, 2, "<\\/");
  return s;
}

}  // namespace

json report_data(const ReportInput& in, const HtmlOptions& options) {
  json fingerprint = json::array();
  for (const auto& [what, value] : in.fingerprint) fingerprint.push_back({what, value});
  json conditions = json::array();
  for (const Condition& c : conditions_of(in))
    conditions.push_back({{"part", c.part},
                          {"split", c.split},
                          {"condition", c.label},
                          {"records", record_figures(in, c, options)},
                          {"convergence", convergence_figures(c)}});
  return {{"title", in.title},          {"fingerprint", std::move(fingerprint)}, {"notes", in.notes},
          {"records", records(in, options)}, {"conditions", std::move(conditions)},
          {"held_out", prediction_figures(in, options)}, {"distributions", distributions(in)}, {"ecdfs", ecdf_figures(in)},
          {"runtimes", tables(in.runtimes)}, {"laws", law_figures(in)}, {"tables", tables(in.tables)}};
}

std::string render_html(const ReportInput& input, const HtmlOptions& options) {
  std::string html;
  html += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>";
  html += escape_html(input.title);
  html += "</title>\n<style>\n";
  html += kReportCss;
  html += "\n</style>\n</head>\n<body>\n<div id=\"report\"></div>\n<script type=\"application/json\" id=\"dampbench-data\">";
  html += script_safe(report_data(input, options).dump());
  html += "</script>\n<script>\n";
  html += kD3Js;  // D3 and the page script contain no "</script"
  html += "\n</script>\n<script>\n";
  html += kReportJs;
  html += "\n</script>\n</body>\n</html>\n";
  return html;
}

}  // namespace dampbench::report
