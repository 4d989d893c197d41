// Devices for the OpenCL tests: skipped with the registry's reason where this machine has no OpenCL
// device with fp64, failed instead when POSEKIT_EXPECT_BACKENDS lists opencl.
#pragma once

#include "opencl/opencl_device.hpp"
#include "opencl/opencl_discovery.hpp"

#include <posekit/device_registry.hpp>

#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>
#include <string>

namespace posekit::opencl::testing {

/// Why no OpenCL device can be used here, or empty when one can.
inline std::string opencl_unavailable_reason() {
  const Discovery discovery = discover_device();
  return discovery.device ? std::string() : discovery.reason;
}

/// Whether POSEKIT_EXPECT_BACKENDS names opencl.
inline bool opencl_expected() {
  const char* expected = std::getenv("POSEKIT_EXPECT_BACKENDS");
  if (expected == nullptr) return false;
  for (const std::string& name : parse_backend_list(expected)) {
    if (name == "opencl") return true;
  }
  return false;
}

}  // namespace posekit::opencl::testing

/// Skips the current test (fails it when opencl is expected) when no OpenCL device is usable.
#define POSEKIT_REQUIRE_OPENCL()                                                             \
  do {                                                                                       \
    const std::string posekit_reason_ = ::posekit::opencl::testing::opencl_unavailable_reason(); \
    if (!posekit_reason_.empty()) {                                                          \
      if (::posekit::opencl::testing::opencl_expected()) {                                   \
        FAIL() << "POSEKIT_EXPECT_BACKENDS lists opencl, but " << posekit_reason_;          \
      }                                                                                      \
      GTEST_SKIP() << "no OpenCL device: " << posekit_reason_;                               \
    }                                                                                        \
  } while (0)
