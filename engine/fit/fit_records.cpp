#include "engine/fit/fit_records.hpp"

#include <fmt/format.h>

#include "engine/common/error.hpp"
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

namespace {

void add_record(const Model& model, const Dataset& record, FitRecords& r) {
  r.signals.push_back(prepare_signals(record));
  check_record(model, r.signals.back());
  r.names += (r.names.empty() ? "" : "+") + r.signals.back().name;
}

}  // namespace

FitRecords load_fit_records(const Model& model, const std::vector<std::string>& paths, const RecordOptions& data) {
  std::vector<Dataset> records;
  for (const std::string& path : paths) {
    RecordOptions d = data;
    d.path = path;
    for (Dataset& record : load_records(d, true)) records.push_back(std::move(record));
  }
  FitRecords r;
  r.signals.reserve(records.size());  // pointers() point into it
  for (const Dataset& record : records) add_record(model, record, r);
  return r;
}

FitRecords command_records(const Model& model, const std::vector<std::string>& paths,
                           const std::vector<Dataset>& records, const RecordOptions& data, std::string_view command) {
  if (paths.empty() && records.empty()) throw InputError(fmt::format("{}: give at least one --data FILE", command));
  if (!paths.empty() && !records.empty())
    throw InputError(fmt::format("{}: give records as files or as loaded records, not both", command));
  return records.empty() ? load_fit_records(model, paths, data) : fit_records_of(model, records);
}

FitRecords fit_records_of(const Model& model, const std::vector<Dataset>& records) {
  FitRecords r;
  r.signals.reserve(records.size());
  for (const Dataset& record : records) {
    if (!record.has_measured())
      throw InputError(fmt::format("record '{}' has no {}: fitting and evaluating need the measured output", record.name,
                                   record.is_system() ? "displacement y" : "force F"));
    add_record(model, record, r);
  }
  return r;
}

}  // namespace dampbench
