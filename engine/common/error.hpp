#pragma once
// Errors raised at the boundary (files, sweep specs, command-line values, the results store). Hot loops never
// throw: a failed candidate is a +inf metric, not an exception (docs/design.md, "Performance principles").
// Each class has its exit code (engine/cli/main.cpp; README "Exit codes").
#include <stdexcept>
#include <string>

namespace dampbench {

/// Bad user input: a command-line value or option (exit 2). The message names where and what was expected.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Input data that cannot be used: a record or sweep file that is missing or malformed, or the options that say
/// how to read it (exit 3). The message names the file, line and key or column.
class DataError : public InputError {
 public:
  using InputError::InputError;
};

/// The results store cannot be opened, read or written, belongs to another sweep, or is locked (exit 4).
class StoreError : public InputError {
 public:
  using InputError::InputError;
};

/// The user stopped the work (Ctrl-C in the Python module); what finished before is kept by the caller.
class Interrupted : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Exit codes of the command line, one per class of outcome.
enum ExitCode : int {
  kExitOk = 0,
  kExitDifferent = 1,   ///< `verify` found differences, `table` found no such table
  kExitUsage = 2,       ///< InputError and command-line syntax
  kExitData = 3,        ///< DataError
  kExitStore = 4,       ///< StoreError, and output files or folders that cannot be written
  kExitInternal = 70,   ///< anything else: a bug (EX_SOFTWARE)
  kExitInterrupted = 130,
};

/// Runs `fn`; an InputError it throws (other than a StoreError) comes out as a DataError with the same message:
/// everything that goes wrong while reading a record or a sweep file is about that input.
template <class Fn>
auto as_data_error(Fn&& fn) {
  try {
    return fn();
  } catch (const DataError&) {
    throw;
  } catch (const StoreError&) {
    throw;
  } catch (const InputError& e) {
    throw DataError(e.what());
  }
}

}  // namespace dampbench
