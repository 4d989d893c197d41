#include "interpolation_fixtures.hpp"

#include "test_data.hpp"

#include <posekit/demo_shape.hpp>
#include <posekit/mesh_io.hpp>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

namespace posekit::testing {

PoseSet demo_arm(const std::vector<double>& bend_angles_degrees, int ring_segments) {
  DemoArmOptions options;
  options.ring_segments = ring_segments;
  options.bend_angles_degrees = bend_angles_degrees;
  return make_demo_arm(options);
}

std::vector<int> arm_vertices_below(const PoseSet& arm, double below) {
  std::vector<int> rows;
  for (int v = 0; v < arm.vertex_count(); ++v) {
    if (arm.pose(0)(v, 0) < below) rows.push_back(v);
  }
  return rows;
}

std::vector<int> arm_vertices_above(const PoseSet& arm, double above) {
  std::vector<int> rows;
  for (int v = 0; v < arm.vertex_count(); ++v) {
    if (arm.pose(0)(v, 0) > above) rows.push_back(v);
  }
  return rows;
}

Eigen::Vector3d principal_axis(const Eigen::MatrixX3d& x, const std::vector<int>& rows, const Eigen::Vector3d& reference) {
  Eigen::MatrixX3d points(static_cast<Eigen::Index>(rows.size()), 3);
  for (size_t i = 0; i < rows.size(); ++i) points.row(static_cast<Eigen::Index>(i)) = x.row(rows[i]);
  const Eigen::MatrixX3d centred = points.rowwise() - points.colwise().mean();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(centred.transpose() * centred);
  Eigen::Vector3d axis = solver.eigenvectors().col(2);
  if (axis.dot(reference) < 0.0) axis = -axis;
  return axis;
}

double arm_bend_degrees(const PoseSet& arm, const Eigen::MatrixX3d& x) {
  // The cylinder runs from x = 0 to x = 4 with the joint at 2: far from the joint the bones are rigid.
  const std::vector<int> upper = arm_vertices_below(arm, 1.0);
  const std::vector<int> lower = arm_vertices_above(arm, 3.0);
  // Both axes oriented from the upper bone towards the lower one.
  Eigen::Vector3d upper_centre = Eigen::Vector3d::Zero();
  Eigen::Vector3d lower_centre = Eigen::Vector3d::Zero();
  for (const int v : upper) upper_centre += x.row(v).transpose() / static_cast<double>(upper.size());
  for (const int v : lower) lower_centre += x.row(v).transpose() / static_cast<double>(lower.size());
  const Eigen::Vector3d outward = lower_centre - upper_centre;
  const Eigen::Vector3d upper_axis = principal_axis(x, upper, outward);
  const Eigen::Vector3d lower_axis = principal_axis(x, lower, outward);
  return std::acos(std::clamp(upper_axis.dot(lower_axis), -1.0, 1.0)) * 180.0 / 3.14159265358979323846;
}

double largest_distance(const Eigen::MatrixX3d& a, const Eigen::MatrixX3d& b) {
  return (a - b).rowwise().norm().maxCoeff();
}

std::optional<PoseSet> shared_poses(const std::vector<std::string>& files) {
  std::vector<std::filesystem::path> paths;
  for (const std::string& file : files) {
    const auto path = shared_pose(file);
    if (!path) return std::nullopt;
    paths.push_back(*path);
  }
  return read_pose_set(paths);
}

}  // namespace posekit::testing
