// The error measures of interpolated poses: zero on the inputs, exact on a uniform scaling, and the
// counters that catch collapsed and turned-over faces.
#include "interpolation_fixtures.hpp"

#include <posekit/error.hpp>
#include <posekit/interpolate.hpp>
#include <posekit/interpolation_error.hpp>

#include <gtest/gtest.h>

namespace posekit::testing {
namespace {

TEST(InterpolationError, InputPosesHaveNoError) {
  const PoseSet arm = demo_arm({45.0, 90.0});
  const InterpolationErrorMeter meter(arm);
  for (int k = 0; k < 3; ++k) {
    Eigen::VectorXd weights = Eigen::VectorXd::Zero(3);
    weights(k) = 1.0;
    const InterpolationError error = meter.measure(arm.pose(k), weights);
    EXPECT_TRUE(error.finite);
    EXPECT_LT(error.edge_length.max, 1e-12);
    EXPECT_LT(error.dihedral_degrees.max, 1e-9);
    EXPECT_EQ(error.collapsed_faces, 0);
    EXPECT_EQ(error.folded_edges, 0);
    EXPECT_EQ(error.flipped_faces, 0);
  }
}

TEST(InterpolationError, ScalingGivesItsRelativeLengthErrorAndNoAngleError) {
  const PoseSet arm = demo_arm({30.0});
  const InterpolationError error = interpolation_error(1.1 * arm.pose(0), arm, two_pose_weights(0.0));
  EXPECT_NEAR(error.edge_length.max, 0.1, 1e-12);
  EXPECT_NEAR(error.edge_length.p99, 0.1, 1e-12);
  EXPECT_NEAR(error.edge_length.p999, 0.1, 1e-12);
  EXPECT_LT(error.dihedral_degrees.max, 1e-9);
  EXPECT_EQ(error.flipped_faces, 0);
}

TEST(InterpolationError, PercentilesRankTheWorstEdges) {
  // Stretching one vertex moves only its edges: the 99th percentile stays at zero, the maximum does not.
  const PoseSet arm = demo_arm({30.0});
  Eigen::MatrixX3d moved = arm.pose(0);
  moved.row(10) *= 1.01;
  const InterpolationError error = interpolation_error(moved, arm, two_pose_weights(0.0));
  EXPECT_GT(error.edge_length.max, 1e-3);
  EXPECT_EQ(error.edge_length.p99, 0.0);
}

TEST(InterpolationError, VertexErrorsLieWhereTheEdgesChanged) {
  // One vertex moved: it and its neighbours carry the largest relative error of their edges, every
  // other vertex none; on a uniform scaling every vertex carries the scale.
  const PoseSet arm = demo_arm({30.0});
  const InterpolationErrorMeter meter(arm);
  Eigen::MatrixX3d moved = arm.pose(0);
  moved.row(10) *= 1.01;
  const Eigen::VectorXd errors = meter.vertex_edge_length_errors(moved, two_pose_weights(0.0));
  ASSERT_EQ(errors.size(), arm.vertex_count());
  EXPECT_NEAR(errors.maxCoeff(), meter.measure(moved, two_pose_weights(0.0)).edge_length.max, 1e-15);
  EXPECT_GT(errors(10), 1e-3);
  const int touched = static_cast<int>((errors.array() > 0.0).count());
  EXPECT_GE(touched, 4);
  EXPECT_LE(touched, 12);
  const Eigen::VectorXd scaled = meter.vertex_edge_length_errors(1.1 * arm.pose(0), two_pose_weights(0.0));
  EXPECT_NEAR(scaled.minCoeff(), 0.1, 1e-12);
  EXPECT_NEAR(scaled.maxCoeff(), 0.1, 1e-12);
  EXPECT_THROW(meter.vertex_edge_length_errors(moved, Eigen::VectorXd::Ones(3)), ArgumentError);
}

TEST(InterpolationError, CatchesCollapsedAndTurnedOverFaces) {
  const PoseSet arm = demo_arm({30.0});
  // Flattened onto the plane y = 0: faces along the side collapse.
  Eigen::MatrixX3d flat = arm.pose(0);
  flat.col(1).setZero();
  EXPECT_GT(interpolation_error(flat, arm, two_pose_weights(0.0)).collapsed_faces, 100);
  // A vertex slid along the surface past its neighbours turns the faces it crosses over.
  Eigen::MatrixX3d slid = arm.pose(0);
  int v = 0;
  for (int i = 0; i < arm.vertex_count(); ++i) {
    if (std::abs(arm.pose(0)(i, 0) - 2.0) < 0.05 && arm.pose(0)(i, 1) > 0.45) v = i;
  }
  slid(v, 0) += 0.25;  // about two and a half edge lengths along the tube
  const InterpolationError error = interpolation_error(slid, arm, two_pose_weights(0.0));
  EXPECT_GT(error.folded_edges, 0);
  EXPECT_GT(error.flipped_faces, 0);
  EXPECT_LT(error.flipped_faces, 20);
}

TEST(InterpolationError, NonFiniteResultIsReported) {
  const PoseSet arm = demo_arm({30.0});
  Eigen::MatrixX3d broken = arm.pose(0);
  broken(3, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(interpolation_error(broken, arm, two_pose_weights(0.5)).finite);
}

TEST(InterpolationError, RejectsMismatchedSizes) {
  const PoseSet arm = demo_arm({30.0});
  const InterpolationErrorMeter meter(arm);
  EXPECT_THROW(meter.measure(arm.pose(0), Eigen::VectorXd::Ones(3)), ArgumentError);
  EXPECT_THROW(meter.measure(arm.pose(0).topRows(10), two_pose_weights(0.5)), ArgumentError);
}

}  // namespace
}  // namespace posekit::testing
