#include "geometry/vertex_checks.hpp"

#include <posekit/error.hpp>
#include <posekit/geometry.hpp>

namespace posekit {

double bounding_box_diagonal(const Eigen::Ref<const Eigen::MatrixX3d>& vertices) {
  if (vertices.rows() == 0) throw ArgumentError("bounding_box_diagonal: the mesh has no vertex");
  detail::check_finite_vertices(vertices, "bounding_box_diagonal");
  return (vertices.colwise().maxCoeff() - vertices.colwise().minCoeff()).norm();
}

}  // namespace posekit
