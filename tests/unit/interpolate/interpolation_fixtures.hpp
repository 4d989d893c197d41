// Pose sets and measurements shared by the interpolation tests.
#pragma once

#include <posekit/mesh.hpp>

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

namespace posekit::testing {

/// The demo arm (32 segments per ring, about 1,400 vertices) in its rest pose and bent by each angle.
PoseSet demo_arm(const std::vector<double>& bend_angles_degrees, int ring_segments = 32);

/// Rows of the rest pose of `arm` with x below `below` (upper bone) or above `above` (lower bone).
std::vector<int> arm_vertices_below(const PoseSet& arm, double below);
std::vector<int> arm_vertices_above(const PoseSet& arm, double above);

/// Unit direction of the principal axis of the rows `rows` of `x`, oriented along `reference`.
Eigen::Vector3d principal_axis(const Eigen::MatrixX3d& x, const std::vector<int>& rows, const Eigen::Vector3d& reference);

/// Angle in degrees between the principal axes of the upper and lower bone of the arm pose `x`.
double arm_bend_degrees(const PoseSet& arm, const Eigen::MatrixX3d& x);

/// Largest distance between corresponding rows of `a` and `b`.
double largest_distance(const Eigen::MatrixX3d& a, const Eigen::MatrixX3d& b);

/// The poses `files` (relative to the shared data folder) read as one pose set, or nullopt when absent.
std::optional<PoseSet> shared_poses(const std::vector<std::string>& files);

}  // namespace posekit::testing
