// The correction's command-line flags, shared by `correct` and `correct-sequence`: one definition of
// each flag, its default and its check, and of how the flags become CorrectionOptions.
#pragma once

#include <posekit/correct.hpp>

#include <CLI/CLI.hpp>

#include <map>
#include <string>

namespace posekit::cli {

struct CorrectionFlags {
  std::string device = "auto";
  std::string exclude;  ///< file of vertex indices kept out of the constraints
  bool full_refactorization = false;
  bool progress_lines = false;
  std::map<std::string, bool> skipped_stages;  ///< --no-<stage>, one per optional repair stage
  CorrectionOptions correction;
};

/// Registers --device, --exclude, the fitting, integration and reproduction options, --progress and
/// one --no-<stage> flag per optional repair stage on `command`, stored in `flags`.
void add_correction_flags(CLI::App* command, CorrectionFlags& flags);

/// The options the flags ask for, with the excluded vertices read from their file (checked against
/// `vertex_count`).
CorrectionOptions correction_options(const CorrectionFlags& flags, int vertex_count);

}  // namespace posekit::cli
