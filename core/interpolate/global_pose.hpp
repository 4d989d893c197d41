// The six global pose parameters of the mixed shape space: each pose's barycentre and the logarithm
// of its rotation against pose 0, combined linearly and used to place an interpolated shape.
#pragma once

#include <posekit/mesh.hpp>

#include <Eigen/Core>

#include <vector>

namespace posekit::interpolation {

class GlobalPose {
 public:
  /// The barycentre (mean of the vertices that faces use) of every pose and its orientation: the
  /// rotation that best aligns pose 0 with it (Kabsch), as a rotation vector. `poses` must outlive this.
  explicit GlobalPose(const PoseSet& poses);

  /// `shape` (#V by 3, placed anywhere) moved rigidly so that it is turned like pose 0 by
  /// exp(sum_k w_k log R_k) and centred on sum_k w_k c_k, for the K `weights`. Vertices that no face
  /// uses carry no shape: they take the linear blend of their positions.
  Eigen::MatrixX3d place(const Eigen::Ref<const Eigen::MatrixX3d>& shape, const Eigen::VectorXd& weights) const;

  /// Rows of the vertices that faces use.
  const std::vector<int>& used_vertices() const { return used_; }

 private:
  const PoseSet& poses_;
  std::vector<int> used_;
  Eigen::MatrixX3d first_;  // pose 0, used vertices
  std::vector<Eigen::RowVector3d> barycentres_;
  std::vector<Eigen::Vector3d> orientations_;
};

}  // namespace posekit::interpolation
