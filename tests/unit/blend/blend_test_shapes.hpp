// Small shapes for the blend tests: the icosphere (known Laplace-Beltrami spectrum) and the demo arm
// in a few bends, with helpers to pick constraints.
#pragma once

#include <posekit/demo_shape.hpp>
#include <posekit/geometry.hpp>
#include <posekit/mesh.hpp>
#include <posekit/submesh.hpp>

#include "icosphere.hpp"

#include <Eigen/Core>

#include <cmath>
#include <utility>
#include <vector>

namespace posekit::testing {

/// The demo arm (16 segments per ring, 1,000-odd vertices) bent by each angle, the first usually 0.
inline PoseSet small_arm(const std::vector<double>& angles) {
  DemoArmOptions options;
  options.ring_segments = 16;
  std::vector<double> bends;
  for (double a : angles) {
    if (a != 0.0) bends.push_back(a);
  }
  options.bend_angles_degrees = bends;
  const PoseSet generated = make_demo_arm(options);
  PoseSet poses(generated.faces());
  size_t next = 1;
  for (double a : angles) {
    if (a == 0.0) {
      poses.add_pose(generated.pose(0), generated.pose_name(0));
    } else {
      poses.add_pose(generated.pose(static_cast<int>(next)), generated.pose_name(static_cast<int>(next)));
      ++next;
    }
  }
  return poses;
}

/// `count` vertices spread by farthest-point sampling from the vertex farthest from the centroid.
inline std::vector<int> spread_vertices(const Eigen::MatrixX3d& vertices, int count) {
  return farthest_point_samples(vertices, count);
}

/// A partial scan of `pose`: the faces for which keep(face) holds, their vertices renumbered in
/// order; `original` receives the pose vertex of every scan vertex.
template <typename Keep>
Mesh partial_scan(const Eigen::MatrixX3d& pose, const Eigen::MatrixX3i& faces, Keep keep, std::vector<int>& original) {
  std::vector<char> kept(static_cast<size_t>(faces.rows()), 0);
  for (Eigen::Index f = 0; f < faces.rows(); ++f) kept[static_cast<size_t>(f)] = keep(static_cast<int>(f)) ? 1 : 0;
  return submesh(pose, faces, kept, &original);
}

/// The largest vertex distance between two poses, over the square root of the area of `truth`.
inline double max_distortion(const Eigen::MatrixX3d& result, const Eigen::MatrixX3d& truth, const Eigen::MatrixX3i& faces) {
  return (result - truth).rowwise().norm().maxCoeff() / std::sqrt(face_areas(truth, faces).sum());
}

}  // namespace posekit::testing
