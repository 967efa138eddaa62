#pragma once
// Progress reports and cancellation of long computations (the Monte Carlo, the allocation's verification):
// the caller passes a callback, which the computation calls from one of its threads at most every 0.1 s
// with the work done and the work of the current stage. The callback may throw Cancelled (or any exception)
// to stop the computation: it ends within one poll interval plus the trials in flight, and returns nothing.
#include <cstdint>
#include <functional>
#include <stdexcept>

namespace ccal {

// done and total count trials (the current stage's end, for the adaptive Monte Carlo). Called concurrently
// never: one thread at a time, but not always the same one.
using ProgressCallback = std::function<void(std::uint64_t done, std::uint64_t total)>;

// Thrown by a progress callback to stop the computation; passes through the library unchanged.
class Cancelled : public std::runtime_error {
 public:
  Cancelled() : std::runtime_error("cancelled") {}
};

}  // namespace ccal
