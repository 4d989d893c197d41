// Devices for the CUDA tests: skipped with the runtime's reason where this machine has no usable
// CUDA GPU, failed instead when POSEKIT_EXPECT_BACKENDS lists cuda.
#pragma once

#include "cuda/cuda_device.hpp"
#include "cuda/cuda_discovery.hpp"

#include <posekit/device_registry.hpp>

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

namespace posekit::cuda::testing {

/// Why no CUDA GPU can be used here, or empty when one can.
inline std::string cuda_unavailable_reason() {
  const Discovery discovery = discover_device();
  return discovery.device ? std::string() : discovery.reason;
}

/// Whether POSEKIT_EXPECT_BACKENDS names cuda.
inline bool cuda_expected() {
  const char* expected = std::getenv("POSEKIT_EXPECT_BACKENDS");
  if (expected == nullptr) return false;
  for (const std::string& name : parse_backend_list(expected)) {
    if (name == "cuda") return true;
  }
  return false;
}

}  // namespace posekit::cuda::testing

/// Skips the current test (fails it when cuda is expected) when no CUDA GPU is usable.
#define POSEKIT_REQUIRE_CUDA()                                                               \
  do {                                                                                       \
    const std::string posekit_reason_ = ::posekit::cuda::testing::cuda_unavailable_reason(); \
    if (!posekit_reason_.empty()) {                                                          \
      if (::posekit::cuda::testing::cuda_expected()) {                                       \
        FAIL() << "POSEKIT_EXPECT_BACKENDS lists cuda, but " << posekit_reason_;            \
      }                                                                                      \
      GTEST_SKIP() << "no CUDA device: " << posekit_reason_;                                 \
    }                                                                                        \
  } while (0)
