#include "interpolate/global_pose.hpp"

#include <posekit/rigid_motion.hpp>

#include <Eigen/Geometry>

namespace posekit::interpolation {
namespace {

Eigen::MatrixX3d rows_of(const Eigen::Ref<const Eigen::MatrixX3d>& x, const std::vector<int>& rows) {
  Eigen::MatrixX3d result(static_cast<Eigen::Index>(rows.size()), 3);
  for (size_t i = 0; i < rows.size(); ++i) result.row(static_cast<Eigen::Index>(i)) = x.row(rows[i]);
  return result;
}

}  // namespace

GlobalPose::GlobalPose(const PoseSet& poses) : poses_(poses) {
  std::vector<char> used(static_cast<size_t>(poses.vertex_count()), 0);
  const Eigen::MatrixX3i& faces = poses.faces();
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    for (int corner = 0; corner < 3; ++corner) used[static_cast<size_t>(faces(f, corner))] = 1;
  }
  for (int v = 0; v < poses.vertex_count(); ++v) {
    if (used[static_cast<size_t>(v)]) used_.push_back(v);
  }
  first_ = rows_of(poses.pose(0), used_);
  for (int k = 0; k < poses.pose_count(); ++k) {
    const Eigen::MatrixX3d pose = rows_of(poses.pose(k), used_);
    barycentres_.push_back(pose.colwise().mean());
    const Eigen::AngleAxisd turn(best_rigid_transform(first_, pose).rotation);
    orientations_.push_back(turn.angle() * turn.axis());
  }
}

Eigen::MatrixX3d GlobalPose::place(const Eigen::Ref<const Eigen::MatrixX3d>& shape,
                                   const Eigen::VectorXd& weights) const {
  Eigen::RowVector3d centre = Eigen::RowVector3d::Zero();
  Eigen::Vector3d log = Eigen::Vector3d::Zero();
  Eigen::MatrixX3d result = Eigen::MatrixX3d::Zero(shape.rows(), 3);
  for (Eigen::Index k = 0; k < weights.size(); ++k) {
    centre += weights(k) * barycentres_[static_cast<size_t>(k)];
    log += weights(k) * orientations_[static_cast<size_t>(k)];
    result += weights(k) * poses_.pose(static_cast<int>(k));
  }
  const double angle = log.norm();
  const Eigen::Matrix3d turn =
      angle > 0.0 ? Eigen::AngleAxisd(angle, log / angle).toRotationMatrix() : Eigen::Matrix3d::Identity();
  // Bring the shape to pose 0's orientation first, then turn it.
  const Eigen::MatrixX3d used_shape = rows_of(shape, used_);
  const Eigen::Matrix3d to_first = best_rigid_transform(used_shape, first_).rotation;
  const Eigen::RowVector3d own_centre = used_shape.colwise().mean();
  const Eigen::Matrix3d rotation = turn * to_first;
  for (const int v : used_) result.row(v) = (shape.row(v) - own_centre) * rotation.transpose() + centre;
  return result;
}

}  // namespace posekit::interpolation
