#include "kernel_isa.hpp"

namespace posekit::cpu {

const char* to_string(KernelIsa isa) {
  switch (isa) {
    case KernelIsa::baseline: return "baseline";
    case KernelIsa::avx2: return "avx2";
    case KernelIsa::avx512: return "avx512";
  }
  return "unknown";
}

bool is_supported(KernelIsa isa) {
  switch (isa) {
    case KernelIsa::baseline: return true;
#if POSEKIT_CPU_MULTIVERSION
    // __builtin_cpu_supports also checks that the operating system saves the vector registers.
    case KernelIsa::avx2:
      __builtin_cpu_init();
      return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    case KernelIsa::avx512:
      __builtin_cpu_init();
      return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
             __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx2") &&
             __builtin_cpu_supports("fma");
#else
    case KernelIsa::avx2:
    case KernelIsa::avx512: return false;
#endif
  }
  return false;
}

KernelIsa best_supported_isa() {
  if (is_supported(KernelIsa::avx512)) return KernelIsa::avx512;
  if (is_supported(KernelIsa::avx2)) return KernelIsa::avx2;
  return KernelIsa::baseline;
}

}  // namespace posekit::cpu
