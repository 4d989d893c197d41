#include "correct/local_correction.hpp"

#include "correct/repair_stage.hpp"
#include "correction_fixture.hpp"
#include "two_sheets.hpp"

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
  const Eigen::MatrixX3d entangled = waved(dented(sheets, 0.3));
  const testing::StageFixture fixture(waved(sheets.vertices), entangled, sheets.faces);
  Candidate result = fixture.candidate(entangled);
  ASSERT_GT(result.new_face_count(), 0);
  const SweepOutcome local = correct_regions_locally(result, fixture.context);
  EXPECT_GE(local.regions, 1);
  EXPECT_EQ(result.new_face_count(), 0);
  EXPECT_TRUE(self_intersecting_faces(result.pose(), sheets.faces).empty());
  // The sheets' rims are outside every region and did not move.
  EXPECT_EQ(result.pose().row(0), entangled.row(0));
  EXPECT_EQ(result.pose().row(sheets.top(0, 0)), entangled.row(sheets.top(0, 0)));
  EXPECT_GT(local.vertices, 0);
  EXPECT_LT(local.vertices, static_cast<int>(entangled.rows()));
}

TEST(LocalCorrection, LeavesACleanResultAlone) {
  const TwoSheets sheets = two_sheets(15);
  const Eigen::MatrixX3d clean_pose = dented(sheets, 0.1);
  const testing::StageFixture fixture(sheets.vertices, clean_pose, sheets.faces);
  Candidate result = fixture.candidate(clean_pose);
  const SweepOutcome local = correct_regions_locally(result, fixture.context);
  EXPECT_EQ(local.regions, 0);
  EXPECT_EQ(result.pose(), clean_pose);
}

// Where the candidate still has at least half of the target's new faces, the pose is entangled
// throughout: the local correction's first place leaves it to the stages after it, in every scope,
// and its later place corrects it; where fewer remain, both run.
TEST(LocalCorrection, FirstPlaceLeavesAPoseEntangledThroughoutToTheStagesAfterIt) {
  const TwoSheets sheets = two_sheets(25);
  const Eigen::MatrixX3d entangled = waved(dented(sheets, 0.4));
  testing::StageFixture fixture(waved(sheets.vertices), entangled, sheets.faces);
  const Candidate as_target = fixture.candidate(entangled);
  const Candidate shallower = fixture.candidate(waved(dented(sheets, 0.22)));
  ASSERT_GT(as_target.new_face_count(), 0);
  ASSERT_GT(shallower.new_face_count(), 0);
  ASSERT_LE(2 * shallower.new_face_count(), fixture.context.target_new_faces);
  const std::unique_ptr<RepairStage> first = make_local_correction_stage(EntangledPoses::left_to_later_stages);
  const std::unique_ptr<RepairStage> later = make_local_correction_stage(EntangledPoses::corrected);
  for (const CorrectionScope scope :
       {CorrectionScope::whole_pose, CorrectionScope::leg, CorrectionScope::stretch_retry}) {
    fixture.context.scope = scope;
    EXPECT_FALSE(first->wanted(as_target, fixture.context));
    EXPECT_TRUE(later->wanted(as_target, fixture.context));
    for (const RepairStage* stage : {first.get(), later.get()}) {
      EXPECT_TRUE(stage->wanted(shallower, fixture.context));
      EXPECT_FALSE(stage->wanted(fixture.candidate(waved(sheets.vertices)), fixture.context));
    }
  }
}

// The target's own regions are tried only where the candidate's pass left faces and freed under
// three quarters of them.
TEST(LocalCorrection, TriesTheTargetOnlyWhereTheCandidatesPassFreedLittle) {
  EXPECT_TRUE(target_pass_wanted(80, 74));
  EXPECT_TRUE(target_pass_wanted(441, 441));
  EXPECT_TRUE(target_pass_wanted(19, 9));
  EXPECT_TRUE(target_pass_wanted(4, 2));
  EXPECT_FALSE(target_pass_wanted(4, 1));
  EXPECT_FALSE(target_pass_wanted(209, 3));
  EXPECT_FALSE(target_pass_wanted(31, 0));
  EXPECT_FALSE(target_pass_wanted(0, 0));
}

}  // namespace
}  // namespace posekit::detail
