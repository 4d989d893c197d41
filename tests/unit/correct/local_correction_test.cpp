#include "correct/local_correction.hpp"

#include "two_sheets.hpp"

#include <posekit/cpu_device.hpp>
#include <posekit/self_intersections.hpp>

#include <gtest/gtest.h>

#include <cmath>

namespace posekit::detail {
namespace {

// Flat sheets would put every constraint on the quadric z (z - 0.2) = 0, where the field's
// polynomial part is undetermined: a gentle wave makes them a shape.
Eigen::MatrixX3d waved(Eigen::MatrixX3d pose) {
  for (Eigen::Index v = 0; v < pose.rows(); ++v) pose(v, 2) += 0.03 * std::sin(6.0 * pose(v, 0)) * std::cos(5.0 * pose(v, 1));
  return pose;
}

// The top sheet's dent pushed through the bottom sheet, as a fallback leaves a region that took
// an entangled target's shape: corrected again on its own, from the flat sheets, the dent stops at
// the bottom sheet.
TEST(LocalCorrection, CorrectsAnEntangledRegionAgainOnItsOwn) {
  const TwoSheets sheets = two_sheets(25);
  const Eigen::MatrixX3d reference = waved(sheets.vertices);
  Eigen::MatrixX3d result = waved(dented(sheets, 0.3));
  const Eigen::MatrixX3d entangled = result;
  const int intersecting = static_cast<int>(self_intersecting_faces(result, sheets.faces).size());
  ASSERT_GT(intersecting, 0);
  const std::unique_ptr<Device> device = make_cpu_device();
  const LocalCorrectionResult local =
      correct_regions_locally(result, reference, sheets.faces, {}, *device, CorrectionOptions{});
  EXPECT_EQ(local.new_faces_before, intersecting);
  EXPECT_GE(local.regions, 1);
  EXPECT_TRUE(self_intersecting_faces(result, sheets.faces).empty());
  // The sheets' rims are outside every region and did not move.
  EXPECT_EQ(result.row(0), entangled.row(0));
  EXPECT_EQ(result.row(sheets.top(0, 0)), entangled.row(sheets.top(0, 0)));
  EXPECT_GT(local.vertices, 0);
  EXPECT_LT(local.vertices, static_cast<int>(result.rows()));
}

TEST(LocalCorrection, LeavesACleanResultAlone) {
  const TwoSheets sheets = two_sheets(15);
  Eigen::MatrixX3d result = dented(sheets, 0.1);
  const Eigen::MatrixX3d clean = result;
  const std::unique_ptr<Device> device = make_cpu_device();
  const LocalCorrectionResult local =
      correct_regions_locally(result, sheets.vertices, sheets.faces, {}, *device, CorrectionOptions{});
  EXPECT_EQ(local.new_faces_before, 0);
  EXPECT_EQ(local.regions, 0);
  EXPECT_EQ(result, clean);
}

}  // namespace
}  // namespace posekit::detail
