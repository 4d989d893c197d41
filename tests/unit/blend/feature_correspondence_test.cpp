#include <gtest/gtest.h>

#include <posekit/error.hpp>
#include <posekit/feature_correspondence.hpp>

#include "blend_test_shapes.hpp"

#include <set>

namespace posekit {
namespace {

TEST(PermissibleAssignments, PermuteWithinGroupsOnly) {
  const std::vector<int> vertices{10, 11, 12, 13, 14, 15};
  const std::vector<std::string> groups{"legs", "", "legs", "head", "legs", "head"};
  const std::vector<std::vector<int>> all = permissible_assignments(vertices, groups);
  ASSERT_EQ(all.size(), 12u);  // 3! * 2!
  EXPECT_EQ(all.front(), vertices);
  EXPECT_EQ(std::set<std::vector<int>>(all.begin(), all.end()).size(), 12u);
  for (const std::vector<int>& a : all) {
    EXPECT_EQ(a[1], 11);
    EXPECT_EQ(std::set<int>({a[0], a[2], a[4]}), std::set<int>({10, 12, 14}));
    EXPECT_EQ(std::set<int>({a[3], a[5]}), std::set<int>({13, 15}));
  }
  EXPECT_EQ(permissible_assignments({1, 2}, {"", ""}).size(), 1u);
  EXPECT_THROW(permissible_assignments({1, 2, 3}, {"a", "a"}), ArgumentError);
  EXPECT_THROW(permissible_assignments({1, 2, 3, 4}, {"a", "a", "a", "a"}, 23), ArgumentError);
}

TEST(ChooseCorrespondence, FindsTheAssignmentOfLeastEnergy) {
  // Features on the 90-degree bend; the tip of the second bone and a vertex half way along the first
  // are given in the wrong order, in one group. Only the right order is a natural pose.
  const PoseSet examples = testing::small_arm({0.0, 45.0, 135.0});
  const PoseSet target = testing::small_arm({90.0});
  BlendedDeformer deformer(examples);
  const Eigen::MatrixX3d& rest = examples.pose(0);
  std::vector<int> features = testing::spread_vertices(rest, 8);
  Eigen::Index middle = 0;
  (rest.rowwise() - Eigen::RowVector3d(1.0, 0.5, 0.0)).rowwise().squaredNorm().minCoeff(&middle);
  Eigen::Index tip = 0;
  rest.col(0).maxCoeff(&tip);
  features.push_back(static_cast<int>(middle));
  features.push_back(static_cast<int>(tip));
  std::vector<int> shuffled = features;
  std::swap(shuffled[8], shuffled[9]);
  Eigen::MatrixX3d positions(10, 3);
  for (int r = 0; r < 10; ++r) positions.row(r) = target.pose(0).row(features[static_cast<size_t>(r)]);
  std::vector<std::string> groups(10, "");
  groups[8] = groups[9] = "ends";
  const auto assignments = permissible_assignments(shuffled, groups);
  ASSERT_EQ(assignments.size(), 2u);
  const CorrespondenceChoice choice = choose_correspondence(deformer, positions, assignments);
  EXPECT_EQ(choice.assignment, 1);
  EXPECT_EQ(choice.vertices, features);
  ASSERT_EQ(choice.energies.size(), 2u);
  EXPECT_LT(10 * choice.energies[1], choice.energies[0]);
  EXPECT_EQ(deformer.constraint_count(), 10);
  EXPECT_LT(testing::max_distortion(choice.result.vertices, target.pose(0), examples.faces()), 0.03);
  EXPECT_THROW(choose_correspondence(deformer, positions, {}), ArgumentError);
  EXPECT_THROW(choose_correspondence(deformer, positions, {{1, 2}}), ArgumentError);
}

}  // namespace
}  // namespace posekit
