#include "cli_common.hpp"

#include <posekit/error.hpp>

#include <cstdio>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>

namespace posekit::cli {
namespace {

// Exception texts are meant to be one line; a stray newline from a third-party message is folded.
std::string one_line(std::string text) {
  for (char& c : text) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  return text;
}

}  // namespace

int run_guarded(const std::function<void()>& body) {
  try {
    body();
    return 0;
  } catch (const std::bad_alloc&) {
    std::cerr << "posekit: error: out of memory\n";
  } catch (const std::exception& error) {
    std::cerr << "posekit: error: " << one_line(error.what()) << "\n";
  }
  return 1;
}

void print_warnings(const std::vector<std::string>& warnings) {
  for (const std::string& warning : warnings) std::cerr << "posekit: warning: " << one_line(warning) << "\n";
}

void write_text_atomically(const std::filesystem::path& file, const std::string& text) {
  std::random_device random;
  std::filesystem::path temporary = file;
  temporary += ".tmp-" + std::to_string(random());
  {
    std::ofstream stream(temporary, std::ios::binary | std::ios::trunc);
    if (!stream) throw InputError(file.string(), 0, "cannot open for writing");
    stream << text;
    stream.flush();
    if (!stream) {
      stream.close();
      std::filesystem::remove(temporary);
      throw InputError(file.string(), 0, "write failed");
    }
  }
  std::error_code error;
  std::filesystem::rename(temporary, file, error);
  if (error) {
    std::filesystem::remove(temporary);
    throw InputError(file.string(), 0, "cannot replace the file: " + error.message());
  }
}

void print_json(const nlohmann::json& value) { std::cout << value.dump(2) << "\n"; }

}  // namespace posekit::cli
