#include "backend_status_json.hpp"

namespace posekit::cli {

nlohmann::json backend_status_json(const BackendStatus& status) {
  nlohmann::json entry{{"name", status.name}, {"state", to_string(status.state)}};
  if (status.state == BackendState::available) {
    entry["device"] = status.info.name;
    entry["driver"] = status.info.driver;
    entry["fp64"] = status.info.fp64;
    entry["emulated_on_cpu"] = status.info.emulated_on_cpu;
    entry["compute_units"] = status.info.compute_units;
    entry["max_buffer_bytes"] = status.info.max_buffer_bytes;
  } else {
    entry["reason"] = status.reason;
  }
  return entry;
}

}  // namespace posekit::cli
