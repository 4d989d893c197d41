#include "keyword_options.hpp"

#include <posekit/error.hpp>

#include <algorithm>
#include <cctype>
#include <string>
#include <vector>

namespace posekit::python {
namespace py = pybind11;

namespace {

// "--key-frames" in a command-line message becomes "key_frames", the keyword's name.
std::string keyword_names(const std::string& message) {
  std::string out;
  for (size_t i = 0; i < message.size(); ++i) {
    if (message.compare(i, 2, "--") == 0 && i + 2 < message.size() && std::islower(static_cast<unsigned char>(message[i + 2]))) {
      i += 2;
      while (i < message.size() && (std::islower(static_cast<unsigned char>(message[i])) || message[i] == '-')) {
        out += message[i] == '-' ? '_' : message[i];
        ++i;
      }
      --i;
    } else {
      out += message[i];
    }
  }
  return out;
}

}  // namespace

void parse_keywords(CLI::App& app, const py::kwargs& keywords) {
  std::vector<std::string> arguments;
  for (const auto& [key, value] : keywords) {
    std::string flag = "--" + std::string(py::str(key));
    std::replace(flag.begin(), flag.end(), '_', '-');
    if (py::isinstance<py::bool_>(value)) {
      // A flag: true switches it on; false leaves its default (off).
      if (value.cast<bool>()) arguments.push_back(flag);
    } else {
      arguments.push_back(flag);
      arguments.push_back(py::str(value));
    }
  }
  std::reverse(arguments.begin(), arguments.end());  // CLI11 takes the arguments last first
  try {
    app.parse(arguments);
  } catch (const CLI::ParseError& error) {
    throw ArgumentError(app.get_name() + ": " + keyword_names(error.what()));
  }
}

}  // namespace posekit::python
