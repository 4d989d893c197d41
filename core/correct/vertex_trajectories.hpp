// Per-vertex C1 cubic Hermite trajectories through key frames, and the space-time constraints
// sampled from them.
#pragma once

#include <posekit/device.hpp>

#include <Eigen/Core>
#include <vector>

namespace posekit::detail {

/// Trajectories through key frames at the evenly spaced times 0, 1/K, ..., 1; tangents by finite
/// differences (central inside, one-sided at the ends).
class VertexTrajectories {
 public:
  /// `frames` holds K + 1 >= 2 poses of #V by 3, frame i at time i / K.
  explicit VertexTrajectories(std::vector<Eigen::MatrixX3d> frames);

  int vertex_count() const { return static_cast<int>(frames_.front().rows()); }
  /// The key frames, frame i at time i / K.
  const std::vector<Eigen::MatrixX3d>& frames() const { return frames_; }
  /// Position of `vertex` at time t in [0, 1].
  Eigen::Vector3d position(int vertex, double t) const;
  /// Positions of every vertex at time t in [0, 1] (#V by 3).
  Eigen::MatrixX3d pose(double t) const;
  /// Time derivative of the position of `vertex` at time t in [0, 1].
  Eigen::Vector3d velocity(int vertex, double t) const;

 private:
  // Segment index and local parameter s in [0, 1] of time t.
  void locate(double t, int& segment, double& s) const;
  std::vector<Eigen::MatrixX3d> frames_;
  std::vector<Eigen::MatrixX3d> tangents_;  // dX/dt at each frame
  double spacing_;
};

/// Space-time constraints sampled from trajectories: positions (x, y, z, t) and velocities, time by
/// time, each row belonging to vertex row_vertices[row].
struct SpaceTimeConstraints {
  Points4 positions;
  Eigen::MatrixX3d velocities;
  std::vector<int> row_vertices;  ///< the vertex of each row
  std::vector<int> vertices;      ///< the vertices constrained at the last time (t = 1), ascending
};

/// Constraints at `constrained_at.size()` >= 2 evenly spaced times in [0, 1]: at time i the vertices
/// flagged in constrained_at[i] (one flag per vertex).
SpaceTimeConstraints sample_constraints(const VertexTrajectories& trajectories,
                                        const std::vector<std::vector<char>>& constrained_at);

/// The same vertices, those marked in `constrained`, at each of `time_count` evenly spaced times.
SpaceTimeConstraints sample_constraints(const VertexTrajectories& trajectories,
                                        const std::vector<char>& constrained, int time_count);

}  // namespace posekit::detail
