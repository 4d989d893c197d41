#include <posekit/error.hpp>
#include <posekit/geometry.hpp>
#include <posekit/topology.hpp>

#include <algorithm>
#include <limits>

namespace posekit {

Eigen::VectorXd edge_stretch(const Eigen::Ref<const Eigen::MatrixX3d>& pose,
                             const Eigen::Ref<const Eigen::MatrixX3d>& first,
                             const Eigen::Ref<const Eigen::MatrixX3d>& second,
                             const Eigen::Ref<const Eigen::MatrixX3i>& faces, double shortest) {
  if (first.rows() != pose.rows() || second.rows() != pose.rows()) {
    throw ArgumentError("edge stretch of poses with " + std::to_string(pose.rows()) + ", " +
                        std::to_string(first.rows()) + " and " + std::to_string(second.rows()) + " vertices");
  }
  check_face_indices(faces, static_cast<int>(pose.rows()));
  if (!(shortest >= 0.0)) throw ArgumentError("the shortest edge length of edge stretch must be >= 0");
  Eigen::VectorXd stretch(faces.rows());
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    double largest = 0.0;
    for (int c = 0; c < 3; ++c) {
      const int a = faces(f, c);
      const int b = faces(f, (c + 1) % 3);
      const double length = (pose.row(a) - pose.row(b)).norm();
      const double bound =
          std::max({(first.row(a) - first.row(b)).norm(), (second.row(a) - second.row(b)).norm(), shortest});
      // An edge of no length in both poses (and no floor) stays 1 while it keeps none.
      const double ratio = bound > 0.0 ? length / bound : (length > 0.0 ? std::numeric_limits<double>::infinity() : 1.0);
      largest = std::max(largest, ratio);
    }
    stretch(f) = largest;
  }
  return stretch;
}

}  // namespace posekit
