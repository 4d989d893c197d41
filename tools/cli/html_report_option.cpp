#include "html_report_option.hpp"

namespace posekit::cli {
namespace {

std::string& stored_command_line() {
  static std::string line;
  return line;
}

std::string quoted(const std::string& argument) {
  if (!argument.empty() && argument.find_first_of(" \t\"'\\$") == std::string::npos) return argument;
  std::string text = "'";
  for (const char c : argument) text += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return text + "'";
}

}  // namespace

void add_html_option(CLI::App* command, std::string& file) {
  command->add_option("--html", file,
                      "Write an interactive HTML report to this file (one self-contained page that opens offline)");
}

void set_command_line(int argc, const char* const* argv) {
  std::string line = "posekit";
  for (int i = 1; i < argc; ++i) line += " " + quoted(argv[i]);
  stored_command_line() = line;
}

const std::string& command_line() { return stored_command_line(); }

}  // namespace posekit::cli
