#include <posekit/atomic_file.hpp>

#include <posekit/error.hpp>
#include <posekit/integer_list.hpp>
#include <posekit/rigid_segmentation.hpp>

#include <limits>
#include <string>
#include <vector>

namespace posekit {

Eigen::VectorXi read_part_labels(const std::filesystem::path& file, int vertex_count,
                                 const Eigen::Ref<const Eigen::MatrixX3i>& faces) {
  const std::string name = file.string();
  std::vector<int> labels = read_integer_list(file, "part id", 0, std::numeric_limits<int>::max());
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
  write_file_atomically(file, text);
}

}  // namespace posekit
