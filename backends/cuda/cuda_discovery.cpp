#include "cuda_discovery.hpp"

#include "cuda_check.hpp"

#include <cuda_runtime_api.h>

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#ifndef POSEKIT_CUDA_ARCHITECTURES
#define POSEKIT_CUDA_ARCHITECTURES ""
#endif

namespace posekit::cuda {
namespace {

std::string version_text(int version) {
  return std::to_string(version / 1000) + "." + std::to_string((version % 1000) / 10);
}

std::string fixed(double value, int digits) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", digits, value);
  return text;
}

}  // namespace

int fp64_fma_per_clock(int major, int minor) {
  const int architecture = 10 * major + minor;
  switch (architecture) {
    case 60: case 70: case 80: return 32;       // P100, V100, A100
    case 90: case 100: return 64;               // H100 / H200, B200
    case 61: case 62: return 4;
    case 72: case 75: case 86: case 87: case 89: case 120: case 121: return 2;
    default: return 0;
  }
}

double fp64_peak_flops(const DiscoveredDevice& device) {
  return 2.0 * fp64_fma_per_clock(device.major, device.minor) * device.multiprocessors *
         (device.clock_khz * 1e3);
}

bool runs_on(const std::string& architectures, int major, int minor) {
  std::string list = architectures;
  for (char& c : list) {
    if (c == ';') c = ',';
  }
  std::stringstream entries(list);
  std::string entry;
  bool understood = false;
  const int device = 10 * major + minor;
  while (std::getline(entries, entry, ',')) {
    std::size_t digits = 0;
    while (digits < entry.size() && std::isdigit(static_cast<unsigned char>(entry[digits]))) {
      ++digits;
    }
    if (digits == 0) continue;
    understood = true;
    const int built = std::atoi(entry.substr(0, digits).c_str());
    std::string rest = entry.substr(digits);
    const bool specific = !rest.empty() && rest[0] == 'a';  // sm_90a: that architecture only
    if (!rest.empty() && (rest[0] == 'a' || rest[0] == 'f')) rest.erase(0, 1);
    const bool real = rest.empty() || rest == "-real";
    const bool virtual_code = rest.empty() || rest == "-virtual";
    if (real && (specific ? device == built : (device / 10 == built / 10 && device >= built))) {
      return true;
    }
    if (virtual_code && !specific && device >= built) return true;
  }
  return !understood;
}

std::string built_architectures() { return POSEKIT_CUDA_ARCHITECTURES; }

Discovery discover_device() {
  Discovery discovery;
  int count = 0;
  const cudaError_t counted = cudaGetDeviceCount(&count);
  if (counted != cudaSuccess) {
    cudaGetLastError();  // leave no error behind for a later call to report
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
    cudaGetLastError();
    discovery.reason = "cudaGetDeviceProperties failed (" + describe(queried) + ")";
    return discovery;
  }
  int driver_version = 0;
  int runtime_version = 0;
  int clock_khz = 0;
  if (cudaDriverGetVersion(&driver_version) != cudaSuccess ||
      cudaRuntimeGetVersion(&runtime_version) != cudaSuccess ||
      cudaDeviceGetAttribute(&clock_khz, cudaDevAttrClockRate, ordinal) != cudaSuccess) {
    cudaGetLastError();  // only descriptive values are missing
  }
  DiscoveredDevice found;
  found.ordinal = ordinal;
  found.device_name = properties.name;
  found.driver = "driver " + version_text(driver_version) + ", runtime " +
                 version_text(runtime_version);
  found.major = properties.major;
  found.minor = properties.minor;
  found.multiprocessors = properties.multiProcessorCount;
  found.clock_khz = clock_khz;
  found.global_memory_bytes = properties.totalGlobalMem;
  if (!runs_on(built_architectures(), found.major, found.minor)) {
    discovery.reason = "found " + found.device_name + " (sm_" + std::to_string(found.major) +
                       std::to_string(found.minor) + "), but this build has CUDA kernels for " +
                       built_architectures() +
                       " only (rebuild with CMAKE_CUDA_ARCHITECTURES including " +
                       std::to_string(found.major) + std::to_string(found.minor) + ")";
    return discovery;
  }
  discovery.device = found;
  return discovery;
}

DeviceInfo describe(const DiscoveredDevice& device) {
  DeviceInfo info;
  info.backend = "cuda";
  info.name = device.device_name;
  info.driver = device.driver + ", sm_" + std::to_string(device.major) +
                std::to_string(device.minor) + ", " + std::to_string(device.multiprocessors) +
                " SMs at " + std::to_string(device.clock_khz / 1000) + " MHz";
  const double peak = fp64_peak_flops(device);
  info.driver += peak > 0 ? ", fp64 peak " + fixed(peak * 1e-9, 0) + " GFLOP/s"
                          : ", fp64 peak unknown";
  info.fp64 = true;
  info.emulated_on_cpu = false;
  info.max_buffer_bytes = device.global_memory_bytes;
  info.compute_units = device.multiprocessors;
  return info;
}

}  // namespace posekit::cuda
