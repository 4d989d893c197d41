#include <gtest/gtest.h>

#include <posekit/error.hpp>
#include <posekit/rotation_clusters.hpp>

#include "blend_test_shapes.hpp"

#include <set>

namespace posekit {
namespace {

TEST(RotationClusters, SeparateTheTwoBonesOfTheArm) {
  // The arm bends about the joint at x = 2 with a blend one unit wide: the vertices of each bone move
  // rigidly together across the examples and must share a label.
  const PoseSet arm = testing::small_arm({0.0, 45.0, 90.0, 135.0});
  std::vector<Eigen::MatrixX3d> examples;
  for (int k = 0; k < arm.pose_count(); ++k) examples.push_back(arm.pose(k));
  const std::vector<int> labels = rotation_clusters(examples, arm.faces(), 2, 0.1);
  std::set<int> first, second;
  for (Eigen::Index v = 0; v < arm.pose(0).rows(); ++v) {
    const double x = arm.pose(0)(v, 0);
    if (x < 1.2) first.insert(labels[static_cast<size_t>(v)]);
    if (x > 2.8) second.insert(labels[static_cast<size_t>(v)]);
  }
  ASSERT_EQ(first.size(), 1u);
  ASSERT_EQ(second.size(), 1u);
  EXPECT_NE(*first.begin(), *second.begin());
}

TEST(RotationClusters, UseEveryLabelAndAreDeterministic) {
  const PoseSet arm = testing::small_arm({0.0, 90.0});
  const std::vector<Eigen::MatrixX3d> examples{arm.pose(0), arm.pose(1)};
  const std::vector<int> a = rotation_clusters(examples, arm.faces(), 12);
  EXPECT_EQ(a, rotation_clusters(examples, arm.faces(), 12));
  EXPECT_EQ(std::set<int>(a.begin(), a.end()).size(), 12u);
  EXPECT_EQ(*std::max_element(a.begin(), a.end()), 11);
  EXPECT_THROW(rotation_clusters(examples, arm.faces(), 0), ArgumentError);
  EXPECT_THROW(rotation_clusters({}, arm.faces(), 2), ArgumentError);
}

TEST(WeightClusters, FollowTheLargestWeightAndRenumber) {
  Eigen::MatrixXd w(4, 3);
  w << 0.1, 0.0, 0.9,  //
      0.2, 0.0, 0.8,   //
      0.7, 0.0, 0.3,   //
      0.0, 0.0, 1.0;
  EXPECT_EQ(weight_clusters(w), (std::vector<int>{0, 0, 1, 0}));
}

}  // namespace
}  // namespace posekit
