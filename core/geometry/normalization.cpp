#include "geometry/vertex_checks.hpp"

#include <posekit/error.hpp>
#include <posekit/geometry.hpp>

#include <algorithm>
#include <limits>
#include <string>

namespace posekit {

Eigen::MatrixX3d UnitSphereNormalization::apply(const Eigen::Ref<const Eigen::MatrixX3d>& vertices) const {
  return (vertices.rowwise() - center) * scale;
}

Eigen::MatrixX3d UnitSphereNormalization::undo(const Eigen::Ref<const Eigen::MatrixX3d>& normalized) const {
  return (normalized / scale).rowwise() + center;
}

UnitSphereNormalization unit_sphere_normalization(const Eigen::Ref<const Eigen::MatrixX3d>& vertices) {
  return shared_unit_sphere_normalization(std::vector<Eigen::Ref<const Eigen::MatrixX3d>>{vertices});
}

UnitSphereNormalization shared_unit_sphere_normalization(
    const std::vector<Eigen::Ref<const Eigen::MatrixX3d>>& poses) {
  const char* function = "unit_sphere_normalization";
  Eigen::RowVector3d lowest = Eigen::RowVector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::RowVector3d highest = -lowest;
  bool any_vertex = false;
  for (const Eigen::Ref<const Eigen::MatrixX3d>& pose : poses) {
    if (pose.rows() == 0) continue;
    detail::check_finite_vertices(pose, function);
    lowest = lowest.cwiseMin(pose.colwise().minCoeff());
    highest = highest.cwiseMax(pose.colwise().maxCoeff());
    any_vertex = true;
  }
  if (!any_vertex) throw ArgumentError(std::string(function) + ": no vertex to normalize");

  UnitSphereNormalization result;
  // The bounding-box center is cheap and deterministic (unlike a minimal enclosing ball) and leaves a
  // radius of at most half the box diagonal; measuring the radius from it keeps every vertex inside.
  result.center = 0.5 * (lowest + highest);
  double radius = 0.0;
  for (const Eigen::Ref<const Eigen::MatrixX3d>& pose : poses) {
    if (pose.rows() == 0) continue;
    radius = std::max(radius, (pose.rowwise() - result.center).rowwise().norm().maxCoeff());
  }
  if (!(radius > 0.0)) throw ArgumentError(std::string(function) + ": all vertices coincide");
  result.scale = 1.0 / radius;
  return result;
}

UnitSphereNormalization shared_unit_sphere_normalization(const PoseSet& poses) {
  std::vector<Eigen::Ref<const Eigen::MatrixX3d>> all;
  all.reserve(static_cast<size_t>(poses.pose_count()));
  for (int i = 0; i < poses.pose_count(); ++i) all.emplace_back(poses.pose(i));
  return shared_unit_sphere_normalization(all);
}

}  // namespace posekit
