#include "engine/fit/fit_records.hpp"

#include "engine/fit/fit.hpp"
#include "engine/record/record_options.hpp"

namespace dampbench {

std::vector<const Signals*> FitRecords::pointers() const {
  std::vector<const Signals*> p;
  for (const Signals& s : signals) p.push_back(&s);
  return p;
}

double FitRecords::samples() const {
  double n = 0;
  for (const Signals& s : signals) n += static_cast<double>(s.size());
  return n;
}

FitRecords load_fit_records(const Model& model, const std::vector<std::string>& paths, const RecordOptions& data) {
  FitRecords r;
  r.signals.reserve(paths.size());  // pointers() point into it
  for (const std::string& path : paths) {
    RecordOptions d = data;
    d.path = path;
    r.signals.push_back(prepare_signals(load_record(d, true)));
    check_record(model, r.signals.back());
    r.names += (r.names.empty() ? "" : "+") + r.signals.back().name;
  }
  return r;
}

}  // namespace dampbench
