#include <posekit/device_registry.hpp>
#include <posekit/error.hpp>

#include "device/backend_factory.hpp"

#include <algorithm>
#include <cstdlib>
#include <exception>
#include <sstream>
#include <utility>

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

// "auto" prefers a real GPU, then the CPU backend, then GPU APIs emulated on the CPU.
int auto_rank(const BackendStatus& status) {
  if (status.name == "cpu") return 1;
  return status.info.emulated_on_cpu ? 2 : 0;
}

}  // namespace

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
  const std::vector<std::string> disabled = disabled_backends();
  if (name == "auto") {
    std::vector<std::pair<int, const detail::BackendFactory*>> candidates;
    for (const detail::BackendFactory& factory : factories) {
      const BackendStatus status = probe(factory, disabled);
      if (status.state == BackendState::available) candidates.emplace_back(auto_rank(status), &factory);
    }
    if (candidates.empty()) throw Error("no compute device is available (see 'posekit devices')");
    std::stable_sort(candidates.begin(), candidates.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    // A device that probes well can still fail to start (a driver out of memory, a lost GPU): then
    // the next best one is used.
    std::string failures;
    for (const auto& [rank, factory] : candidates) {
      try {
        return factory->create();
      } catch (const Error& error) {
        failures += (failures.empty() ? "" : "; ") + factory->name + ": " + error.what();
      }
    }
    throw Error("no compute device could be created (" + failures + ")");
  }
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
