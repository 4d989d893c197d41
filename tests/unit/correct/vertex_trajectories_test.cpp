#include <gtest/gtest.h>

#include <cmath>

#include <posekit/error.hpp>

#include "correct/vertex_trajectories.hpp"

namespace posekit::detail {
namespace {

// One vertex moving along x(t) = t^2 sampled at 5 frames: Hermite with finite-difference tangents
// passes through every frame, has a continuous velocity, and a near-exact derivative inside.
std::vector<Eigen::MatrixX3d> parabola_frames(int count) {
  std::vector<Eigen::MatrixX3d> frames;
  for (int i = 0; i < count; ++i) {
    const double t = static_cast<double>(i) / (count - 1);
    Eigen::MatrixX3d frame(1, 3);
    frame << t * t, 2.0 * t, 1.0;
    frames.push_back(frame);
  }
  return frames;
}

TEST(VertexTrajectories, InterpolatesKeyFrames) {
  const VertexTrajectories trajectories(parabola_frames(5));
  for (int i = 0; i < 5; ++i) {
    const double t = i / 4.0;
    EXPECT_NEAR(trajectories.position(0, t).x(), t * t, 1e-14);
    EXPECT_NEAR(trajectories.position(0, t).y(), 2.0 * t, 1e-14);
  }
}

TEST(VertexTrajectories, VelocityMatchesLinearMotionExactly) {
  const VertexTrajectories trajectories(parabola_frames(5));
  for (double t : {0.0, 0.1, 0.33, 0.5, 0.9, 1.0}) {
    EXPECT_NEAR(trajectories.velocity(0, t).y(), 2.0, 1e-12) << t;
    EXPECT_NEAR(trajectories.velocity(0, t).z(), 0.0, 1e-12) << t;
  }
}

TEST(VertexTrajectories, VelocityIsContinuousAtKeyFrames) {
  const VertexTrajectories trajectories(parabola_frames(5));
  for (int i = 1; i < 4; ++i) {
    const double t = i / 4.0;
    EXPECT_NEAR(trajectories.velocity(0, t - 1e-9).x(), trajectories.velocity(0, t + 1e-9).x(), 1e-6);
    // Central differences of t^2 are exact at interior frames.
    EXPECT_NEAR(trajectories.velocity(0, t).x(), 2.0 * t, 1e-12);
  }
}

TEST(VertexTrajectories, VelocityIsTheDerivativeOfPosition) {
  const VertexTrajectories trajectories(parabola_frames(6));
  for (double t : {0.05, 0.31, 0.62, 0.97}) {
    const double h = 1e-6;
    const double numeric = (trajectories.position(0, t + h).x() - trajectories.position(0, t - h).x()) / (2 * h);
    EXPECT_NEAR(trajectories.velocity(0, t).x(), numeric, 1e-7) << t;
  }
}

TEST(VertexTrajectories, PoseHoldsEveryVertexAtOneTime) {
  std::vector<Eigen::MatrixX3d> frames;
  for (int i = 0; i < 4; ++i) {
    const double t = i / 3.0;
    Eigen::MatrixX3d frame(3, 3);
    frame << t, t * t, 1.0, -t, 2.0, t * t * t, 0.5, std::sin(t), t;
    frames.push_back(frame);
  }
  const VertexTrajectories trajectories(frames);
  for (double t : {0.0, 0.2, 1.0 / 3.0, 0.5, 0.95, 1.0}) {
    const Eigen::MatrixX3d pose = trajectories.pose(t);
    ASSERT_EQ(pose.rows(), 3);
    for (int v = 0; v < 3; ++v) {
      EXPECT_LT((pose.row(v).transpose() - trajectories.position(v, t)).norm(), 1e-15) << v << " at " << t;
    }
  }
}

TEST(SampleConstraints, OneRowPerConstrainedVertexAndTime) {
  std::vector<Eigen::MatrixX3d> frames(3, Eigen::MatrixX3d::Zero(4, 3));
  frames[1].col(0).setConstant(1.0);
  frames[2].col(0).setConstant(2.0);
  const VertexTrajectories trajectories(frames);
  const SpaceTimeConstraints constraints = sample_constraints(trajectories, {1, 0, 1, 1}, 13);
  ASSERT_EQ(constraints.positions.rows(), 3 * 13);
  EXPECT_DOUBLE_EQ(constraints.positions(0, 3), 0.0);
  EXPECT_DOUBLE_EQ(constraints.positions(3 * 13 - 1, 3), 1.0);
  EXPECT_NEAR(constraints.velocities(5, 0), 2.0, 1e-12);
  EXPECT_THROW(sample_constraints(trajectories, {1, 1, 1, 1}, 1), ArgumentError);
}

TEST(SampleConstraints, EachTimeItsOwnVertices) {
  std::vector<Eigen::MatrixX3d> frames(3, Eigen::MatrixX3d::Zero(4, 3));
  frames[2].col(1).setConstant(2.0);
  const VertexTrajectories trajectories(frames);
  // Vertex 1 is constrained at the first time only, vertex 3 at the last only.
  const std::vector<std::vector<char>> constrained_at{{1, 1, 1, 0}, {1, 0, 1, 0}, {1, 0, 1, 1}};
  const SpaceTimeConstraints constraints = sample_constraints(trajectories, constrained_at);
  ASSERT_EQ(constraints.positions.rows(), 3 + 2 + 3);
  EXPECT_EQ(constraints.row_vertices, (std::vector<int>{0, 1, 2, 0, 2, 0, 2, 3}));
  EXPECT_EQ(constraints.vertices, (std::vector<int>{0, 2, 3}));
  EXPECT_DOUBLE_EQ(constraints.positions(3, 3), 0.5);
  EXPECT_DOUBLE_EQ(constraints.positions(7, 1), 2.0);
  EXPECT_THROW(sample_constraints(trajectories, {{1, 1, 1, 1}}), ArgumentError);
  EXPECT_THROW(sample_constraints(trajectories, {{1, 1, 1}, {1, 1, 1}}), ArgumentError);
}

TEST(VertexTrajectories, NeedsTwoFrames) {
  EXPECT_THROW(VertexTrajectories(parabola_frames(1)), ArgumentError);
}

}  // namespace
}  // namespace posekit::detail
