#include "correct/intersection_fallback.hpp"

#include "two_sheets.hpp"

#include <posekit/self_intersections.hpp>

#include <gtest/gtest.h>

#include <cmath>

namespace posekit::detail {
namespace {

TEST(IntersectionFallback, TakesTheTargetsShapeWhereTheResultHasNewIntersections) {
  const TwoSheets sheets = two_sheets(21);
  const std::vector<int> reference_intersecting;
  Eigen::MatrixX3d result = dented(sheets, 0.3);  // pushed through the bottom sheet
  ASSERT_FALSE(self_intersecting_faces(result, sheets.faces).empty());
  const Eigen::MatrixX3d target = dented(sheets, 0.1);  // close, but clean
  const Eigen::MatrixX3d integrated = result;
  const std::vector<char> in_transit(sheets.vertices.rows(), 0);

  const FallbackResult outcome =
      restore_target_regions(result, target, reference_intersecting, sheets.faces, in_transit, 0.05);
  EXPECT_GT(outcome.new_faces_before, 0);
  EXPECT_GE(outcome.regions, 1);
  EXPECT_EQ(outcome.global_regions, 0);
  EXPECT_TRUE(self_intersecting_faces(result, sheets.faces).empty());
  // Far from the dent nothing moved.
  EXPECT_EQ(result.row(sheets.top(0, 0)), integrated.row(sheets.top(0, 0)));
  EXPECT_EQ(result.topRows(sheets.n * sheets.n), integrated.topRows(sheets.n * sheets.n));
  EXPECT_LT(outcome.vertices, sheets.n * sheets.n);
}

TEST(IntersectionFallback, LeavesTheResultWhenTheTargetIntersectsThereToo) {
  const TwoSheets sheets = two_sheets(41);  // fine enough that the intersection rings are too large to smooth
  Eigen::MatrixX3d result = dented(sheets, 0.3);
  const Eigen::MatrixX3d integrated = result;
  const Eigen::MatrixX3d target = dented(sheets, 0.35);
  const std::vector<char> in_transit(sheets.vertices.rows(), 0);

  const FallbackResult outcome = restore_target_regions(result, target, {}, sheets.faces, in_transit, 0.05);
  EXPECT_EQ(outcome.regions, 0);
  EXPECT_GE(outcome.rejected_regions, 1);
  EXPECT_EQ(result, integrated);
}

TEST(IntersectionFallback, KeepsIntersectionsTheReferenceAlreadyHas) {
  const TwoSheets sheets = two_sheets(21);
  Eigen::MatrixX3d result = dented(sheets, 0.3);
  const std::vector<int> reference_intersecting = self_intersecting_faces(result, sheets.faces);
  const Eigen::MatrixX3d integrated = result;
  const std::vector<char> in_transit(sheets.vertices.rows(), 0);
  const FallbackResult outcome =
      restore_target_regions(result, sheets.vertices, reference_intersecting, sheets.faces, in_transit, 0.05);
  EXPECT_EQ(outcome.new_faces_before, 0);
  EXPECT_EQ(outcome.regions, 0);
  EXPECT_EQ(result, integrated);
}

TEST(IntersectionFallback, SmoothsAFoldThatTheTargetHasToo) {
  const TwoSheets sheets = two_sheets(21);
  Eigen::MatrixX3d result = sheets.vertices;
  const int folded = sheets.top(10, 10);
  result(folded, 0) += 1.6 / 20.0;  // past its neighbour: the triangles around it overlap
  ASSERT_FALSE(self_intersecting_faces(result, sheets.faces).empty());
  const Eigen::MatrixX3d target = result;
  const std::vector<char> in_transit(sheets.vertices.rows(), 0);

  const FallbackResult outcome = restore_target_regions(result, target, {}, sheets.faces, in_transit, 0.05);
  EXPECT_EQ(outcome.regions, 0);
  EXPECT_EQ(outcome.smoothed_regions, 1);
  EXPECT_TRUE(self_intersecting_faces(result, sheets.faces).empty());
  EXPECT_LT((result.row(folded) - sheets.vertices.row(folded)).norm(), 0.5 / 20.0);
  EXPECT_EQ(result.topRows(sheets.n * sheets.n), target.topRows(sheets.n * sheets.n));
}

}  // namespace
}  // namespace posekit::detail
