#include <posekit/demo_shape.hpp>
#include <posekit/error.hpp>
#include <posekit/geometry.hpp>
#include <posekit/self_intersections.hpp>
#include <posekit/topology.hpp>

#include "cgal_reference.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>

namespace posekit {
namespace {

constexpr double kPi = 3.14159265358979323846;

double enclosed_volume(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces) {
  double volume = 0.0;
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Eigen::Vector3d a = vertices.row(faces(f, 0));
    const Eigen::Vector3d b = vertices.row(faces(f, 1));
    const Eigen::Vector3d c = vertices.row(faces(f, 2));
    volume += a.dot(b.cross(c)) / 6.0;
  }
  return volume;
}

TEST(DemoArm, DefaultPosesAndSizes) {
  const PoseSet arm = make_demo_arm();
  ASSERT_EQ(arm.pose_count(), 4);
  EXPECT_EQ(arm.pose_name(0), "rest");
  EXPECT_EQ(arm.pose_name(1), "bend-45");
  EXPECT_EQ(arm.pose_name(2), "bend-90");
  EXPECT_EQ(arm.pose_name(3), "bend-135");
  EXPECT_EQ(arm.vertex_count(), 4034);
  EXPECT_EQ(arm.faces().rows(), 8064);
}

TEST(DemoArm, RestPoseIsAClosedSmoothOutwardCapsule) {
  const DemoArmOptions options;
  const PoseSet arm = make_demo_arm(options);
  const Eigen::MatrixX3d& rest = arm.pose(0);
  const EdgeMap map = edge_map(arm.faces());
  const AdjacencyLists around = edge_faces(map);
  for (int e = 0; e < around.item_count(); ++e) ASSERT_EQ(around.count(e), 2) << "edge " << e;
  EXPECT_EQ(rest.rows() - map.edges.rows() + arm.faces().rows(), 2);  // a sphere's Euler characteristic

  // Outward and close to the exact capsule volume (the polygon is inscribed, so slightly smaller).
  const double r = options.radius;
  const double exact = kPi * r * r * options.cylinder_length + 4.0 / 3.0 * kPi * r * r * r;
  const double volume = enclosed_volume(rest, arm.faces());
  EXPECT_LT(volume, exact);
  EXPECT_GT(volume, 0.99 * exact);

  // Every vertex on the capsule surface.
  for (Eigen::Index v = 0; v < rest.rows(); ++v) {
    const double x = std::clamp(rest(v, 0), 0.0, options.cylinder_length);
    const double distance = (rest.row(v) - Eigen::RowVector3d(x, 0.0, 0.0)).norm();
    ASSERT_NEAR(distance, r, 1e-12) << "vertex " << v;
  }
  // Smooth and consistently oriented: neighbouring faces are nearly parallel. The ring edges of the
  // cylinder are slightly concave because neighbouring rings are turned by half a segment.
  const Eigen::VectorXd angles = dihedral_angles(rest, arm.faces(), map, around);
  EXPECT_GT(angles.minCoeff(), -0.05);
  EXPECT_LT(angles.maxCoeff(), 0.2);
  // No sliver: even the fans at the poles keep a sizeable fraction of the average area.
  const Eigen::VectorXd areas = face_areas(rest, arm.faces());
  EXPECT_GT(areas.minCoeff(), 0.1 * areas.mean());
}

TEST(DemoArm, SkinningMovesOnlyTheSecondBoneAndTheJoint) {
  DemoArmOptions options;
  options.bend_angles_degrees = {100.0};
  const PoseSet arm = make_demo_arm(options);
  const Eigen::MatrixX3d& rest = arm.pose(0);
  const Eigen::MatrixX3d& bent = arm.pose(1);
  const double joint = 0.5 * options.cylinder_length;
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(100.0 * kPi / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  int rigid_first = 0;
  int rigid_second = 0;
  for (Eigen::Index v = 0; v < rest.rows(); ++v) {
    const double x = rest(v, 0);
    if (x <= joint - 0.5 * options.blend_width) {
      ASSERT_EQ(bent.row(v), rest.row(v)) << "vertex " << v;
      ++rigid_first;
    } else if (x >= joint + 0.5 * options.blend_width) {
      const Eigen::Vector3d pivot(joint, 0.0, 0.0);
      const Eigen::Vector3d expected = rotation * (rest.row(v).transpose() - pivot) + pivot;
      ASSERT_LT((bent.row(v).transpose() - expected).norm(), 1e-12) << "vertex " << v;
      ++rigid_second;
    }
  }
  EXPECT_GT(rigid_first, 1000);
  EXPECT_GT(rigid_second, 1000);
}

TEST(DemoArm, StrongBendsSelfIntersectAtTheInnerSideOfTheJoint) {
  DemoArmOptions options;
  options.bend_angles_degrees = {45.0, 135.0, 150.0};
  const PoseSet arm = make_demo_arm(options);
  EXPECT_TRUE(self_intersecting_faces(arm.pose(0), arm.faces()).empty());
  EXPECT_TRUE(self_intersecting_faces(arm.pose(1), arm.faces()).empty());
  const Eigen::MatrixX3d& rest = arm.pose(0);
  const double joint = 0.5 * options.cylinder_length;
  for (int pose = 2; pose < arm.pose_count(); ++pose) {
    const std::vector<int> hits = self_intersecting_faces(arm.pose(pose), arm.faces());
    EXPECT_GT(hits.size(), 50u) << arm.pose_name(pose);
    // Only the inner side near the joint collides: the side the arm bends towards (+y), within the
    // distance from the joint where the inner surfaces of two straight tubes at angle
    // (180 - bend) would meet, r / sin((180 - bend) / 2), plus one ring spacing.
    const double opening = (180.0 - options.bend_angles_degrees[static_cast<size_t>(pose) - 1]) * kPi / 180.0;
    const double reach = options.radius / std::sin(0.5 * opening) + 2.0 * kPi * options.radius / options.ring_segments;
    for (const int f : hits) {
      Eigen::RowVector3d centroid = Eigen::RowVector3d::Zero();
      for (int k = 0; k < 3; ++k) centroid += rest.row(arm.faces()(f, k)) / 3.0;
      EXPECT_LT(std::abs(centroid.x() - joint), reach) << arm.pose_name(pose) << " face " << f;
      EXPECT_GT(centroid.y(), 0.0) << arm.pose_name(pose) << " face " << f;
    }
  }
  // A stronger bend collapses more of the joint.
  EXPECT_LT(self_intersecting_faces(arm.pose(2), arm.faces()).size(),
            self_intersecting_faces(arm.pose(3), arm.faces()).size());
}

TEST(DemoArm, EveryPoseMatchesCgal) {
  DemoArmOptions options;
  options.bend_angles_degrees = {30.0, 90.0, 120.0, -150.0, 180.0};
  const PoseSet arm = make_demo_arm(options);
  for (int pose = 0; pose < arm.pose_count(); ++pose) {
    const auto expected = ::posekit::testing::cgal_self_intersecting_faces(arm.pose(pose), arm.faces());
    ASSERT_TRUE(expected.has_value());
    EXPECT_EQ(self_intersecting_faces(arm.pose(pose), arm.faces()), *expected) << arm.pose_name(pose);
  }
}

TEST(DemoArm, IsDeterministic) {
  DemoArmOptions options;
  options.ring_segments = 24;
  options.bend_angles_degrees = {22.5, -70.0};
  const PoseSet first = make_demo_arm(options);
  const PoseSet second = make_demo_arm(options);
  ASSERT_EQ(first.pose_count(), 3);
  EXPECT_EQ(first.pose_name(1), "bend-22.5");
  EXPECT_EQ(first.pose_name(2), "bend--70");
  EXPECT_EQ(first.faces(), second.faces());
  for (int pose = 0; pose < first.pose_count(); ++pose) EXPECT_EQ(first.pose(pose), second.pose(pose));
  EXPECT_LT(first.vertex_count(), 2000);
}

TEST(DemoArm, RejectsBadOptions) {
  const DemoArmOptions defaults;
  const auto rejects = [&defaults](auto change) {
    DemoArmOptions options = defaults;
    change(options);
    EXPECT_THROW(make_demo_arm(options), ArgumentError);
  };
  rejects([](DemoArmOptions& o) { o.ring_segments = 4; });
  rejects([](DemoArmOptions& o) { o.ring_segments = 30; });
  rejects([](DemoArmOptions& o) { o.ring_segments = 1 << 20; });
  rejects([](DemoArmOptions& o) { o.radius = 0.0; });
  rejects([](DemoArmOptions& o) { o.radius = std::nan(""); });
  rejects([](DemoArmOptions& o) { o.cylinder_length = -1.0; });
  rejects([](DemoArmOptions& o) { o.blend_width = 5.0; });
  rejects([](DemoArmOptions& o) { o.bend_angles_degrees = {190.0}; });
}

}  // namespace
}  // namespace posekit
