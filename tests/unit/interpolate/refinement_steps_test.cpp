// The fixed-pattern block matrix and the two refinements of the mixed-space projection: given a
// pose's own lengths and angles, the joint refinement and the local/global passes leave it alone;
// given another pose's, they move towards it.
#include "interpolate/articulated_refinement.hpp"
#include "interpolate/block_sparse_matrix.hpp"
#include "interpolate/edge_space_patch.hpp"
#include "interpolate/joint_layout.hpp"
#include "interpolate/local_global_projection.hpp"
#include "interpolation_fixtures.hpp"
#include "test_data.hpp"

#include <posekit/edge_space.hpp>
#include <posekit/interpolate.hpp>
#include <posekit/interpolation_error.hpp>

#include <gtest/gtest.h>

namespace posekit::testing {
namespace {

TEST(BlockSparseMatrix3, AddsBlocksWhereTripletsWouldPutThem) {
  interpolation::BlockSparseMatrix3 matrix(4, {{0, 1}, {2, 3}, {1, 3}});
  Eigen::Matrix3d block;
  block << 1, 2, 3, 4, 5, 6, 7, 8, 9;
  matrix.add(matrix.slot(1, 3), block);
  matrix.add(matrix.slot(3, 1), block.transpose());
  matrix.add(matrix.diagonal_slot(2), 2.0 * block);
  matrix.add_diagonal(0, 5.0);
  Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(12, 12);
  expected.block(3, 9, 3, 3) = block;
  expected.block(9, 3, 3, 3) = block.transpose();
  expected.block(6, 6, 3, 3) = 2.0 * block;
  expected.block(0, 0, 3, 3) = 5.0 * Eigen::Matrix3d::Identity();
  EXPECT_TRUE(matrices_near(Eigen::MatrixXd(matrix.matrix()), expected, 0.0, 0.0));
  EXPECT_NEAR(matrix.mean_diagonal(), (15.0 + 2.0 * 15.0) / 12.0, 1e-12);
  matrix.set_zero();
  EXPECT_EQ(Eigen::MatrixXd(matrix.matrix()).cwiseAbs().maxCoeff(), 0.0);
}

class RefinementSteps : public ::testing::Test {
 protected:
  void SetUp() override {
    arm_ = demo_arm({50.0}, 16);
    edges_ = edge_map(arm_.faces());
    incident_ = edge_faces(edges_);
    coordinates_ = edge_space_coordinates(arm_, edges_, incident_);
    parts_.resize(arm_.faces().rows());
    for (int f = 0; f < arm_.faces().rows(); ++f) parts_(f) = arm_.pose(0)(arm_.faces()(f, 0), 0) < 2.0 ? 0 : 1;
    layout_ = interpolation::build_joint_layout(arm_.faces(), parts_, edges_, incident_,
                                                vertex_neighbours(arm_.faces(), arm_.vertex_count()), 3);
  }
  PoseSet arm_;
  EdgeMap edges_;
  AdjacencyLists incident_;
  EdgeSpaceCoordinates coordinates_;
  Eigen::VectorXi parts_;
  interpolation::JointLayout layout_;
};

TEST_F(RefinementSteps, LocalGlobalPassesKeepAPoseWithItsOwnTargets) {
  const interpolation::LocalGlobalProjection projection(arm_.faces(), arm_.vertex_count(), edges_, incident_,
                                                        coordinates_.hinge, coordinates_.lengths.col(0), 0.5);
  Eigen::MatrixX3d x = arm_.pose(1);
  projection.project(x, coordinates_.lengths.col(1), coordinates_.angles.col(1), 5);
  EXPECT_LT(largest_distance(x, arm_.pose(1)), 1e-6);  // round-off of the solves, on an arm 5 units long
}

TEST_F(RefinementSteps, LocalGlobalPassesLowerTheErrors) {
  // Linear vertex interpolation has shortened edges; the passes give them back their lengths.
  const Eigen::VectorXd weights = two_pose_weights(0.5);
  const interpolation::LocalGlobalProjection projection(arm_.faces(), arm_.vertex_count(), edges_, incident_,
                                                        coordinates_.hinge, coordinates_.lengths.col(0), 0.5);
  const InterpolationErrorMeter meter(arm_);
  Eigen::MatrixX3d x = 0.5 * (arm_.pose(0) + arm_.pose(1));
  const InterpolationError before = meter.measure(x, weights);
  projection.project(x, coordinates_.combined_lengths(weights), coordinates_.combined_angles(weights), 5);
  const InterpolationError after = meter.measure(x, weights);
  EXPECT_LT(after.edge_length.p99, 0.5 * before.edge_length.p99);
  EXPECT_LT(after.dihedral_degrees.p99, before.dihedral_degrees.p99);
}

TEST_F(RefinementSteps, JointRefinementKeepsAPoseWithItsOwnTargets) {
  std::vector<interpolation::EdgeSpacePatch> patches;
  for (const auto& joint : layout_.joints) {
    patches.push_back(interpolation::make_edge_space_patch(joint.faces, arm_.faces(), arm_.vertex_count(), edges_,
                                                           incident_, coordinates_.hinge));
  }
  std::vector<const interpolation::EdgeSpacePatch*> pointers;
  for (const auto& patch : patches) pointers.push_back(&patch);
  interpolation::ArticulatedRefinement refinement(pointers, layout_.rigid_pieces, arm_.vertex_count());
  Eigen::MatrixX3d x = arm_.pose(1);
  const interpolation::ArticulatedStats stats =
      refinement.refine(x, coordinates_.lengths.col(1), coordinates_.angles.col(1), 0.1, 3, 1e-4);
  EXPECT_LT(stats.initial_energy, 1e-20);
  EXPECT_LT(largest_distance(x, arm_.pose(1)), 1e-12);
}

TEST_F(RefinementSteps, JointRefinementMovesRigidPiecesRigidly) {
  // Start from pose 0 with pose 1's targets: the joint must bend and the lower bone follow it rigidly.
  std::vector<interpolation::EdgeSpacePatch> patches;
  for (const auto& joint : layout_.joints) {
    patches.push_back(interpolation::make_edge_space_patch(joint.faces, arm_.faces(), arm_.vertex_count(), edges_,
                                                           incident_, coordinates_.hinge));
  }
  std::vector<const interpolation::EdgeSpacePatch*> pointers;
  for (const auto& patch : patches) pointers.push_back(&patch);
  interpolation::ArticulatedRefinement refinement(pointers, layout_.rigid_pieces, arm_.vertex_count());
  Eigen::MatrixX3d x = arm_.pose(0);
  const interpolation::ArticulatedStats stats =
      refinement.refine(x, coordinates_.lengths.col(1), coordinates_.angles.col(1), 0.1, 10, 1e-8);
  EXPECT_LT(stats.final_energy, 0.01 * stats.initial_energy);
  EXPECT_NEAR(arm_bend_degrees(arm_, x), 50.0, 3.0);
  for (const auto& piece : layout_.rigid_pieces) {
    // Each piece moved as a whole: its edges keep their pose-0 lengths.
    for (size_t i = 1; i < piece.vertices.size(); i += 7) {
      const int a = piece.vertices[i - 1];
      const int b = piece.vertices[i];
      EXPECT_NEAR((x.row(a) - x.row(b)).norm(), (arm_.pose(0).row(a) - arm_.pose(0).row(b)).norm(), 1e-9);
    }
  }
}

}  // namespace
}  // namespace posekit::testing
