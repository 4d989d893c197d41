#include "correct/time_rollback.hpp"

#include "two_sheets.hpp"

#include <posekit/self_intersections.hpp>

#include <gtest/gtest.h>

namespace posekit::detail {
namespace {

// Path lines along which the top sheet's dent deepens from nothing to `depth`, evenly in time.
struct DentPaths {
  const TwoSheets* sheets = nullptr;
  double depth = 0;
  int calls = 0;
  std::vector<Eigen::MatrixX3d> operator()(const std::vector<int>& vertices, int segments) {
    ++calls;
    std::vector<Eigen::MatrixX3d> samples;
    for (int k = 0; k <= segments; ++k) {
      const Eigen::MatrixX3d pose = dented(*sheets, depth * k / segments);
      Eigen::MatrixX3d rows(static_cast<Eigen::Index>(vertices.size()), 3);
      for (size_t i = 0; i < vertices.size(); ++i) rows.row(static_cast<Eigen::Index>(i)) = pose.row(vertices[i]);
      samples.push_back(rows);
    }
    return samples;
  }
};

TEST(TimeRollback, MovesADentPressedThroughAnotherSheetBackUntilItIsClean) {
  const TwoSheets sheets = two_sheets(41);
  DentPaths paths{&sheets, 0.3};
  Eigen::MatrixX3d result = dented(sheets, 0.3);  // through the bottom sheet, 0.2 below
  const Eigen::MatrixX3d pressed = result;
  const int intersecting = static_cast<int>(self_intersecting_faces(result, sheets.faces).size());
  ASSERT_GT(intersecting, 0);
  const RollbackResult rollback = roll_back_regions(
      result, [&](const std::vector<int>& v, int s) { return paths(v, s); }, sheets.faces, {});
  EXPECT_EQ(rollback.new_faces_before, intersecting);
  EXPECT_EQ(rollback.new_faces_after, 0);
  EXPECT_TRUE(self_intersecting_faces(result, sheets.faces).empty());
  EXPECT_EQ(rollback.regions, 1);
  // The latest clean time: the dent's 0.3 * t must stay above the bottom sheet 0.2 below.
  EXPECT_LT(rollback.earliest_time, 0.2 / 0.3);
  EXPECT_GE(rollback.earliest_time, 0.3);
  // The bottom sheet did not move (its path lines stand still), nor did the top sheet's rim.
  EXPECT_EQ(result.topRows(sheets.n * sheets.n), pressed.topRows(sheets.n * sheets.n));
  EXPECT_EQ(result.row(sheets.top(0, 0)), pressed.row(sheets.top(0, 0)));
  EXPECT_LT(rollback.vertices, sheets.n * sheets.n / 2);
}

TEST(TimeRollback, KeepsTheIntersectionsOfTheReference) {
  const TwoSheets sheets = two_sheets(21);
  DentPaths paths{&sheets, 0.3};
  Eigen::MatrixX3d result = dented(sheets, 0.3);
  const Eigen::MatrixX3d pressed = result;
  // Intersections the reference already has are not the rollback's to remove.
  const RollbackResult rollback = roll_back_regions(
      result, [&](const std::vector<int>& v, int s) { return paths(v, s); }, sheets.faces,
      self_intersecting_faces(result, sheets.faces));
  EXPECT_EQ(rollback.new_faces_before, 0);
  EXPECT_EQ(rollback.regions, 0);
  EXPECT_EQ(paths.calls, 0);
  EXPECT_EQ(result, pressed);
}

}  // namespace
}  // namespace posekit::detail
