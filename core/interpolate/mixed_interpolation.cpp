#include "interpolate/mixed_interpolation.hpp"

#include "interpolate/pose_deformations.hpp"

#include <posekit/rigid_motion.hpp>

#include <tbb/parallel_for.h>

#include <chrono>

namespace posekit::interpolation {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

Eigen::MatrixX3d rows_of(const Eigen::Ref<const Eigen::MatrixX3d>& x, const std::vector<int>& rows) {
  Eigen::MatrixX3d result(static_cast<Eigen::Index>(rows.size()), 3);
  for (size_t i = 0; i < rows.size(); ++i) result.row(static_cast<Eigen::Index>(i)) = x.row(rows[i]);
  return result;
}

}  // namespace

MixedInterpolation::MixedInterpolation(const PoseSet& poses, const EdgeMap& edges, const AdjacencyLists& incident_faces,
                                       const AdjacencyLists& neighbours, const EdgeSpaceCoordinates& coordinates,
                                       const Eigen::VectorXi& face_parts, const InterpolationOptions& options,
                                       PrecomputationTimes& times)
    : poses_(poses), coordinates_(coordinates), options_(options) {
  auto start = Clock::now();
  layout_ = build_joint_layout(poses.faces(), face_parts, edges, incident_faces, neighbours, options.joint_width);
  times.layout += seconds_since(start);

  // Every rigid piece registered across all poses once: only the blend depends on the weights.
  start = Clock::now();
  const int pose_count = poses.pose_count();
  aligned_pieces_.resize(layout_.rigid_pieces.size());
  tbb::parallel_for(size_t{0}, layout_.rigid_pieces.size(), [&](size_t p) {
    std::vector<Eigen::MatrixX3d> copies;
    for (int k = 0; k < pose_count; ++k) copies.push_back(rows_of(poses.pose(k), layout_.rigid_pieces[p].vertices));
    const std::vector<RigidTransform> motions = register_simultaneously(copies);
    for (int k = 0; k < pose_count; ++k) {
      copies[static_cast<size_t>(k)] = motions[static_cast<size_t>(k)].apply(copies[static_cast<size_t>(k)]);
    }
    aligned_pieces_[p] = std::move(copies);
  });
  times.registration += seconds_since(start);

  start = Clock::now();
  const PoseDeformations deformations = pose_deformations(poses);
  joints_.resize(layout_.joints.size());
  tbb::parallel_for(size_t{0}, layout_.joints.size(), [&](size_t j) {
    joints_[j] = std::make_unique<EdgeSpaceReconstruction>(
        make_edge_space_patch(layout_.joints[j].faces, poses.faces(), poses.vertex_count(), edges, incident_faces,
                              coordinates.hinge),
        poses.pose(0), deformations);
  });
  std::vector<char> in_rigid(static_cast<size_t>(poses.vertex_count()), 0);
  for (const MeshComponent& piece : layout_.rigid_pieces) {
    for (const int v : piece.vertices) in_rigid[static_cast<size_t>(v)] = 1;
  }
  std::vector<MeshComponent> components = layout_.rigid_pieces;
  components.insert(components.end(), layout_.joints.begin(), layout_.joints.end());
  for (const MeshComponent& component : components) component_vertices_.push_back(component.vertices);
  alignment_ = std::make_unique<ComponentAlignment>(component_vertices_, poses.vertex_count());
  stitching_ = std::make_unique<EdgeStitching>(edges, components, in_rigid, poses.vertex_count());
  std::vector<const EdgeSpacePatch*> patches;
  for (const auto& joint : joints_) patches.push_back(&joint->patch());
  refinement_ = std::make_unique<ArticulatedRefinement>(patches, layout_.rigid_pieces, poses.vertex_count());
  projection_ = std::make_unique<LocalGlobalProjection>(poses.faces(), poses.vertex_count(), edges, incident_faces,
                                                        coordinates.hinge, coordinates.lengths.col(0),
                                                        options.projection_hinge_weight);
  global_pose_ = std::make_unique<GlobalPose>(poses);
  times.factorization += seconds_since(start);

  InterpolationLayout& summary = layout_summary_;
  summary.parts = face_parts.size() > 0 ? face_parts.maxCoeff() + 1 : 0;
  summary.rigid_pieces = static_cast<int>(layout_.rigid_pieces.size());
  summary.joints = static_cast<int>(layout_.joints.size());
  summary.joint_faces = layout_.joint_face_count;
  for (const auto& joint : joints_) summary.joint_edges += joint->patch().edge_count();
  for (const MeshComponent& piece : layout_.rigid_pieces) summary.rigid_vertices += static_cast<int>(piece.vertices.size());
  summary.mixed_dimension = 2LL * summary.joint_edges + 3LL * summary.rigid_vertices + 6;
  summary.edge_dimension = 2LL * coordinates.edge_count();
}

