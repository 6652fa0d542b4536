// Errors of the engine as Python exceptions, one class per exit code of the command line (engine/common/error.hpp),
// each carrying the command line's message; and run_released, which every long call goes through.
#include <chrono>
#include <condition_variable>
#include <exception>
#include <filesystem>
#include <mutex>
#include <new>
#include <thread>

#include <fmt/format.h>
#include <tbb/global_control.h>

#include "engine/common/error.hpp"
#include "engine/kernels/isa.hpp"
#include "python/src/bindings.hpp"

namespace dampbench::python {

namespace {

/// The module's exception classes (bind_errors makes them).
struct ErrorClasses {
  py::handle usage, data, store, internal;
};
ErrorClasses classes;

/// Raises `cls` (its class attribute exit_code is the command line's exit code) with `message`.
void raise(py::handle cls, const char* message) { PyErr_SetString(cls.ptr(), message); }

}  // namespace

void bind_errors(py::module_& m) {
  // Error is the base of every dampbench error; its subclasses follow the exit codes of the command line.
  static py::exception<std::runtime_error> error(m, "Error");
  static py::exception<InputError> usage(m, "UsageError", error.ptr());
  static py::exception<DataError> data(m, "DataError", usage.ptr());
  static py::exception<StoreError> store(m, "StoreError", usage.ptr());
  static py::exception<std::logic_error> internal(m, "InternalError", error.ptr());
  error.doc() = "Any error of dampbench; exit_code is the command line's for the same error.";
  usage.doc() = "A bad value or option (the command line's exit code 2).";
  data.doc() = "A record or file that cannot be used, or the options saying how to read it (exit code 3).";
  store.doc() = "A store or output file that cannot be opened, read or written (exit code 4).";
  internal.doc() = "A bug in dampbench (exit code 70): please report it.";
  classes = {usage, data, store, internal};
  error.attr("exit_code") = static_cast<int>(kExitInternal);
  usage.attr("exit_code") = static_cast<int>(kExitUsage);
  data.attr("exit_code") = static_cast<int>(kExitData);
  store.attr("exit_code") = static_cast<int>(kExitStore);
  internal.attr("exit_code") = static_cast<int>(kExitInternal);
  py::register_exception_translator([](std::exception_ptr p) {
    if (!p) return;
    try {
      std::rethrow_exception(p);
    } catch (const Interrupted&) {
      PyErr_SetNone(PyExc_KeyboardInterrupt);
    } catch (const StoreError& e) {
      raise(classes.store, e.what());
    } catch (const DataError& e) {
      raise(classes.data, e.what());
    } catch (const InputError& e) {
      raise(classes.usage, e.what());
    } catch (const std::filesystem::filesystem_error& e) {  // output folders and files, as the command line
      raise(classes.store, e.what());
    } catch (const std::bad_alloc&) {
      PyErr_SetString(PyExc_MemoryError, "out of memory");
    } catch (const py::error_already_set&) {
      throw;  // a Python error raised inside a callback: pybind11 restores it
    } catch (const py::builtin_exception&) {
      throw;  // pybind11's own (TypeError, ValueError, ...)
    } catch (const std::exception& e) {
      raise(classes.internal, (std::string("internal error (please report it): ") + e.what()).c_str());
    }
  });
}

void run_released(const std::function<void()>& work, std::atomic<bool>& stop, const EngineLimits& limits) {
  std::optional<tbb::global_control> thread_limit;
  if (limits.threads) {
    if (*limits.threads < 1) throw InputError(fmt::format("threads: expected a whole number >= 1, got {}", *limits.threads));
    thread_limit.emplace(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(*limits.threads));
  }
  const Isa previous_isa = active_isa();
  if (limits.isa) select_isa(*limits.isa, "isa");
  struct RestoreIsa {
    Isa isa;
    ~RestoreIsa() { select_isa(isa); }
  } restore{previous_isa};

  std::mutex mutex;
  std::condition_variable finished;
  bool done = false, interrupted = false;
  std::exception_ptr failure;
  {
    py::gil_scoped_release released;
    std::thread worker([&] {
      try {
        work();
      } catch (...) {
        failure = std::current_exception();
      }
      const std::lock_guard lock(mutex);
      done = true;
      finished.notify_one();
    });
    std::unique_lock lock(mutex);
    while (!finished.wait_for(lock, std::chrono::milliseconds(50), [&] { return done; })) {
      lock.unlock();
      {
        py::gil_scoped_acquire held;
        if (PyErr_CheckSignals() != 0) {  // the handler raised (KeyboardInterrupt): stop the work, raise it after
          PyErr_Clear();
          interrupted = true;
          stop = true;
        }
      }
      lock.lock();
    }
    lock.unlock();
    worker.join();
  }
  if (interrupted) throw Interrupted("interrupted");
  if (failure) std::rethrow_exception(failure);
}

}  // namespace dampbench::python
