#pragma once
// Uniform numbers in [0, 1) from a 64-bit linear congruential generator (Knuth's MMIX constants): the same
// sequence on every platform and standard library, for tests that sweep an argument range.
#include <cstdint>

namespace ccal::test {

struct PortableUniform {
  std::uint64_t state;
  double operator()() {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return double(state >> 11) / double(1ull << 53);
  }
};

}  // namespace ccal::test
