// Pieces shared by the posekit subcommands: error reporting, JSON output, atomic text files.
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace posekit::cli {

/// Runs a subcommand body; turns any exception into one line on stderr and exit status 1.
int run_guarded(const std::function<void()>& body);

/// Prints each warning as one "posekit: warning: ..." line on stderr.
void print_warnings(const std::vector<std::string>& warnings);

/// Writes `text` to `file` whole or not at all (temporary file in the same folder, then rename).
void write_text_atomically(const std::filesystem::path& file, const std::string& text);

/// Prints JSON to stdout, indented.
void print_json(const nlohmann::json& value);

}  // namespace posekit::cli
