#include "correct/region_relaxation.hpp"

#include "correction_fixture.hpp"
#include "two_sheets.hpp"

#include <posekit/self_intersections.hpp>

#include <gtest/gtest.h>

namespace posekit::detail {
namespace {

// The top sheet creased down through the bottom one, as a blend or a local correction can leave a
// region: relaxed towards the flat reference with its surroundings held, it clears the bottom
// sheet, and what lies beyond the region keeps its place.
TEST(RegionRelaxation, RelaxesACreasedRegionTowardsTheReferenceShape) {
  const TwoSheets sheets = two_sheets(25);
  const Eigen::MatrixX3d creased = dented(sheets, 0.3);
  const testing::StageFixture fixture(sheets.vertices, creased, sheets.faces);
  Candidate result = fixture.candidate(creased);
  ASSERT_GT(result.new_face_count(), 0);
  const SweepOutcome relaxation = relax_folded_regions(result, fixture.context);
  EXPECT_EQ(result.new_face_count(), 0);
  EXPECT_GE(relaxation.regions, 1);
  EXPECT_TRUE(self_intersecting_faces(result.pose(), sheets.faces).empty());
  EXPECT_GT(relaxation.vertices, 0);
  EXPECT_LT(relaxation.vertices, static_cast<int>(creased.rows()) / 4);
  // The rims are outside every region.
  EXPECT_EQ(result.pose().row(0), creased.row(0));
  EXPECT_EQ(result.pose().row(sheets.top(0, 0)), creased.row(sheets.top(0, 0)));
  // The crease is lifted off the bottom sheet.
  EXPECT_GT(result.pose()(sheets.top(12, 12), 2), 0.0);
}

// Faces the reference already has intersecting are not the stage's to free.
TEST(RegionRelaxation, LeavesReferenceIntersectionsAndCleanPosesAlone) {
  const TwoSheets sheets = two_sheets(15);
  const Eigen::MatrixX3d clean_pose = dented(sheets, 0.1);
  const testing::StageFixture flat(sheets.vertices, clean_pose, sheets.faces);
  Candidate clean = flat.candidate(clean_pose);
  SweepOutcome relaxation = relax_folded_regions(clean, flat.context);
  EXPECT_EQ(relaxation.regions, 0);
  EXPECT_EQ(clean.pose(), clean_pose);
  const Eigen::MatrixX3d reference = dented(sheets, 0.3);
  const testing::StageFixture entangled(reference, reference, sheets.faces);
  Candidate result = entangled.candidate(reference);
  EXPECT_EQ(result.new_face_count(), 0);
  relaxation = relax_folded_regions(result, entangled.context);
  EXPECT_EQ(relaxation.regions, 0);
  EXPECT_EQ(result.pose(), reference);
}

}  // namespace
}  // namespace posekit::detail
