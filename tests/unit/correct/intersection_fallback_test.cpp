#include "correct/intersection_fallback.hpp"

#include "correction_fixture.hpp"
#include "two_sheets.hpp"

#include <posekit/self_intersections.hpp>

#include <gtest/gtest.h>

#include <cmath>

namespace posekit::detail {
namespace {

TEST(IntersectionFallback, TakesTheTargetsShapeWhereTheResultHasNewIntersections) {
  const TwoSheets sheets = two_sheets(21);
  const Eigen::MatrixX3d integrated = dented(sheets, 0.3);  // pushed through the bottom sheet
  ASSERT_FALSE(self_intersecting_faces(integrated, sheets.faces).empty());
  const testing::StageFixture fixture(sheets.vertices, dented(sheets, 0.1), sheets.faces);  // target close, but clean
  Candidate result = fixture.candidate(integrated);
  const int before = result.new_face_count();
  const std::vector<char> in_transit(sheets.vertices.rows(), 0);
  const FallbackOutcome outcome = restore_target_regions(result, fixture.context, in_transit, 0.05);
  EXPECT_GT(before, 0);
  EXPECT_GE(outcome.sweep.regions, 1);
  EXPECT_EQ(outcome.smoothed_regions, 0);
  EXPECT_EQ(outcome.global_regions, 0);
  EXPECT_EQ(result.new_face_count(), 0);
  EXPECT_TRUE(self_intersecting_faces(result.pose(), sheets.faces).empty());
  // Far from the dent nothing moved.
  EXPECT_EQ(result.pose().row(sheets.top(0, 0)), integrated.row(sheets.top(0, 0)));
  EXPECT_EQ(result.pose().topRows(sheets.n * sheets.n), integrated.topRows(sheets.n * sheets.n));
  EXPECT_LT(outcome.sweep.vertices, sheets.n * sheets.n);
}

TEST(IntersectionFallback, LeavesTheResultWhenTheTargetIntersectsThereToo) {
  const TwoSheets sheets = two_sheets(41);  // fine enough that the intersection rings are too large to smooth
  const Eigen::MatrixX3d integrated = dented(sheets, 0.3);
  const testing::StageFixture fixture(sheets.vertices, dented(sheets, 0.35), sheets.faces);
  Candidate result = fixture.candidate(integrated);
  const std::vector<char> in_transit(sheets.vertices.rows(), 0);
  const FallbackOutcome outcome = restore_target_regions(result, fixture.context, in_transit, 0.05);
  EXPECT_EQ(outcome.sweep.regions, 0);
  EXPECT_EQ(result.pose(), integrated);
}

TEST(IntersectionFallback, KeepsIntersectionsTheReferenceAlreadyHas) {
  const TwoSheets sheets = two_sheets(21);
  const Eigen::MatrixX3d integrated = dented(sheets, 0.3);
  const testing::StageFixture fixture(integrated, sheets.vertices, sheets.faces);
  Candidate result = fixture.candidate(integrated);
  EXPECT_EQ(result.new_face_count(), 0);
  const std::vector<char> in_transit(sheets.vertices.rows(), 0);
  const FallbackOutcome outcome = restore_target_regions(result, fixture.context, in_transit, 0.05);
  EXPECT_EQ(outcome.sweep.regions, 0);
  EXPECT_EQ(result.pose(), integrated);
}

TEST(IntersectionFallback, SmoothsAFoldThatTheTargetHasToo) {
  const TwoSheets sheets = two_sheets(21);
  Eigen::MatrixX3d folded_pose = sheets.vertices;
  const int folded = sheets.top(10, 10);
  folded_pose(folded, 0) += 1.6 / 20.0;  // past its neighbour: the triangles around it overlap
  ASSERT_FALSE(self_intersecting_faces(folded_pose, sheets.faces).empty());
  const testing::StageFixture fixture(sheets.vertices, folded_pose, sheets.faces);
  Candidate result = fixture.candidate(folded_pose);
  const std::vector<char> in_transit(sheets.vertices.rows(), 0);
  const FallbackOutcome outcome = restore_target_regions(result, fixture.context, in_transit, 0.05);
  EXPECT_EQ(outcome.sweep.regions, 1);
  EXPECT_EQ(outcome.smoothed_regions, 1);
  EXPECT_TRUE(self_intersecting_faces(result.pose(), sheets.faces).empty());
  EXPECT_LT((result.pose().row(folded) - sheets.vertices.row(folded)).norm(), 0.5 / 20.0);
  EXPECT_EQ(result.pose().topRows(sheets.n * sheets.n), folded_pose.topRows(sheets.n * sheets.n));
}

}  // namespace
}  // namespace posekit::detail
