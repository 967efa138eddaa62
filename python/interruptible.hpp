#pragma once
// Long computations from Python that Ctrl-C stops and that report progress: the computation runs on a worker
// thread while the calling (main) thread, the only one on which Python runs signal handlers, waits in steps
// of 50 ms without the GIL; between steps it runs the pending signal handlers (PyErr_CheckSignals) and the
// user's progress callback. A KeyboardInterrupt, or an exception from the callback, asks the computation to
// stop (its ProgressCallback throws Cancelled at its next poll, at most 0.1 s later), waits for it to end and
// raises that exception: nothing is returned and nothing is left half-done.
#include <pybind11/pybind11.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <type_traits>
#include <utility>

#include "ccal/core/progress.hpp"

namespace ccal::python {

namespace py = pybind11;

// Progress shared between the worker's callback and the waiting thread.
struct ProgressState {
  std::atomic<bool> cancel{false};
  std::atomic<bool> fresh{false};
  std::atomic<std::uint64_t> done{0}, total{0};
};

// progress: None or a callable, found now, not as "'int' object is not callable" from within the
// computation's first report.
inline void check_progress_argument(const py::object& progress) {
  if (!progress.is_none() && !PyCallable_Check(progress.ptr()))
    throw py::type_error("progress: expected None or a callable progress(done, total), got " +
                         std::string(py::str(progress.get_type().attr("__name__"))) + " (" +
                         std::string(py::repr(progress)) + ")");
}

// compute(ProgressCallback) → result; progress: None or a callable progress(done, total) run on the calling
// thread with the GIL, about every 0.05–0.1 s.
template <class Compute>
auto run_interruptible(const py::object& progress, Compute&& compute)
    -> std::invoke_result_t<Compute&, ProgressCallback> {
  using Result = std::invoke_result_t<Compute&, ProgressCallback>;
  check_progress_argument(progress);
  auto state = std::make_shared<ProgressState>();
  const ProgressCallback callback = [state](std::uint64_t done, std::uint64_t total) {
    state->done.store(done);
    state->total.store(total);
    state->fresh.store(true);
    if (state->cancel.load()) throw Cancelled();
  };
  std::optional<Result> result;
  std::exception_ptr error;
  std::mutex mutex;
  std::condition_variable ended;
  bool finished = false;
  std::thread worker([&] {
    try {
      result.emplace(compute(callback));
    } catch (...) {
      error = std::current_exception();
    }
    const std::lock_guard lock(mutex);
    finished = true;
    ended.notify_all();
  });
  std::optional<py::error_already_set> python_error;
  try {
    for (;;) {
      bool done = false;
      {
        py::gil_scoped_release release;
        std::unique_lock lock(mutex);
        done = ended.wait_for(lock, std::chrono::milliseconds(50), [&] { return finished; });
      }
      if (done) break;
      if (python_error) continue;  // cancelled: wait for the computation to stop
      try {
        if (PyErr_CheckSignals() != 0) throw py::error_already_set();
        if (!progress.is_none() && state->fresh.exchange(false)) progress(state->done.load(), state->total.load());
      } catch (py::error_already_set& e) {
        python_error.emplace(std::move(e));
        state->cancel.store(true);
      }
    }
  } catch (...) {  // never leave the worker running
    state->cancel.store(true);
    {
      py::gil_scoped_release release;
      worker.join();
    }
    throw;
  }
  worker.join();
  if (python_error) throw *python_error;  // KeyboardInterrupt, or the callback's exception
  if (error) std::rethrow_exception(error);
  if (!progress.is_none() && state->total.load() > 0) progress(state->total.load(), state->total.load());
  return std::move(*result);
}

}  // namespace ccal::python
