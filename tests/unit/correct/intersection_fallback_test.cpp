#include "correct/intersection_fallback.hpp"

#include <posekit/self_intersections.hpp>

#include <gtest/gtest.h>

#include <cmath>

namespace posekit::detail {
namespace {

// Two parallel square sheets of n by n vertices, 0.2 apart: the bottom at z = 0, the top at z = 0.2.
struct TwoSheets {
  Eigen::MatrixX3d vertices;
  Eigen::MatrixX3i faces;
  int n = 0;
  int top(int i, int j) const { return n * n + i * n + j; }
};

TwoSheets two_sheets(int n) {
  TwoSheets sheets;
  sheets.n = n;
  sheets.vertices.resize(2 * n * n, 3);
  sheets.faces.resize(2 * 2 * (n - 1) * (n - 1), 3);
  int face = 0;
  for (int sheet = 0; sheet < 2; ++sheet) {
    const int base = sheet * n * n;
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        sheets.vertices.row(base + i * n + j) << i / double(n - 1), j / double(n - 1), 0.2 * sheet;
      }
    }
    for (int i = 0; i + 1 < n; ++i) {
      for (int j = 0; j + 1 < n; ++j) {
        const int a = base + i * n + j;
        sheets.faces.row(face++) << a, a + n, a + 1;
        sheets.faces.row(face++) << a + 1, a + n, a + n + 1;
      }
    }
  }
  return sheets;
}

// The top sheet with a dent of the given depth around its middle.
Eigen::MatrixX3d dented(const TwoSheets& sheets, double depth) {
  Eigen::MatrixX3d pose = sheets.vertices;
  for (int i = 0; i < sheets.n; ++i) {
    for (int j = 0; j < sheets.n; ++j) {
      const double x = i / double(sheets.n - 1) - 0.5;
      const double y = j / double(sheets.n - 1) - 0.5;
      pose(sheets.top(i, j), 2) -= depth * std::exp(-(x * x + y * y) / 0.01);
    }
  }
  return pose;
}

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
