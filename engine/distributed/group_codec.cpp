#include "engine/distributed/group_codec.hpp"

#include <cstdint>
#include <array>
#include <cstring>
#include <type_traits>

#include <fmt/format.h>

#include "engine/common/error.hpp"

namespace dampbench::distributed {
namespace {

/// Values written as their bytes: numbers, enums, trace points, fixed arrays of doubles.
template <class T>
concept Raw = std::is_arithmetic_v<T> || std::is_enum_v<T> || std::is_same_v<T, TracePoint> ||
              std::is_same_v<T, std::array<double, kMetricCount>>;

/// Appends raw values, strings and vectors (length first), optionals and the records' structs to a byte string.
class Writer {
 public:
  template <Raw T>
  void put(const T& v) {
    out_.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  void put(const std::string& s) {
    put(static_cast<std::uint64_t>(s.size()));
    out_.append(s);
  }
  template <class T>
  void put(const std::vector<T>& v) {
    put(static_cast<std::uint64_t>(v.size()));
    for (const auto& x : v) put(x);
  }
  template <class T>
  void put(const std::optional<T>& v) {
    put(static_cast<std::uint8_t>(v.has_value()));
    if (v) put(*v);
  }
  void put(const sweep::RunRecord& r) {
    put(r.run);
    put(r.best_value);
    put(r.metrics);
    put(r.params);
    put(r.evaluations);
    put(r.stop_reason);
    put(r.trace);
    put(static_cast<std::uint8_t>(r.at_local_optimum));
  }
  void put(const sweep::DatasetMetricRecord& d) {
    put(d.run);
    put(d.dataset);
    put(static_cast<std::uint8_t>(d.predicted));
    put(d.metrics);
  }
  void put(const sweep::SensitivityRecord& s) {
    put(s.dataset);
    put(s.S);
    put(s.SP);
  }
  void put(const Identifiability& id) {
    put(id.std_error);
    put(id.relative_error);
    put(id.correlation);
    put(id.flags);
    put(id.samples);
  }
  std::string take() { return std::move(out_); }

 private:
  std::string out_;
};

/// Bytes of a default T as Writer writes it: the least any element of type T takes, so that a length prefix can
/// be checked against the bytes left before anything is allocated.
template <class T>
std::size_t encoded_size() {
  static const std::size_t bytes = [] {
    Writer w;
    w.put(T{});
    return w.take().size();
  }();
  return bytes;
}

/// Reads what Writer wrote, in the same order; DataError instead of reading past the end.
class Reader {
 public:
  explicit Reader(std::string_view in) : in_(in) {}
  template <Raw T>
  void get(T& v) {
    need(sizeof v);
    std::memcpy(&v, in_.data() + at_, sizeof v);
    at_ += sizeof v;
  }
  void get(std::string& s) {
    const std::size_t n = length(1);
    s.assign(in_.data() + at_, n);
    at_ += n;
  }
  template <class T>
  void get(std::vector<T>& v) {
    v.resize(length(encoded_size<T>()));
    for (auto& x : v) get(x);
  }
  template <class T>
  void get(std::optional<T>& v) {
    std::uint8_t has = 0;
    get(has);
    v.reset();
    if (has) get(v.emplace());
  }
  void get(bool& b) {
    std::uint8_t x = 0;
    get(x);
    b = x != 0;
  }
  void get(sweep::RunRecord& r) {
    get(r.run);
    get(r.best_value);
    get(r.metrics);
    get(r.params);
    get(r.evaluations);
    get(r.stop_reason);
    get(r.trace);
    get(r.at_local_optimum);
  }
  void get(sweep::DatasetMetricRecord& d) {
    get(d.run);
    get(d.dataset);
    get(d.predicted);
    get(d.metrics);
  }
  void get(sweep::SensitivityRecord& s) {
    get(s.dataset);
    get(s.S);
    get(s.SP);
  }
  void get(Identifiability& id) {
    get(id.std_error);
    get(id.relative_error);
    get(id.correlation);
    get(id.flags);
    get(id.samples);
  }
  void done() const {
    if (at_ != in_.size())
      throw DataError(fmt::format("task group message: {} bytes left over after the record", in_.size() - at_));
  }

 private:
  /// A length prefix, checked against what is left (each element takes at least `element_bytes`).
  std::size_t length(std::size_t element_bytes) {
    std::uint64_t n = 0;
    get(n);
    if (n > (in_.size() - at_) / element_bytes) need(in_.size() - at_ + 1);
    return static_cast<std::size_t>(n);
  }
  void need(std::size_t bytes) const {
    if (bytes > in_.size() - at_)
      throw DataError(fmt::format("task group message: truncated at byte {} of {}", at_, in_.size()));
  }
  std::string_view in_;
  std::size_t at_ = 0;
};

}  // namespace

std::string encode_group(const sweep::GroupRecord& g) {
  Writer w;
  w.put(g.index);
  w.put(g.part);
  w.put(g.split);
  w.put(g.fitset);
  w.put(g.model);
  w.put(g.optimizer);
  w.put(g.metric);
  w.put(g.runs);
  w.put(g.task_key);
  w.put(static_cast<std::uint8_t>(g.failed));
  w.put(g.message);
  w.put(g.wall_time_s);
  w.put(g.candidate_samples);
  w.put(g.evaluations);
  w.put(g.dampbench_version);
  w.put(g.build_flags);
  w.put(g.spec_hash);
  w.put(g.dataset_hash);
  w.put(g.laws);
  w.put(g.run_results);
  w.put(g.dataset_metrics);
  w.put(g.sensitivity);
  w.put(g.identifiability);
  return w.take();
}

sweep::GroupRecord decode_group(std::string_view bytes) {
  Reader r(bytes);
  sweep::GroupRecord g;
  r.get(g.index);
  r.get(g.part);
  r.get(g.split);
  r.get(g.fitset);
  r.get(g.model);
  r.get(g.optimizer);
  r.get(g.metric);
  if (const auto m = static_cast<int>(g.metric); m < 0 || m >= kMetricCount)
    throw DataError(fmt::format("task group message: metric number {} is not one of the {} metrics", m, kMetricCount));
  r.get(g.runs);
  r.get(g.task_key);
  r.get(g.failed);
  r.get(g.message);
  r.get(g.wall_time_s);
  r.get(g.candidate_samples);
  r.get(g.evaluations);
  r.get(g.dampbench_version);
  r.get(g.build_flags);
  r.get(g.spec_hash);
  r.get(g.dataset_hash);
  r.get(g.laws);
  r.get(g.run_results);
  r.get(g.dataset_metrics);
  r.get(g.sensitivity);
  r.get(g.identifiability);
  r.done();
  return g;
}

}  // namespace dampbench::distributed
