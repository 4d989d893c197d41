#include <posekit/blend_files.hpp>
#include <posekit/error.hpp>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

namespace posekit {
namespace {

// The fields of each line that holds any, with its line number.
class FieldReader {
 public:
  FieldReader(const std::filesystem::path& file, const char* what) : name_(file.string()), stream_(file, std::ios::binary) {
    if (!stream_) throw InputError(name_, 0, std::string("cannot open the ") + what);
  }
  bool next(std::vector<std::string>& fields) {
    std::string line;
    while (std::getline(stream_, line)) {
      ++line_number_;
      const size_t comment = line.find('#');
      if (comment != std::string::npos) line.resize(comment);
      for (char& c : line) {
        if (c == '\t' || c == '\r') c = ' ';
      }
      std::istringstream words(line);
      fields.clear();
      std::string word;
      while (words >> word) fields.push_back(word);
      if (!fields.empty()) return true;
    }
    if (stream_.bad()) throw InputError(name_, line_number_, "read error");
    return false;
  }
  long line() const { return line_number_; }
  const std::string& name() const { return name_; }
  [[noreturn]] void fail(const std::string& problem) const { throw InputError(name_, line_number_, problem); }

  double number(const std::string& word, const char* what) const {
    errno = 0;
    char* end = nullptr;
    const double value = std::strtod(word.c_str(), &end);
    if (end == word.c_str() || *end != '\0') fail("'" + word + "' is not a number (" + what + ")");
    if (!std::isfinite(value)) fail(std::string(what) + " '" + word + "' is not finite");
    return value;
  }

 private:
  std::string name_;
  std::ifstream stream_;
  long line_number_ = 0;
};

}  // namespace

PointConstraints read_point_constraints(const std::filesystem::path& file, int vertex_count) {
  FieldReader reader(file, "constraint file");
  PointConstraints result;
  std::vector<Eigen::RowVector3d> positions;
  std::map<int, long> seen;
  std::vector<std::string> fields;
  while (reader.next(fields)) {
    if (fields.size() != 4 && fields.size() != 5) {
      reader.fail("expected 'VERTEX X Y Z [GROUP]', found " + std::to_string(fields.size()) + " fields");
    }
    errno = 0;
    char* end = nullptr;
    const long long index = std::strtoll(fields[0].c_str(), &end, 10);
    if (end == fields[0].c_str() || *end != '\0' || errno == ERANGE) {
      reader.fail("'" + fields[0] + "' is not a vertex index");
    }
    if (index < 0 || index >= vertex_count) {
      reader.fail("vertex index " + fields[0] + " is outside [0, " + std::to_string(vertex_count) + ")");
    }
    const auto [previous, inserted] = seen.emplace(static_cast<int>(index), reader.line());
    if (!inserted) {
      reader.fail("vertex " + fields[0] + " is already constrained on line " + std::to_string(previous->second));
    }
    const char* axes[3] = {"x", "y", "z"};
    Eigen::RowVector3d position;
    for (int a = 0; a < 3; ++a) position(a) = reader.number(fields[static_cast<size_t>(a) + 1], axes[a]);
    result.vertices.push_back(static_cast<int>(index));
    positions.push_back(position);
    result.groups.push_back(fields.size() == 5 ? fields[4] : std::string());
    result.lines.push_back(reader.line());
  }
  if (result.vertices.empty()) throw InputError(reader.name(), 0, "the file lists no constraint");
  result.positions.resize(static_cast<Eigen::Index>(positions.size()), 3);
  for (size_t r = 0; r < positions.size(); ++r) result.positions.row(static_cast<Eigen::Index>(r)) = positions[r];
  return result;
}

Eigen::MatrixXd read_skinning_weights(const std::filesystem::path& file, int vertex_count) {
  FieldReader reader(file, "skinning weight file");
  std::vector<double> values;
  size_t columns = 0;
  long rows = 0;
  std::vector<std::string> fields;
  while (reader.next(fields)) {
    if (columns == 0) columns = fields.size();
    if (fields.size() != columns) {
      reader.fail("row has " + std::to_string(fields.size()) + " weights; the first row has " + std::to_string(columns));
    }
    if (rows >= vertex_count) reader.fail("more rows than the " + std::to_string(vertex_count) + " vertices");
    bool any = false;
    for (const std::string& word : fields) {
      const double value = reader.number(word, "weight");
      any = any || value != 0.0;
      values.push_back(value);
    }
    if (!any) reader.fail("every weight of vertex " + std::to_string(rows) + " is zero");
    ++rows;
  }
  if (rows != vertex_count) {
    throw InputError(reader.name(), 0, "has " + std::to_string(rows) + " weight rows for " + std::to_string(vertex_count) +
                                           " vertices");
  }
  Eigen::MatrixXd weights(vertex_count, static_cast<Eigen::Index>(columns));
  for (long r = 0; r < rows; ++r) {
    for (size_t c = 0; c < columns; ++c) weights(r, static_cast<Eigen::Index>(c)) = values[static_cast<size_t>(r) * columns + c];
  }
  return weights;
}

}  // namespace posekit
