#include "correct/region_relaxation.hpp"

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
  Eigen::MatrixX3d result = dented(sheets, 0.3);
  const Eigen::MatrixX3d creased = result;
  const int intersecting = static_cast<int>(self_intersecting_faces(result, sheets.faces).size());
  ASSERT_GT(intersecting, 0);
  const RelaxationResult relaxation = relax_folded_regions(result, sheets.vertices, sheets.faces, {});
  EXPECT_EQ(relaxation.new_faces_before, intersecting);
  EXPECT_EQ(relaxation.new_faces_after, 0);
  EXPECT_GE(relaxation.regions, 1);
  EXPECT_TRUE(self_intersecting_faces(result, sheets.faces).empty());
  EXPECT_GT(relaxation.vertices, 0);
  EXPECT_LT(relaxation.vertices, static_cast<int>(result.rows()) / 4);
  // The rims are outside every region.
  EXPECT_EQ(result.row(0), creased.row(0));
  EXPECT_EQ(result.row(sheets.top(0, 0)), creased.row(sheets.top(0, 0)));
  // The crease is lifted off the bottom sheet.
  EXPECT_GT(result(sheets.top(12, 12), 2), 0.0);
}

// Faces the reference already has intersecting are not the stage's to free.
TEST(RegionRelaxation, LeavesReferenceIntersectionsAndCleanPosesAlone) {
  const TwoSheets sheets = two_sheets(15);
  Eigen::MatrixX3d clean = dented(sheets, 0.1);
  const Eigen::MatrixX3d before = clean;
  RelaxationResult relaxation = relax_folded_regions(clean, sheets.vertices, sheets.faces, {});
  EXPECT_EQ(relaxation.new_faces_before, 0);
  EXPECT_EQ(relaxation.regions, 0);
  EXPECT_EQ(clean, before);

  const Eigen::MatrixX3d reference = dented(sheets, 0.3);
  Eigen::MatrixX3d result = reference;
  relaxation = relax_folded_regions(result, reference, sheets.faces, self_intersecting_faces(reference, sheets.faces));
  EXPECT_EQ(relaxation.new_faces_before, 0);
  EXPECT_EQ(result, reference);
}

}  // namespace
}  // namespace posekit::detail
