// Polar decomposition, best rigid motions, simultaneous registration, per-face deformation gradients
// and rotation logarithms that agree across neighbouring faces.
#include <posekit/demo_shape.hpp>
#include <posekit/error.hpp>
#include <posekit/face_deformation.hpp>
#include <posekit/rigid_motion.hpp>
#include <posekit/topology.hpp>

#include "test_data.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <random>

namespace posekit {
namespace {

Eigen::Matrix3d turn(double angle, const Eigen::Vector3d& axis) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

Eigen::MatrixX3d random_points(int count, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  Eigen::MatrixX3d points(count, 3);
  for (int i = 0; i < count; ++i) points.row(i) << coordinate(random), coordinate(random), coordinate(random);
  return points;
}

TEST(PolarDecomposition, SplitsRotationAndStretch) {
  const Eigen::Matrix3d rotation = turn(1.2, Eigen::Vector3d(1, -2, 0.5));
  Eigen::Matrix3d stretch;
  stretch << 2.0, 0.3, 0.0, 0.3, 1.0, 0.1, 0.0, 0.1, 0.5;
  const PolarDecomposition polar = polar_decomposition(rotation * stretch);
  EXPECT_TRUE(testing::matrices_near(polar.rotation, rotation, 1e-12, 0.0));
  EXPECT_TRUE(testing::matrices_near(polar.stretch, stretch, 1e-12, 0.0));
}

TEST(PolarDecomposition, KeepsAReflectionInTheStretch) {
  const Eigen::Matrix3d mirror = Eigen::Vector3d(1.0, 1.0, -1.0).asDiagonal();
  const PolarDecomposition polar = polar_decomposition(turn(0.4, Eigen::Vector3d::UnitY()) * mirror);
  EXPECT_NEAR(polar.rotation.determinant(), 1.0, 1e-12);
  EXPECT_LT(polar.stretch.determinant(), 0.0);
  EXPECT_NEAR(nearest_rotation(Eigen::Matrix3d::Identity() * 3.0).determinant(), 1.0, 1e-12);
}

TEST(BestRigidTransform, RecoversAKnownMotion) {
  const Eigen::MatrixX3d source = random_points(50, 1);
  RigidTransform motion;
  motion.rotation = turn(2.5, Eigen::Vector3d(0.3, 1.0, -0.2));
  motion.translation << 0.5, -1.0, 2.0;
  const RigidTransform found = best_rigid_transform(source, motion.apply(source));
  EXPECT_TRUE(testing::matrices_near(found.rotation, motion.rotation, 1e-12, 0.0));
  EXPECT_TRUE(testing::matrices_near(found.translation, motion.translation, 1e-12, 0.0));
  EXPECT_TRUE(testing::matrices_near(found.inverse().after(found).rotation, Eigen::Matrix3d::Identity(), 1e-12, 0.0));
  EXPECT_THROW(best_rigid_transform(source, source.topRows(3)), ArgumentError);
  EXPECT_THROW(best_rigid_transform(Eigen::MatrixX3d(0, 3), Eigen::MatrixX3d(0, 3)), ArgumentError);
}

TEST(RegisterSimultaneously, BringsEveryCopyOntoTheFirst) {
  const Eigen::MatrixX3d shape = random_points(40, 2);
  std::vector<Eigen::MatrixX3d> copies{shape};
  for (int k = 1; k < 4; ++k) {
    RigidTransform motion;
    motion.rotation = turn(0.9 * k, Eigen::Vector3d(k, 1.0, -1.0));
    motion.translation << k, 0.0, -k;
    // Slightly different copies, as nearly rigid parts are.
    copies.push_back(motion.apply(shape + 0.001 * random_points(40, 10 + k)));
  }
  const std::vector<RigidTransform> motions = register_simultaneously(copies);
  ASSERT_EQ(motions.size(), 4u);
  EXPECT_TRUE(testing::matrices_near(motions[0].rotation, Eigen::Matrix3d::Identity(), 1e-15, 0.0));
  for (int k = 1; k < 4; ++k) {
    EXPECT_TRUE(testing::matrices_near(motions[k].apply(copies[k]), shape, 0.005, 0.0)) << "copy " << k;
  }
  EXPECT_THROW(register_simultaneously({}), ArgumentError);
  EXPECT_THROW(register_simultaneously({shape, shape.topRows(5)}), ArgumentError);
}

TEST(FaceDeformationGradients, AreTheRotationOfARigidMotion) {
  const PoseSet arm = make_demo_arm(DemoArmOptions{16, 0.5, 4.0, 1.0, {}});
  const Eigen::Matrix3d rotation = turn(1.0, Eigen::Vector3d(1, 1, 0));
  const Eigen::MatrixX3d moved = (arm.pose(0) * rotation.transpose()).rowwise() + Eigen::RowVector3d(3, 0, 0);
  for (const Eigen::Matrix3d& gradient : face_deformation_gradients(arm.pose(0), moved, arm.faces())) {
    ASSERT_TRUE(testing::matrices_near(gradient, rotation, 1e-9, 0.0));
  }
  EXPECT_THROW(face_deformation_gradients(arm.pose(0), moved.topRows(4), arm.faces()), ArgumentError);
}

TEST(ConsistentRotationLogs, FollowATwistPastHalfATurn) {
  // A tube twisted about its axis progressively up to 190 degrees at its end: the principal logarithm
  // jumps by 2 pi where the twist passes 180 degrees; the consistent branch goes on smoothly.
  const PoseSet arm = make_demo_arm(DemoArmOptions{16, 0.5, 4.0, 1.0, {}});
  const Eigen::MatrixX3i& faces = arm.faces();
  std::vector<Eigen::AngleAxisd> rotations;
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    double x = 0.0;
    for (int c = 0; c < 3; ++c) x += arm.pose(0)(faces(f, c), 0) / 3.0;
    const double angle = std::clamp(x / 4.0, 0.0, 1.0) * 190.0 * 3.14159265358979323846 / 180.0;
    // From the matrix, as rotations arrive: the principal angle lies in [0, pi].
    rotations.emplace_back(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitX()).toRotationMatrix());
  }
  const std::vector<Eigen::Vector3d> logs = consistent_rotation_logs(rotations, faces);
  const EdgeMap edges = edge_map(faces);
  const AdjacencyLists incident = edge_faces(edges);
  double largest_jump = 0.0;
  for (int e = 0; e < incident.item_count(); ++e) {
    if (incident.count(e) != 2) continue;
    largest_jump = std::max(largest_jump, (logs[static_cast<size_t>(incident[e][0])] - logs[static_cast<size_t>(incident[e][1])]).norm());
  }
  EXPECT_LT(largest_jump, 0.5);
  for (size_t f = 0; f < logs.size(); ++f) {
    // Each log is a logarithm of its rotation.
    const double angle = logs[f].norm();
    const Eigen::Matrix3d back = angle > 0.0 ? Eigen::AngleAxisd(angle, logs[f] / angle).toRotationMatrix()
                                             : Eigen::Matrix3d::Identity();
    ASSERT_TRUE(testing::matrices_near(back, rotations[f].toRotationMatrix(), 1e-9, 0.0));
  }
}

}  // namespace
}  // namespace posekit
