#include "correct/time_rollback.hpp"

#include "correction_fixture.hpp"
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
      samples.push_back(pose(vertices, Eigen::all));
    }
    return samples;
  }
};

TEST(TimeRollback, MovesADentPressedThroughAnotherSheetBackUntilItIsClean) {
  const TwoSheets sheets = two_sheets(41);
  DentPaths paths{&sheets, 0.3};
  const Eigen::MatrixX3d pressed = dented(sheets, 0.3);  // through the bottom sheet, 0.2 below
  const testing::StageFixture fixture(sheets.vertices, pressed, sheets.faces);
  Candidate result = fixture.candidate(pressed);
  ASSERT_GT(result.new_face_count(), 0);
  const RollbackOutcome rollback =
      roll_back_regions(result, fixture.context, [&](const std::vector<int>& v, int s) { return paths(v, s); });
  EXPECT_EQ(result.new_face_count(), 0);
  EXPECT_TRUE(self_intersecting_faces(result.pose(), sheets.faces).empty());
  EXPECT_EQ(rollback.sweep.regions, 1);
  // The latest clean time: the dent's 0.3 * t must stay above the bottom sheet 0.2 below.
  EXPECT_LT(rollback.earliest_time, 0.2 / 0.3);
  EXPECT_GE(rollback.earliest_time, 0.3);
  // The bottom sheet did not move (its path lines stand still), nor did the top sheet's rim.
  EXPECT_EQ(result.pose().topRows(sheets.n * sheets.n), pressed.topRows(sheets.n * sheets.n));
  EXPECT_EQ(result.pose().row(sheets.top(0, 0)), pressed.row(sheets.top(0, 0)));
  EXPECT_LT(rollback.sweep.vertices, sheets.n * sheets.n / 2);
}

TEST(TimeRollback, KeepsTheIntersectionsOfTheReference) {
  const TwoSheets sheets = two_sheets(21);
  DentPaths paths{&sheets, 0.3};
  const Eigen::MatrixX3d pressed = dented(sheets, 0.3);
  // Intersections the reference already has are not the rollback's to remove.
  const testing::StageFixture fixture(pressed, pressed, sheets.faces);
  Candidate result = fixture.candidate(pressed);
  const RollbackOutcome rollback =
      roll_back_regions(result, fixture.context, [&](const std::vector<int>& v, int s) { return paths(v, s); });
  EXPECT_EQ(rollback.sweep.regions, 0);
  EXPECT_EQ(paths.calls, 0);
  EXPECT_EQ(result.pose(), pressed);
}

}  // namespace
}  // namespace posekit::detail
