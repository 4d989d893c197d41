#include "opencl_discovery.hpp"

#include "pocl_cache.hpp"

#include <cstdlib>
#include <exception>
#include <vector>

namespace posekit::opencl {
namespace {

bool has_fp64(const cl::Device& device) {
  cl_device_fp_config config = 0;
  if (device.getInfo(CL_DEVICE_DOUBLE_FP_CONFIG, &config) != CL_SUCCESS) return false;
  return config != 0;
}

bool is_usable(const cl::Device& device) {
  cl_bool available = CL_FALSE;
  cl_bool compiler = CL_FALSE;
  return device.getInfo(CL_DEVICE_AVAILABLE, &available) == CL_SUCCESS && available == CL_TRUE &&
         device.getInfo(CL_DEVICE_COMPILER_AVAILABLE, &compiler) == CL_SUCCESS &&
         compiler == CL_TRUE;
}

std::string info_string(const cl::Platform& platform, cl_platform_info what) {
  std::string value;
  platform.getInfo(what, &value);
  while (!value.empty() && value.back() == '\0') value.pop_back();
  return value;
}

std::string info_string(const cl::Device& device, cl_device_info what) {
  std::string value;
  device.getInfo(what, &value);
  while (!value.empty() && value.back() == '\0') value.pop_back();
  return value;
}

Discovery discover() {
  Discovery discovery;
  std::vector<cl::Platform> platforms;
  const cl_int status = cl::Platform::get(&platforms);
  if (status != CL_SUCCESS || platforms.empty()) {
    discovery.reason = "no OpenCL platform found (clGetPlatformIDs returned " +
                       std::to_string(status) +
                       "; is an ICD such as pocl-opencl-icd installed?)";
    return discovery;
  }
  const char* wanted_platform = std::getenv("POSEKIT_OPENCL_PLATFORM");
  std::vector<std::string> without_fp64;
  std::vector<std::string> unusable;
  for (const cl::Platform& platform : platforms) {
    // Version strings can run long (PoCL appends its build options after two spaces): keep the head.
    std::string version = info_string(platform, CL_PLATFORM_VERSION);
    version = version.substr(0, version.find("  "));
    const std::string platform_name =
        info_string(platform, CL_PLATFORM_NAME) + " (" + version + ")";
    if (wanted_platform != nullptr && platform_name.find(wanted_platform) == std::string::npos)
      continue;
    std::vector<cl::Device> devices;
    if (platform.getDevices(CL_DEVICE_TYPE_ALL, &devices) != CL_SUCCESS) continue;
    for (const cl::Device& device : devices) {
      const std::string device_name = info_string(device, CL_DEVICE_NAME);
      if (!has_fp64(device)) {
        without_fp64.push_back(device_name);
        continue;
      }
      if (!is_usable(device)) {
        unusable.push_back(device_name);
        continue;
      }
      cl_device_type type = 0;
      device.getInfo(CL_DEVICE_TYPE, &type);
      const bool is_cpu = (type & CL_DEVICE_TYPE_CPU) != 0;
      // A GPU beats a CPU device; among equals the first found wins.
      if (discovery.device && !(discovery.device->is_cpu && !is_cpu)) continue;
      DiscoveredDevice found;
      found.platform = platform;
      found.device = device;
      found.platform_name = platform_name;
      found.device_name = device_name;
      found.driver_version = info_string(device, CL_DRIVER_VERSION);
      found.is_cpu = is_cpu;
      cl_ulong max_allocation = 0;
      device.getInfo(CL_DEVICE_MAX_MEM_ALLOC_SIZE, &max_allocation);
      found.max_allocation_bytes = max_allocation;
      cl_uint units = 0;
      device.getInfo(CL_DEVICE_MAX_COMPUTE_UNITS, &units);
      found.compute_units = static_cast<int>(units);
      discovery.device = found;
    }
  }
  if (!discovery.device) {
    if (!without_fp64.empty()) {
      discovery.reason = "no OpenCL device with fp64 (cl_khr_fp64); found without it: " +
                         without_fp64.front();
    } else if (!unusable.empty()) {
      discovery.reason = "the OpenCL device with fp64 is not available or has no compiler: " +
                         unusable.front();
    } else if (wanted_platform != nullptr) {
      discovery.reason =
          std::string("no OpenCL platform matches POSEKIT_OPENCL_PLATFORM=") + wanted_platform;
    } else {
      discovery.reason = "no OpenCL device found";
    }
  }
  return discovery;
}

}  // namespace

Discovery discover_device() {
  try {
    prepare_opencl_environment();
    return discover();
  } catch (const std::exception& error) {
    // Allocation failures and the like; a broken driver must not end the process.
    Discovery discovery;
    discovery.reason = std::string("OpenCL device discovery failed: ") + error.what();
    return discovery;
  }
}

DeviceInfo describe_device(const DiscoveredDevice& device) {
  DeviceInfo info;
  info.backend = "opencl";
  info.name = device.device_name;
  info.driver = device.platform_name;
  if (!device.driver_version.empty()) info.driver += ", driver " + device.driver_version;
  info.fp64 = true;
  info.emulated_on_cpu = device.is_cpu;
  info.max_buffer_bytes = device.max_allocation_bytes;
  info.compute_units = device.compute_units;
  return info;
}

}  // namespace posekit::opencl
