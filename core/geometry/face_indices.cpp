#include <posekit/error.hpp>
#include <posekit/topology.hpp>

#include <string>

namespace posekit {

void check_face_indices(const Eigen::Ref<const Eigen::MatrixX3i>& faces, int vertex_count) {
  if (vertex_count < 0) {
    throw ArgumentError("vertex_count must not be negative (got " + std::to_string(vertex_count) + ")");
  }
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    for (int corner = 0; corner < 3; ++corner) {
      const int vertex = faces(f, corner);
      if (vertex < 0 || vertex >= vertex_count) {
        throw ArgumentError("face " + std::to_string(f) + " corner " + std::to_string(corner) +
                            " refers to vertex " + std::to_string(vertex) + ", outside [0, " +
                            std::to_string(vertex_count) + ")");
      }
    }
  }
}

}  // namespace posekit
