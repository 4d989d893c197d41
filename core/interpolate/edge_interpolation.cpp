#include "interpolate/edge_interpolation.hpp"

#include <posekit/rigid_motion.hpp>

#include <chrono>
#include <numeric>
#include <vector>

namespace posekit::interpolation {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

}  // namespace

EdgeInterpolation::EdgeInterpolation(const PoseSet& poses, const EdgeMap& edges, const AdjacencyLists& incident_faces,
                                     const EdgeSpaceCoordinates& coordinates, const InterpolationOptions& options,
                                     PrecomputationTimes& times)
    : coordinates_(coordinates), options_(options), vertex_count_(poses.vertex_count()), poses_(poses) {
  const auto start = Clock::now();
  std::vector<int> all_faces(static_cast<size_t>(poses.faces().rows()));
  std::iota(all_faces.begin(), all_faces.end(), 0);
  reconstruction_ = std::make_unique<EdgeSpaceReconstruction>(
      make_edge_space_patch(all_faces, poses.faces(), poses.vertex_count(), edges, incident_faces, coordinates.hinge),
      poses.pose(0), pose_deformations(poses));
  global_pose_ = std::make_unique<GlobalPose>(poses);
  // Pieces of the mesh that share no edge are reconstructed each in a frame of its own.
  const EdgeSpacePatch& patch = reconstruction_->patch();
  std::vector<std::vector<int>> adjacent(static_cast<size_t>(patch.vertex_count()));
  for (int e = 0; e < patch.edge_count(); ++e) {
    adjacent[static_cast<size_t>(patch.edges(e, 0))].push_back(patch.edges(e, 1));
    adjacent[static_cast<size_t>(patch.edges(e, 1))].push_back(patch.edges(e, 0));
  }
  std::vector<char> reached(static_cast<size_t>(patch.vertex_count()), 0);
  for (int first = 0; first < patch.vertex_count(); ++first) {
    if (reached[static_cast<size_t>(first)]) continue;
    reached[static_cast<size_t>(first)] = 1;
    std::vector<int> piece(1, first);
    for (size_t next = 0; next < piece.size(); ++next) {
      for (const int w : adjacent[static_cast<size_t>(piece[next])]) {
        if (reached[static_cast<size_t>(w)]) continue;
        reached[static_cast<size_t>(w)] = 1;
        piece.push_back(w);
      }
    }
    pieces_.push_back(std::move(piece));
  }
  times.factorization += seconds_since(start);
}

Eigen::MatrixX3d EdgeInterpolation::interpolate(const Eigen::VectorXd& weights, InterpolationStepReport& report) {
  const auto start = Clock::now();
  auto stage = Clock::now();
  const EdgeSpacePatch& patch = reconstruction_->patch();
  const Eigen::VectorXd all_lengths = coordinates_.combined_positive_lengths(weights);
  const Eigen::VectorXd all_angles = coordinates_.combined_angles(weights);
  Eigen::VectorXd lengths(patch.edge_count());
  Eigen::VectorXd angles(patch.hinge_count());
  for (int e = 0; e < patch.edge_count(); ++e) lengths(e) = all_lengths(patch.mesh_edges[static_cast<size_t>(e)]);
  for (int h = 0; h < patch.hinge_count(); ++h) angles(h) = all_angles(patch.mesh_hinges[static_cast<size_t>(h)]);
  report.seconds.blend = seconds_since(stage);

  stage = Clock::now();
  ReconstructionOptions reconstruction;
  reconstruction.max_iterations = options_.edge_iterations;
  reconstruction.bending_weight = options_.bending_weight;
  ReconstructionStats stats;
  const Eigen::MatrixX3d local = reconstruction_->reconstruct(weights, lengths, angles, reconstruction, &stats);
  report.gauss_newton_iterations = stats.iterations;
  // The patch numbers only the vertices that faces use; the others are filled in by the placement.
  Eigen::MatrixX3d shape = Eigen::MatrixX3d::Zero(vertex_count_, 3);
  for (int v = 0; v < patch.vertex_count(); ++v) shape.row(patch.vertices[static_cast<size_t>(v)]) = local.row(v);
  if (pieces_.size() > 1) {
    // Each piece where the vertex blend puts it; the whole shape is placed again globally below.
    for (const std::vector<int>& piece : pieces_) {
      Eigen::MatrixX3d source(static_cast<Eigen::Index>(piece.size()), 3);
      Eigen::MatrixX3d target = Eigen::MatrixX3d::Zero(static_cast<Eigen::Index>(piece.size()), 3);
      for (size_t i = 0; i < piece.size(); ++i) {
        const int v = patch.vertices[static_cast<size_t>(piece[i])];
        source.row(static_cast<Eigen::Index>(i)) = shape.row(v);
        for (Eigen::Index k = 0; k < weights.size(); ++k) target.row(static_cast<Eigen::Index>(i)) += weights(k) * poses_.pose(static_cast<int>(k)).row(v);
      }
      const RigidTransform motion = best_rigid_transform(source, target);
      for (const int local_vertex : piece) {
        const int v = patch.vertices[static_cast<size_t>(local_vertex)];
        shape.row(v) = motion.apply_to_point(shape.row(v));
      }
    }
  }
  report.seconds.joints = seconds_since(stage);

  stage = Clock::now();
  Eigen::MatrixX3d result = global_pose_->place(shape, weights);
  report.seconds.placement = seconds_since(stage);
  report.seconds.total = seconds_since(start);
  return result;
}

}  // namespace posekit::interpolation
