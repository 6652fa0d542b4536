#pragma once
// The store's schema (its tables are described in engine/sweep/store.hpp) and the small facts every part of the
// store agrees on: the group columns in read order, the metric list a run's blob holds, the time stamps.
// Internal to engine/sweep/store.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "engine/identification/convergence.hpp"
#include "engine/sweep/store/records.hpp"

struct sqlite3;

namespace dampbench::sweep::store_db {

extern const char* const kSchema;
/// The columns of `groups`, in the order read_group_row reads them.
extern const char* const kGroupColumns;

/// The metrics a run records, in blob order ("of_abs,of_sq,..."): a store is read with the same list.
std::string metric_list();
/// The current UTC time, ISO 8601 to the second.
std::string now_utc();
/// A count kept as text in `meta` under `key` ("" reads 0); anything but digits, or above 10^8, is a StoreError.
long long count(const std::string& text, std::string_view key);
/// An unsigned integer kept as text in the given base (a group's task key in hex); anything else is a StoreError
/// naming `what`.
std::uint64_t stored_integer(const std::string& text, int base, std::string_view what);

/// A best-so-far trace as a blob of (evaluations as the bits of a double, value) pairs, and back.
std::vector<double> trace_blob(const std::vector<TracePoint>& trace);
std::vector<TracePoint> trace_points(const std::vector<double>& v);

/// Writes the header of a new store (meta, parts, models, optimizers, splits, datasets, fit sets).
void insert_header(sqlite3* db, const StoreHeader& h);

}  // namespace dampbench::sweep::store_db
