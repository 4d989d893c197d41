#include <posekit/error.hpp>
#include <posekit/rigid_motion.hpp>

#include <string>

namespace posekit {

Eigen::MatrixX3d RigidTransform::apply(const Eigen::Ref<const Eigen::MatrixX3d>& points) const {
  return (points * rotation.transpose()).rowwise() + translation;
}

RigidTransform RigidTransform::after(const RigidTransform& first) const {
  RigidTransform result;
  result.rotation = rotation * first.rotation;
  result.translation = first.translation * rotation.transpose() + translation;
  return result;
}

RigidTransform RigidTransform::inverse() const {
  RigidTransform result;
  result.rotation = rotation.transpose();
  result.translation = -translation * rotation;
  return result;
}

RigidTransform best_rigid_transform(const Eigen::Ref<const Eigen::MatrixX3d>& source,
                                    const Eigen::Ref<const Eigen::MatrixX3d>& target) {
  if (source.rows() != target.rows()) {
    throw ArgumentError("best_rigid_transform: source has " + std::to_string(source.rows()) + " points but target has " +
                        std::to_string(target.rows()));
  }
  if (source.rows() == 0) throw ArgumentError("best_rigid_transform: no points");
  const Eigen::RowVector3d source_mean = source.colwise().mean();
  const Eigen::RowVector3d target_mean = target.colwise().mean();
  // Cross-covariance target^T source of the centred sets; its nearest rotation is the best one.
  const Eigen::Matrix3d covariance =
      (target.rowwise() - target_mean).transpose() * (source.rowwise() - source_mean);
  RigidTransform result;
  result.rotation = nearest_rotation(covariance);
  result.translation = target_mean - source_mean * result.rotation.transpose();
  return result;
}

std::vector<RigidTransform> register_simultaneously(const std::vector<Eigen::MatrixX3d>& copies, int iterations) {
  if (copies.empty()) throw ArgumentError("register_simultaneously: no copies");
  for (const Eigen::MatrixX3d& copy : copies) {
    if (copy.rows() != copies.front().rows()) {
      throw ArgumentError("register_simultaneously: copies of " + std::to_string(copies.front().rows()) + " and " +
                          std::to_string(copy.rows()) + " points");
    }
  }
  if (copies.front().rows() == 0) throw ArgumentError("register_simultaneously: no points");
  const size_t count = copies.size();
  std::vector<RigidTransform> transforms(count);
  for (size_t k = 1; k < count; ++k) transforms[k] = best_rigid_transform(copies[k], copies[0]);
  for (int iteration = 0; iteration < iterations && count > 2; ++iteration) {
    Eigen::MatrixX3d mean = Eigen::MatrixX3d::Zero(copies[0].rows(), 3);
    for (size_t k = 0; k < count; ++k) mean += transforms[k].apply(copies[k]);
    mean /= static_cast<double>(count);
    std::vector<RigidTransform> next(count);
    for (size_t k = 0; k < count; ++k) next[k] = best_rigid_transform(copies[k], mean);
    // Back into the frame of the first copy.
    const RigidTransform to_first = next[0].inverse();
    double change = 0.0;
    for (size_t k = 0; k < count; ++k) {
      next[k] = to_first.after(next[k]);
      change = std::max(change, (next[k].rotation - transforms[k].rotation).cwiseAbs().maxCoeff());
    }
    transforms = std::move(next);
    if (change <= 1e-12) break;
  }
  transforms[0] = RigidTransform{};
  return transforms;
}

}  // namespace posekit
