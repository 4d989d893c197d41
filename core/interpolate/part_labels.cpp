#include "mesh/atomic_file.hpp"

#include <posekit/error.hpp>
#include <posekit/rigid_segmentation.hpp>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace posekit {

Eigen::VectorXi read_part_labels(const std::filesystem::path& file, int vertex_count, const Eigen::MatrixX3i& faces) {
  const std::string name = file.string();
  std::ifstream stream(file);
  if (!stream) throw InputError(name, 0, "cannot open the part label file");
  std::vector<int> labels;
  std::string line;
  long line_number = 0;
  while (std::getline(stream, line)) {
    ++line_number;
    line = line.substr(0, line.find('#'));
    std::istringstream words(line);
    std::string word;
    while (words >> word) {
      size_t used = 0;
      long long id = -1;
      try {
        id = std::stoll(word, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != word.size() || id < 0 || id > 1'000'000'000) {
        throw InputError(name, line_number, "'" + word + "' is not a part id (a non-negative integer)");
      }
      labels.push_back(static_cast<int>(id));
    }
  }
  if (stream.bad()) throw InputError(name, 0, "read failed");
  const auto count = static_cast<long long>(labels.size());
  const Eigen::Map<const Eigen::VectorXi> read(labels.data(), static_cast<Eigen::Index>(labels.size()));
  if (count == faces.rows()) return read;
  if (count == vertex_count) return face_labels_from_vertex_labels(read, faces);
  throw InputError(name, 0,
                   std::to_string(count) + " part ids, but the mesh has " + std::to_string(vertex_count) +
                       " vertices and " + std::to_string(faces.rows()) + " faces (give one id per vertex or per face)");
}

void write_part_labels(const std::filesystem::path& file, const Eigen::VectorXi& face_labels) {
  std::string text;
  text.reserve(static_cast<size_t>(face_labels.size()) * 4 + 64);
  text += "# posekit part id of each face, in face order\n";
  for (Eigen::Index f = 0; f < face_labels.size(); ++f) {
    text += std::to_string(face_labels(f));
    text += '\n';
  }
  detail::write_file_atomically(file, text);
}

}  // namespace posekit
