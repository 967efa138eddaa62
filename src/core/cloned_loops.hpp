#pragma once
// CCAL_CLONED: a hot loop compiled for each instruction set the machine may have (AVX-512, AVX2, baseline
// x86-64), the one to run chosen when the library is loaded (GCC's target_clones; ELF x86-64 only, else a
// plain function).
//
// Every clone must compute baseline x86-64's bits. The project compiles without floating-point contraction
// (-ffp-contract=off, CMakeLists.txt), but GCC 12's superword-level vectoriser still fuses a lane-alternating
// pair of scalar expressions a·b − c, a·d + e (a rotation by cos and sin, a complex product) into one
// vfmaddsub instruction. So a clone holds explicit SIMD (GCC's vector extensions, which it leaves alone) and
// code in which the test build.no_contraction finds no fused multiply-add; scalar rotations run in baseline
// code, outside the clones. (Turning the vectoriser off in the clones instead costs the bundled example's
// design 25 %.)
//
// CCAL_FLATTEN: everything a loop calls inlined into it (GCC's and Clang's flatten). Not in a sanitizer's
// build, where the instrumented, flattened clones of one loop took GCC over 25 minutes and 4 GB to compile;
// neither there nor in a build without clones is it needed.
#if defined(__x86_64__) && defined(__ELF__) && defined(__GNUC__) && !defined(__clang__) && \
    !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)
#define CCAL_CLONED [[gnu::target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")]]
#define CCAL_FLATTEN [[gnu::flatten]]
#else
#define CCAL_CLONED
#define CCAL_FLATTEN
#endif

#include <cstring>

namespace ccal::lanes {

// Eight doubles in GCC's and Clang's vector extension (one AVX-512 register, two AVX2 ones), each lane IEEE
// arithmetic on its own: the SIMD lanes of the cloned loops. They pass between functions of one file, inlined
// into the clones, so the ABI note GCC gives for 64-byte vectors in baseline code is moot there.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif
inline constexpr int kWidth = 8;
using Doubles = double __attribute__((vector_size(kWidth * sizeof(double))));

// A T (double or Doubles) from consecutive doubles, and back.
template <class T>
[[gnu::always_inline]] inline T load(const double* p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
template <class T>
[[gnu::always_inline]] inline void store(double* p, const T& v) {
  std::memcpy(p, &v, sizeof v);
}

}  // namespace ccal::lanes
