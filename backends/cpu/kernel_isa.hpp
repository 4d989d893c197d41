// The instruction sets the CPU backend's hot loops are compiled for, and which of them this
// processor can run. The library itself is built for the architecture's baseline so that it runs
// anywhere; only the few hot loops get extra copies for wider vector units, chosen at run time.
#pragma once

namespace posekit::cpu {

/// A compiled copy of the hot loops: baseline (any processor of the target architecture),
/// AVX2 with FMA, or AVX-512 (F, DQ, VL). Only x86-64 builds with GCC or Clang have the last two.
enum class KernelIsa { baseline, avx2, avx512 };

/// "baseline", "avx2" or "avx512".
const char* to_string(KernelIsa isa);

/// Whether this build contains the copy and this processor (and its operating system) can run it.
bool is_supported(KernelIsa isa);

/// The widest supported copy.
KernelIsa best_supported_isa();

}  // namespace posekit::cpu

#if defined(__GNUC__)
#define POSEKIT_CPU_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define POSEKIT_CPU_ALWAYS_INLINE inline
#endif

// Function attributes of the extra copies; a file defines the same body under each of them.
#if defined(__GNUC__) && defined(__x86_64__)
#define POSEKIT_CPU_MULTIVERSION 1
#define POSEKIT_CPU_TARGET_AVX2 __attribute__((target("avx2,fma")))
#define POSEKIT_CPU_TARGET_AVX512 __attribute__((target("avx512f,avx512dq,avx512vl,avx2,fma")))
#else
#define POSEKIT_CPU_MULTIVERSION 0
#endif
