// Runs the posekit executable (or another program) in a child process and captures what it printed.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace posekit::testing {

struct CommandResult {
  int exit_status = -1;  ///< the process's exit code, or 128 + signal when it was killed
  std::string out;
  std::string err;
  /// Lines of stderr (a final newline does not start a new line).
  std::vector<std::string> err_lines() const;
};

/// Runs `posekit ARGS...` (the build's own binary) with stdin closed.
CommandResult run_posekit(const std::vector<std::string>& arguments);

/// The same, killed (SIGKILL, exit status 137) as soon as `stop` returns true: an interrupted run.
CommandResult run_posekit_until(const std::vector<std::string>& arguments, const std::function<bool()>& stop);

/// Runs `program ARGS...` (a path, or a name looked up in PATH) with stdin closed.
CommandResult run_program(const std::string& program, const std::vector<std::string>& arguments);

}  // namespace posekit::testing
