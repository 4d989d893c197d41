#include <posekit/error.hpp>
#include <posekit/submesh.hpp>

#include <string>

namespace posekit {

Mesh submesh(const Eigen::Ref<const Eigen::MatrixX3d>& vertices, const Eigen::Ref<const Eigen::MatrixX3i>& faces,
             const std::vector<char>& keep_face,
             std::vector<int>* original_vertex) {
  if (keep_face.size() != static_cast<size_t>(faces.rows())) {
    throw ArgumentError("submesh: " + std::to_string(keep_face.size()) + " face flags for " +
                        std::to_string(faces.rows()) + " faces");
  }
  std::vector<int> index_of(static_cast<size_t>(vertices.rows()), -1);
  std::vector<int> original;
  std::vector<Eigen::RowVector3i> kept;
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    if (keep_face[static_cast<size_t>(f)] == 0) continue;
    Eigen::RowVector3i face;
    for (int c = 0; c < 3; ++c) {
      const int v = faces(f, c);
      if (v < 0 || v >= vertices.rows()) {
        throw ArgumentError("submesh: face " + std::to_string(f) + " names vertex " + std::to_string(v) +
                            ", outside [0, " + std::to_string(vertices.rows()) + ")");
      }
      int& index = index_of[static_cast<size_t>(v)];
      if (index < 0) {
        index = static_cast<int>(original.size());
        original.push_back(v);
      }
      face(c) = index;
    }
    kept.push_back(face);
  }
  Mesh part;
  part.vertices.resize(static_cast<Eigen::Index>(original.size()), 3);
  for (size_t i = 0; i < original.size(); ++i) part.vertices.row(static_cast<Eigen::Index>(i)) = vertices.row(original[i]);
  part.faces.resize(static_cast<Eigen::Index>(kept.size()), 3);
  for (size_t f = 0; f < kept.size(); ++f) part.faces.row(static_cast<Eigen::Index>(f)) = kept[f];
  if (original_vertex != nullptr) *original_vertex = std::move(original);
  return part;
}

}  // namespace posekit
