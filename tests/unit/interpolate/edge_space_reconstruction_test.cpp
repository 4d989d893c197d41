// The edge-space fit: exact on realizable targets, and Gauss-Newton lowers the energy otherwise.
#include "interpolate/edge_space_reconstruction.hpp"
#include "interpolation_fixtures.hpp"

#include <posekit/edge_space.hpp>
#include <posekit/interpolate.hpp>
#include <posekit/rigid_motion.hpp>

#include <gtest/gtest.h>

#include <numeric>

namespace posekit::testing {
namespace {

class WholeArmReconstruction : public ::testing::Test {
 protected:
  void SetUp() override {
    arm_ = demo_arm({70.0}, 16);
    const EdgeMap edges = edge_map(arm_.faces());
    const AdjacencyLists incident = edge_faces(edges);
    coordinates_ = edge_space_coordinates(arm_, edges, incident);
    std::vector<int> faces(static_cast<size_t>(arm_.faces().rows()));
    std::iota(faces.begin(), faces.end(), 0);
    reconstruction_ = std::make_unique<interpolation::EdgeSpaceReconstruction>(
        interpolation::make_edge_space_patch(faces, arm_.faces(), arm_.vertex_count(), edges, incident, coordinates_.hinge),
        arm_.pose(0), interpolation::pose_deformations(arm_));
  }
  void targets(const Eigen::VectorXd& weights, Eigen::VectorXd& lengths, Eigen::VectorXd& angles) const {
    const interpolation::EdgeSpacePatch& patch = reconstruction_->patch();
    const Eigen::VectorXd all_lengths = coordinates_.combined_lengths(weights);
    const Eigen::VectorXd all_angles = coordinates_.combined_angles(weights);
    lengths.resize(patch.edge_count());
    angles.resize(patch.hinge_count());
    for (int e = 0; e < patch.edge_count(); ++e) lengths(e) = all_lengths(patch.mesh_edges[static_cast<size_t>(e)]);
    for (int h = 0; h < patch.hinge_count(); ++h) angles(h) = all_angles(patch.mesh_hinges[static_cast<size_t>(h)]);
  }
  PoseSet arm_;
  EdgeSpaceCoordinates coordinates_;
  std::unique_ptr<interpolation::EdgeSpaceReconstruction> reconstruction_;
};

TEST_F(WholeArmReconstruction, ReproducesEachPoseUpToARigidMotion) {
  for (int k = 0; k < 2; ++k) {
    const Eigen::VectorXd weights = two_pose_weights(k);
    Eigen::VectorXd lengths, angles;
    targets(weights, lengths, angles);
    interpolation::ReconstructionOptions options;
    interpolation::ReconstructionStats stats;
    const Eigen::MatrixX3d x = reconstruction_->reconstruct(weights, lengths, angles, options, &stats);
    EXPECT_LT(stats.final_energy, 1e-16) << "pose " << k;
    const RigidTransform fit = best_rigid_transform(x, arm_.pose(k));
    EXPECT_LT(largest_distance(fit.apply(x), arm_.pose(k)), 1e-8) << "pose " << k;
  }
}

TEST_F(WholeArmReconstruction, GaussNewtonLowersTheEnergyOfInconsistentTargets) {
  const Eigen::VectorXd weights = two_pose_weights(0.5);
  Eigen::VectorXd lengths, angles;
  targets(weights, lengths, angles);
  Eigen::MatrixX3d x = reconstruction_->gradient_guess(weights);
  ASSERT_TRUE(x.allFinite());
  interpolation::ReconstructionOptions options;
  options.max_iterations = 10;
  const interpolation::ReconstructionStats stats = reconstruction_->refine(x, lengths, angles, options);
  EXPECT_GT(stats.iterations, 0);
  EXPECT_LT(stats.final_energy, 0.5 * stats.initial_energy);
  EXPECT_NEAR(stats.final_energy, reconstruction_->energy(x, lengths, angles, options.bending_weight), 1e-12);
}

}  // namespace
}  // namespace posekit::testing
