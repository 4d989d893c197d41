// The --html option every job command shares, and the command line a report shows.
#pragma once

#include <CLI/CLI.hpp>

#include <string>

namespace posekit::cli {

/// Adds `--html FILE` to `command`, stored in `file`.
void add_html_option(CLI::App* command, std::string& file);

/// Remembers the command line (from main) for the reports to show.
void set_command_line(int argc, const char* const* argv);

/// The command line as given, each argument with spaces or quotes quoted.
const std::string& command_line();

}  // namespace posekit::cli
