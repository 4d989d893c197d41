#include <posekit/geometry.hpp>

namespace posekit {

Eigen::VectorXd edge_lengths(const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                             const Eigen::Ref<const Eigen::MatrixX2i>& edges) {
  Eigen::VectorXd lengths(edges.rows());
  for (Eigen::Index e = 0; e < edges.rows(); ++e) {
    lengths(e) = (vertices.row(edges(e, 1)) - vertices.row(edges(e, 0))).norm();
  }
  return lengths;
}

}  // namespace posekit
