// Each subcommand registers itself on the application; its callback stores the exit status.
#pragma once

#include <CLI/CLI.hpp>

namespace posekit::cli {

void add_devices_command(CLI::App& app, int& exit_status);
void add_check_command(CLI::App& app, int& exit_status);
void add_convert_command(CLI::App& app, int& exit_status);
void add_generate_command(CLI::App& app, int& exit_status);
void add_demo_command(CLI::App& app, int& exit_status);
void add_correct_command(CLI::App& app, int& exit_status);
void add_correct_sequence_command(CLI::App& app, int& exit_status);
void add_interpolate_command(CLI::App& app, int& exit_status);
void add_deform_command(CLI::App& app, int& exit_status);
void add_register_command(CLI::App& app, int& exit_status);

}  // namespace posekit::cli
