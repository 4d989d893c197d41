// Finding a CUDA device, describing it, and saying why none was found.
#pragma once

#include <posekit/device.hpp>

#include <optional>
#include <string>

namespace posekit::cuda {

struct DiscoveredDevice {
  int ordinal = 0;
  std::string device_name;
  std::string driver;  ///< "driver X.Y, runtime A.B"
  int major = 0;       ///< compute capability
  int minor = 0;
  int multiprocessors = 0;
  int clock_khz = 0;   ///< peak clock of the multiprocessors
  unsigned long long global_memory_bytes = 0;
};

struct Discovery {
  std::optional<DiscoveredDevice> device;
  std::string reason;  ///< the runtime's error name and text when no device was found
};

/// Asks the CUDA runtime for devices; any error (no driver, insufficient driver, no device) is a
/// reason, never an exception. POSEKIT_CUDA_DEVICE picks an ordinal (default 0). A device for
/// whose architecture this build has no kernels is a reason too.
Discovery discover_device();

/// The registry's description: the GPU's name; the driver, runtime, architecture, multiprocessors,
/// clock and fp64 peak; fp64 (every CUDA GPU has it); global memory as the largest buffer.
DeviceInfo describe(const DiscoveredDevice& device);

/// Double-precision fused multiply-adds per clock of one multiprocessor of compute capability
/// major.minor, from NVIDIA's tables (32 on sm_60, sm_70 and sm_80, 64 on sm_90 and sm_100, 2 on
/// the GeForce-class parts); 0 where this table does not know the architecture.
int fp64_fma_per_clock(int major, int minor);

/// The fp64 peak in flop/s (a fused multiply-add counts 2): multiprocessors x fp64_fma_per_clock x
/// 2 x clock; 0 when unknown.
double fp64_peak_flops(const DiscoveredDevice& device);

/// Whether code built for `architectures` (CMAKE_CUDA_ARCHITECTURES joined by ',' or ';', e.g.
/// "80-real,90-real,90-virtual") runs on compute capability major.minor: machine code for NN runs
/// on NN and on later minor versions of the same major one (NNa only on NN), PTX for NN on NN and
/// every later architecture. Lists it cannot read ("native", "all", empty) count as running.
bool runs_on(const std::string& architectures, int major, int minor);

/// The architectures this build has kernels for, as CMake was given them.
std::string built_architectures();

}  // namespace posekit::cuda
