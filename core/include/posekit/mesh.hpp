// Triangle meshes and pose sets: one face list shared by many vertex sets.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace posekit {

/// A triangle mesh: #V by 3 vertex positions and #F by 3 zero-based vertex indices.
struct Mesh {
  Eigen::MatrixX3d vertices;
  Eigen::MatrixX3i faces;
};

/// Several poses of one shape: a single face list and one #V by 3 vertex matrix per pose.
/// Every pose has the same number of vertices, in the same order.
class PoseSet {
 public:
  PoseSet() = default;
  /// Starts a pose set with `faces` as the shared connectivity and no poses.
  explicit PoseSet(Eigen::MatrixX3i faces) : faces_(std::move(faces)) {}

  /// Appends a pose; throws ArgumentError if its vertex count differs from the others'.
  void add_pose(Eigen::MatrixX3d vertices, std::string name = {});

  const Eigen::MatrixX3i& faces() const { return faces_; }
  int pose_count() const { return static_cast<int>(poses_.size()); }
  /// Number of vertices of every pose (0 when the set has no pose yet).
  int vertex_count() const { return poses_.empty() ? 0 : static_cast<int>(poses_.front().rows()); }
  const Eigen::MatrixX3d& pose(int index) const { return poses_.at(static_cast<size_t>(index)); }
  /// The name given to the pose (usually its file name), or "" if none.
  const std::string& pose_name(int index) const { return names_.at(static_cast<size_t>(index)); }
  /// The pose as a standalone mesh (copies the face list).
  Mesh mesh(int index) const { return Mesh{pose(index), faces_}; }

 private:
  Eigen::MatrixX3i faces_;
  std::vector<Eigen::MatrixX3d> poses_;
  std::vector<std::string> names_;
};

}  // namespace posekit
