#include "correct/vertex_trajectories.hpp"

#include <posekit/error.hpp>

#include <algorithm>
#include <cmath>
#include <utility>

namespace posekit::detail {

VertexTrajectories::VertexTrajectories(std::vector<Eigen::MatrixX3d> frames) : frames_(std::move(frames)) {
  const int count = static_cast<int>(frames_.size());
  if (count < 2) throw ArgumentError("trajectories need at least 2 key frames, got " + std::to_string(count));
  for (const Eigen::MatrixX3d& frame : frames_) {
    if (frame.rows() != frames_.front().rows()) throw ArgumentError("key frames differ in vertex count");
  }
  spacing_ = 1.0 / (count - 1);
  tangents_.resize(static_cast<size_t>(count));
  for (int i = 0; i < count; ++i) {
    const int before = std::max(i - 1, 0);
    const int after = std::min(i + 1, count - 1);
    tangents_[static_cast<size_t>(i)] =
        (frames_[static_cast<size_t>(after)] - frames_[static_cast<size_t>(before)]) / ((after - before) * spacing_);
  }
}

void VertexTrajectories::locate(double t, int& segment, double& s) const {
  const int segments = static_cast<int>(frames_.size()) - 1;
  const double scaled = std::clamp(t, 0.0, 1.0) * segments;
  segment = std::min(static_cast<int>(std::floor(scaled)), segments - 1);
  s = scaled - segment;
}

Eigen::MatrixX3d VertexTrajectories::pose(double t) const {
  int segment = 0;
  double s = 0.0;
  locate(t, segment, s);
  const auto k = static_cast<size_t>(segment);
  const double s2 = s * s;
  const double s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * frames_[k] + ((s3 - 2 * s2 + s) * spacing_) * tangents_[k] +
         (-2 * s3 + 3 * s2) * frames_[k + 1] + ((s3 - s2) * spacing_) * tangents_[k + 1];
}

Eigen::Vector3d VertexTrajectories::position(int vertex, double t) const {
  int segment = 0;
  double s = 0.0;
  locate(t, segment, s);
  const auto k = static_cast<size_t>(segment);
  const double s2 = s * s;
  const double s3 = s2 * s;
  const double h00 = 2 * s3 - 3 * s2 + 1;
  const double h10 = s3 - 2 * s2 + s;
  const double h01 = -2 * s3 + 3 * s2;
  const double h11 = s3 - s2;
  return (h00 * frames_[k].row(vertex) + h10 * spacing_ * tangents_[k].row(vertex) +
          h01 * frames_[k + 1].row(vertex) + h11 * spacing_ * tangents_[k + 1].row(vertex))
      .transpose();
}

Eigen::Vector3d VertexTrajectories::velocity(int vertex, double t) const {
  int segment = 0;
  double s = 0.0;
  locate(t, segment, s);
  const auto k = static_cast<size_t>(segment);
  const double s2 = s * s;
  const double d00 = 6 * s2 - 6 * s;
  const double d10 = 3 * s2 - 4 * s + 1;
  const double d01 = -6 * s2 + 6 * s;
  const double d11 = 3 * s2 - 2 * s;
  return ((d00 * frames_[k].row(vertex) + d01 * frames_[k + 1].row(vertex)) / spacing_ +
          d10 * tangents_[k].row(vertex) + d11 * tangents_[k + 1].row(vertex))
      .transpose();
}

SpaceTimeConstraints sample_constraints(const VertexTrajectories& trajectories,
                                        const std::vector<std::vector<char>>& constrained_at) {
  const auto time_count = static_cast<int>(constrained_at.size());
  if (time_count < 2) throw ArgumentError("constraint times must be at least 2, got " + std::to_string(time_count));
  const int vertex_count = trajectories.vertex_count();
  SpaceTimeConstraints constraints;
  for (const std::vector<char>& flags : constrained_at) {
    if (static_cast<int>(flags.size()) != vertex_count) {
      throw ArgumentError("constraint flags for " + std::to_string(flags.size()) + " vertices, trajectories of " +
                          std::to_string(vertex_count));
    }
    for (int v = 0; v < vertex_count; ++v) {
      if (flags[static_cast<size_t>(v)]) constraints.row_vertices.push_back(v);
    }
  }
  const auto count = static_cast<Eigen::Index>(constraints.row_vertices.size());
  constraints.positions.resize(count, 4);
  constraints.velocities.resize(count, 3);
  Eigen::Index row = 0;
  for (int step = 0; step < time_count; ++step) {
    const double t = static_cast<double>(step) / (time_count - 1);
    for (int v = 0; v < vertex_count; ++v) {
      if (!constrained_at[static_cast<size_t>(step)][static_cast<size_t>(v)]) continue;
      constraints.positions.row(row) << trajectories.position(v, t).transpose(), t;
      constraints.velocities.row(row) = trajectories.velocity(v, t).transpose();
      ++row;
    }
  }
  for (int v = 0; v < vertex_count; ++v) {
    if (constrained_at.back()[static_cast<size_t>(v)]) constraints.vertices.push_back(v);
  }
  return constraints;
}

SpaceTimeConstraints sample_constraints(const VertexTrajectories& trajectories,
                                        const std::vector<char>& constrained, int time_count) {
  if (time_count < 2) throw ArgumentError("constraint times must be at least 2, got " + std::to_string(time_count));
  return sample_constraints(trajectories, std::vector<std::vector<char>>(static_cast<size_t>(time_count), constrained));
}

}  // namespace posekit::detail
