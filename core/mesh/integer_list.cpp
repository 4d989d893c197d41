#include <posekit/error.hpp>
#include <posekit/integer_list.hpp>

#include <fstream>
#include <sstream>

namespace posekit {

std::vector<int> read_integer_list(const std::filesystem::path& file, const std::string& what, int lowest, int end) {
  const std::string name = file.string();
  std::ifstream stream(file);
  if (!stream) throw InputError(name, 0, "cannot open the file");
  std::vector<int> values;
  std::string line;
  long line_number = 0;
  while (std::getline(stream, line)) {
    ++line_number;
    line = line.substr(0, line.find('#'));
    std::istringstream words(line);
    std::string word;
    while (words >> word) {
      size_t used = 0;
      long long value = 0;
      try {
        value = std::stoll(word, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != word.size() || used == 0) throw InputError(name, line_number, "'" + word + "' is not a " + what);
      if (value < lowest || value >= end) {
        throw InputError(name, line_number,
                         what + " " + word + " is outside [" + std::to_string(lowest) + ", " + std::to_string(end) + ")");
      }
      values.push_back(static_cast<int>(value));
    }
  }
  if (stream.bad()) throw InputError(name, 0, "read failed");
  return values;
}

}  // namespace posekit
