#include "geometry/vertex_checks.hpp"

#include <posekit/error.hpp>

namespace posekit::detail {

void check_finite_vertices(const Eigen::Ref<const Eigen::MatrixX3d>& vertices, const std::string& function) {
  if (vertices.allFinite()) return;
  for (Eigen::Index v = 0; v < vertices.rows(); ++v) {
    if (!vertices.row(v).allFinite()) {
      throw ArgumentError(function + ": vertex " + std::to_string(v) + " has a coordinate that is not finite");
    }
  }
}

}  // namespace posekit::detail
