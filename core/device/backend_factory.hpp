// How a backend plugs into the registry: a probe that never throws and a constructor.
#pragma once

#include <posekit/device_registry.hpp>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace posekit::detail {

struct BackendFactory {
  std::string name;
  /// Reports the state on this machine; must not throw.
  std::function<BackendStatus()> probe;
  /// Creates the device; called only when probe() said available. May throw Error.
  std::function<std::unique_ptr<Device>()> create;
};

/// Every backend known to this build, GPU backends first and cpu last (backends/builtin_backends.cpp).
std::vector<BackendFactory> builtin_backends();

/// create_device() over the given factories instead of the built-in ones.
std::unique_ptr<Device> create_device(const std::vector<BackendFactory>& factories, const std::string& name);

/// Status of a backend that this build does not contain.
BackendStatus not_built_status(const std::string& name, const std::string& reason);

}  // namespace posekit::detail
