#include "backend_status_json.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

#include <posekit/device_registry.hpp>

#include <iomanip>
#include <iostream>

namespace posekit::cli {
namespace {

void print_table(const std::vector<BackendStatus>& statuses) {
  std::cout << std::left << std::setw(8) << "backend" << std::setw(13) << "state"
            << "device or reason\n";
  for (const BackendStatus& status : statuses) {
    std::cout << std::left << std::setw(8) << status.name << std::setw(13) << to_string(status.state);
    if (status.state == BackendState::available) {
      std::cout << status.info.name;
      if (!status.info.driver.empty()) std::cout << " [" << status.info.driver << "]";
      std::cout << (status.info.fp64 ? ", fp64" : ", no fp64");
    } else {
      std::cout << status.reason;
    }
    std::cout << "\n";
  }
}

}  // namespace

void add_devices_command(CLI::App& app, int& exit_status) {
  auto* command = app.add_subcommand("devices", "List the compute backends, their state and devices");
  auto json = std::make_shared<bool>(false);
  command->add_flag("--json", *json, "Print JSON instead of a table");
  command->callback([json, &exit_status] {
    exit_status = run_guarded([&] {
      const std::vector<BackendStatus> statuses = list_backends();
      if (*json) {
        nlohmann::json list = nlohmann::json::array();
        for (const BackendStatus& status : statuses) list.push_back(backend_status_json(status));
        print_json(nlohmann::json{{"backends", list}});
      } else {
        print_table(statuses);
      }
    });
  });
}

}  // namespace posekit::cli
