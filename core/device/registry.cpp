#include <posekit/device_registry.hpp>
#include <posekit/error.hpp>

#include "device/backend_factory.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <optional>
#include <sstream>

#ifdef __linux__
#include <dirent.h>
#include <unistd.h>
#endif

namespace posekit {
namespace {

std::vector<std::string> disabled_backends() {
  const char* variable = std::getenv("POSEKIT_DISABLE_BACKENDS");
  return variable == nullptr ? std::vector<std::string>{} : parse_backend_list(variable);
}

BackendStatus probe(const detail::BackendFactory& factory, const std::vector<std::string>& disabled) {
  if (std::find(disabled.begin(), disabled.end(), factory.name) != disabled.end()) {
    BackendStatus status;
    status.name = factory.name;
    status.state = BackendState::unavailable;
    status.reason = "disabled by POSEKIT_DISABLE_BACKENDS";
    return status;
  }
  try {
    BackendStatus status = factory.probe();
    status.name = factory.name;
    return status;
  } catch (const std::exception& error) {
    // Probes are written not to throw; this keeps a broken driver from ending the process.
    BackendStatus status;
    status.name = factory.name;
    status.state = BackendState::unavailable;
    status.reason = error.what();
    return status;
  }
}

bool is_cpu_backend(const detail::BackendFactory& factory) { return factory.name == "cpu"; }

// A factory without a presence check is probed as before, whatever that costs.
bool may_have_gpu(const detail::BackendFactory& factory) {
  return !factory.may_have_gpu || factory.may_have_gpu();
}

// "auto" prefers a real GPU, then the CPU backend, then GPU APIs emulated on the CPU (PoCL,
// lavapipe), each in registration order. Probing a GPU API starts it (a CUDA runtime, a Vulkan
// instance, OpenCL's platforms), which costs a tenth of a second or more on a machine without a
// GPU; so GPU APIs are probed only where their presence check allows a GPU, the first real GPU that
// starts ends the search, and the emulations are probed only once the CPU backend has failed.
std::unique_ptr<Device> create_auto_device(const std::vector<detail::BackendFactory>& factories) {
  const std::vector<std::string> disabled = disabled_backends();
  std::vector<std::optional<BackendStatus>> statuses(factories.size());
  std::vector<bool> attempted(factories.size(), false);
  bool any_available = false;
  std::string failures;

  const auto is_available = [&](std::size_t index) {
    if (!statuses[index]) statuses[index] = probe(factories[index], disabled);
    return statuses[index]->state == BackendState::available;
  };
  // A device that probes well can still fail to start (a driver out of memory, a lost GPU): then
  // nullptr, and the next best one is tried.
  const auto try_create = [&](std::size_t index) -> std::unique_ptr<Device> {
    attempted[index] = true;
    any_available = true;
    try {
      return factories[index].create();
    } catch (const Error& error) {
      failures += (failures.empty() ? "" : "; ") + factories[index].name + ": " + error.what();
      return nullptr;
    }
  };

  // Real GPUs; an emulation found on the way keeps its status for the last round.
  for (std::size_t index = 0; index < factories.size(); ++index) {
    if (is_cpu_backend(factories[index]) || !may_have_gpu(factories[index])) continue;
    if (!is_available(index) || statuses[index]->info.emulated_on_cpu) continue;
    if (std::unique_ptr<Device> device = try_create(index)) return device;
  }
  for (std::size_t index = 0; index < factories.size(); ++index) {
    if (!is_cpu_backend(factories[index]) || !is_available(index)) continue;
    if (std::unique_ptr<Device> device = try_create(index)) return device;
  }
  // Emulations, and GPU APIs whose presence check said no, in case it was wrong.
  for (std::size_t index = 0; index < factories.size(); ++index) {
    if (is_cpu_backend(factories[index]) || attempted[index] || !is_available(index)) continue;
    if (std::unique_ptr<Device> device = try_create(index)) return device;
  }
  if (!any_available) throw Error("no compute device is available (see 'posekit devices')");
  throw Error("no compute device could be created (" + failures + ")");
}

#ifdef __linux__
bool path_exists(const char* path) { return access(path, F_OK) == 0; }

// Whether the directory exists and has an entry (other than . and ..) whose name starts with the prefix.
bool directory_has_entry(const char* directory, const char* name_prefix = "") {
  DIR* listing = opendir(directory);
  if (listing == nullptr) return false;
  bool found = false;
  const std::size_t prefix_length = std::strlen(name_prefix);
  while (const dirent* entry = readdir(listing)) {
    if (entry->d_name[0] != '.' && std::strncmp(entry->d_name, name_prefix, prefix_length) == 0) {
      found = true;
      break;
    }
  }
  closedir(listing);
  return found;
}
#endif

}  // namespace

namespace detail {

bool nvidia_gpu_may_be_present() noexcept {
#ifdef __linux__
  // /proc/driver/nvidia/gpus lists the GPUs the kernel module found even before anything has
  // created their device nodes (nvidia-modprobe does that on CUDA's first use).
  return path_exists("/dev/nvidiactl") || path_exists("/dev/nvidia0") || path_exists("/dev/dxg") ||
         directory_has_entry("/proc/driver/nvidia/gpus");
#else
  return true;
#endif
}

bool gpu_may_be_present() noexcept {
#ifdef __linux__
  // Render nodes, not /dev/dri/card*: a display-only driver (a virtual machine's framebuffer) has a
  // card node but nothing to compute on.
  return nvidia_gpu_may_be_present() || directory_has_entry("/dev/dri", "renderD") ||
         path_exists("/dev/kfd") || path_exists("/dev/mali0") || path_exists("/dev/kgsl-3d0");
#else
  return true;
#endif
}

}  // namespace detail

std::vector<std::string> parse_backend_list(const std::string& comma_separated) {
  std::vector<std::string> names;
  std::stringstream list(comma_separated);
  std::string name;
  while (std::getline(list, name, ',')) {
    name.erase(0, name.find_first_not_of(" \t"));
    name.erase(name.find_last_not_of(" \t") + 1);
    if (!name.empty()) names.push_back(name);
  }
  return names;
}

const char* to_string(BackendState state) {
  switch (state) {
    case BackendState::available: return "available";
    case BackendState::unavailable: return "unavailable";
    case BackendState::not_built: return "not built";
  }
  return "unknown";
}

namespace detail {
BackendStatus not_built_status(const std::string& name, const std::string& reason) {
  BackendStatus status;
  status.name = name;
  status.state = BackendState::not_built;
  status.reason = reason;
  return status;
}
}  // namespace detail

std::vector<BackendStatus> list_backends() {
  const std::vector<std::string> disabled = disabled_backends();
  std::vector<BackendStatus> statuses;
  for (const detail::BackendFactory& factory : detail::builtin_backends()) {
    statuses.push_back(probe(factory, disabled));
  }
  return statuses;
}

std::unique_ptr<Device> create_device(const std::string& name) {
  return detail::create_device(detail::builtin_backends(), name);
}

std::unique_ptr<Device> detail::create_device(const std::vector<BackendFactory>& factories, const std::string& name) {
  if (name == "auto") return create_auto_device(factories);
  const std::vector<std::string> disabled = disabled_backends();
  for (const detail::BackendFactory& factory : factories) {
    if (factory.name != name) continue;
    const BackendStatus status = probe(factory, disabled);
    if (status.state != BackendState::available) {
      throw Error("device '" + name + "' is " + to_string(status.state) + ": " + status.reason);
    }
    return factory.create();
  }
  std::string known;
  for (const detail::BackendFactory& factory : factories) known += " " + factory.name;
  throw ArgumentError("unknown device '" + name + "' (expected auto or one of:" + known + ")");
}

}  // namespace posekit