Eigen::MatrixX3d MixedInterpolation::interpolate(const Eigen::VectorXd& weights, InterpolationStepReport& report) {
  const auto start = Clock::now();
  auto stage = Clock::now();
  const int pose_count = poses_.pose_count();
  const size_t piece_count = aligned_pieces_.size();
  const size_t joint_count = joints_.size();
  std::vector<Eigen::MatrixX3d> shapes(piece_count + joint_count);
  tbb::parallel_for(size_t{0}, piece_count, [&](size_t p) {
    Eigen::MatrixX3d blend = weights(0) * aligned_pieces_[p][0];
    for (int k = 1; k < pose_count; ++k) blend += weights(k) * aligned_pieces_[p][static_cast<size_t>(k)];
    shapes[p] = std::move(blend);
  });
  const Eigen::VectorXd lengths = coordinates_.combined_positive_lengths(weights);
  const Eigen::VectorXd angles = coordinates_.combined_angles(weights);
  report.seconds.blend = seconds_since(stage);

  stage = Clock::now();
  std::vector<int> iterations(joint_count, 0);
  ReconstructionOptions reconstruction;
  reconstruction.max_iterations = options_.joint_iterations;
  reconstruction.bending_weight = options_.bending_weight;
  tbb::parallel_for(size_t{0}, joint_count, [&](size_t j) {
    EdgeSpaceReconstruction& joint = *joints_[j];
    const EdgeSpacePatch& patch = joint.patch();
    Eigen::VectorXd joint_lengths(patch.edge_count());
    Eigen::VectorXd joint_angles(patch.hinge_count());
    for (int e = 0; e < patch.edge_count(); ++e) joint_lengths(e) = lengths(patch.mesh_edges[static_cast<size_t>(e)]);
    for (int h = 0; h < patch.hinge_count(); ++h) joint_angles(h) = angles(patch.mesh_hinges[static_cast<size_t>(h)]);
    ReconstructionStats stats;
    shapes[piece_count + j] = joint.reconstruct(weights, joint_lengths, joint_angles, reconstruction, &stats);
    iterations[j] = stats.iterations;
  }, tbb::simple_partitioner());
  report.gauss_newton_iterations = 0;
  for (const int count : iterations) report.gauss_newton_iterations += count;
  report.seconds.joints = seconds_since(stage);

  stage = Clock::now();
  const std::vector<RigidTransform> motions = alignment_->align(shapes, options_.alignment_sweeps);
  for (size_t c = 0; c < shapes.size(); ++c) shapes[c] = motions[c].apply(shapes[c]);
  // Groups of components that share no vertex with the rest (separate pieces of the mesh) go where the
  // vertex blend puts them; the whole shape is placed again globally below.
  const std::vector<std::vector<int>>& clusters = alignment_->clusters();
  if (clusters.size() > 1) {
    for (const std::vector<int>& cluster : clusters) {
      int rows = 0;
      for (const int c : cluster) rows += static_cast<int>(shapes[static_cast<size_t>(c)].rows());
      Eigen::MatrixX3d source(rows, 3);
      Eigen::MatrixX3d target = Eigen::MatrixX3d::Zero(rows, 3);
      int row = 0;
      for (const int c : cluster) {
        const std::vector<int>& vertices = component_vertices_[static_cast<size_t>(c)];
        for (size_t i = 0; i < vertices.size(); ++i, ++row) {
          source.row(row) = shapes[static_cast<size_t>(c)].row(static_cast<Eigen::Index>(i));
          for (int k = 0; k < pose_count; ++k) target.row(row) += weights(k) * poses_.pose(k).row(vertices[i]);
        }
      }
      const RigidTransform motion = best_rigid_transform(source, target);
      for (const int c : cluster) shapes[static_cast<size_t>(c)] = motion.apply(shapes[static_cast<size_t>(c)]);
    }
  }
  report.seconds.alignment = seconds_since(stage);

  stage = Clock::now();
  Eigen::MatrixX3d stitched = stitching_->stitch(shapes, lengths);
  report.seconds.stitching = seconds_since(stage);

  stage = Clock::now();
  const ArticulatedStats refined = refinement_->refine(stitched, lengths, angles, options_.bending_weight,
                                                       options_.refinement_iterations, 1e-4);
  report.gauss_newton_iterations += refined.iterations;
  report.seconds.refinement = seconds_since(stage);

  stage = Clock::now();
  projection_->project(stitched, lengths, angles, options_.projection_passes);
  report.seconds.projection = seconds_since(stage);

  stage = Clock::now();
  Eigen::MatrixX3d result = global_pose_->place(stitched, weights);
  report.seconds.placement = seconds_since(stage);
  report.seconds.total = seconds_since(start);
  return result;
}

}  // namespace posekit::interpolation
