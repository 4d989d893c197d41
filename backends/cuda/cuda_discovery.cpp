#include "cuda_discovery.hpp"

#include <cuda_runtime_api.h>

#include <cstdlib>

namespace posekit::cuda {
namespace {

std::string describe(cudaError_t error) {
  return std::string(cudaGetErrorName(error)) + ": " + cudaGetErrorString(error);
}

std::string version_text(int version) {
  return std::to_string(version / 1000) + "." + std::to_string((version % 1000) / 10);
}

}  // namespace

Discovery discover_device() {
  Discovery discovery;
  int count = 0;
  const cudaError_t counted = cudaGetDeviceCount(&count);
  if (counted != cudaSuccess) {
    discovery.reason = "cudaGetDeviceCount failed (" + describe(counted) + ")";
    return discovery;
  }
  if (count == 0) {
    discovery.reason = "no CUDA device found";
    return discovery;
  }
  int ordinal = 0;
  if (const char* wanted = std::getenv("POSEKIT_CUDA_DEVICE")) ordinal = std::atoi(wanted);
  if (ordinal < 0 || ordinal >= count) {
    discovery.reason = "POSEKIT_CUDA_DEVICE=" + std::to_string(ordinal) + " but there are " +
                       std::to_string(count) + " CUDA devices";
    return discovery;
  }
  cudaDeviceProp properties{};
  const cudaError_t queried = cudaGetDeviceProperties(&properties, ordinal);
  if (queried != cudaSuccess) {
    discovery.reason = "cudaGetDeviceProperties failed (" + describe(queried) + ")";
    return discovery;
  }
  int driver_version = 0;
  int runtime_version = 0;
  cudaDriverGetVersion(&driver_version);
  cudaRuntimeGetVersion(&runtime_version);
  DiscoveredDevice found;
  found.ordinal = ordinal;
  found.device_name = properties.name;
  found.driver = "driver " + version_text(driver_version) + ", runtime " + version_text(runtime_version) +
                 ", sm_" + std::to_string(properties.major) + std::to_string(properties.minor);
  found.compute_units = properties.multiProcessorCount;
  found.global_memory_bytes = properties.totalGlobalMem;
  discovery.device = found;
  return discovery;
}

}  // namespace posekit::cuda
