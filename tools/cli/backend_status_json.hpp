// A compute backend's state as JSON: the entries of `posekit devices --json` and of the Python
// package's devices().
#pragma once

#include <posekit/device_registry.hpp>

#include <nlohmann/json.hpp>

namespace posekit::cli {

/// `name`, `state`, then the device's `device`, `driver`, `fp64`, `emulated_on_cpu`, `compute_units`
/// and `max_buffer_bytes` when it is available, or the `reason` when it is not.
nlohmann::json backend_status_json(const BackendStatus& status);

}  // namespace posekit::cli
