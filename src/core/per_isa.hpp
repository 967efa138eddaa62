#pragma once
// Code compiled once per instruction set, for loops whose clones must differ in their source, not only in the
// instructions the compiler picks (cloned_loops.hpp's target_clones gives every clone the same source):
// a body file, included by per_isa_bodies.inc into the namespaces isa_v4 (AVX-512: x86-64-v4), isa_v3 (AVX2
// and FMA: x86-64-v3) and isa_base (baseline x86-64, the only one on other compilers and in sanitizer builds),
// each under `#pragma GCC target` and with CCAL_ISA_LEVEL 4, 3 or 0; running_isa() names the one this
// processor runs. A body may then use the fused multiply-add where its
// result is exact (exact_products.inc), so that every namespace computes the same bits.
//
// Usage, at namespace scope of a source file that has included every header the body needs (the body named
// relative to src/core/, where the including file is):
//   #define CCAL_ISA_BODY "../layer/my_loops.inc"
//   #include "../core/per_isa_bodies.inc"
// then call the function f of the body by CCAL_ON_THIS_ISA(f(arguments)): isa_v4::f, isa_v3::f or isa_base::f,
// by running_isa().
#if defined(__x86_64__) && defined(__ELF__) && defined(__GNUC__) && !defined(__clang__) && \
    !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)
#define CCAL_PER_ISA 1
#include <immintrin.h>
#else
#define CCAL_PER_ISA 0
#endif

namespace ccal {

enum class Isa { v4, v3, base };

// The instruction set of this processor, as GCC's resolver picks target_clones' "arch=x86-64-v4",
// "arch=x86-64-v3" or "default" (core/cloned_loops.hpp): the same choice for both kinds of clone.
inline Isa running_isa() {
#if CCAL_PER_ISA
  static const Isa isa = __builtin_cpu_supports("x86-64-v4")   ? Isa::v4
                         : __builtin_cpu_supports("x86-64-v3") ? Isa::v3
                                                               : Isa::base;
  return isa;
#else
  return Isa::base;
#endif
}

}  // namespace ccal

// The statement `call`, a call of a void function of the body, in this processor's namespace.
#if CCAL_PER_ISA
#define CCAL_ON_THIS_ISA(call)      \
  do {                              \
    switch (::ccal::running_isa()) { \
      case ::ccal::Isa::v4:         \
        isa_v4::call;               \
        break;                      \
      case ::ccal::Isa::v3:         \
        isa_v3::call;               \
        break;                      \
      case ::ccal::Isa::base:       \
        isa_base::call;             \
        break;                      \
    }                               \
  } while (false)
#else
#define CCAL_ON_THIS_ISA(call) isa_base::call
#endif
