// The halfway stage: the correction in two legs through the pose halfway in edge space, whose
// halfway pose depends on the pair alone and is computed once per pair analysis.
#include "correct/repair_stage.hpp"

#include "bent_arm.hpp"
#include "correction_fixture.hpp"

#include <gtest/gtest.h>


namespace posekit::detail {
namespace {

// The first run computes the halfway pose and keeps it in the pair analysis; a second run of the
// same analysis (the wider collar's) borrows it, spends nothing on it and proposes the same pose.
TEST(HalfwayLegs, ComputesTheHalfwayPoseOncePerPair) {
  const PoseSet& arm = posekit::testing::bent_arm(16, 150.0);
  testing::StageFixture fixture(arm.pose(0), arm.pose(1), arm.faces());
  const Candidate entangled = fixture.candidate(arm.pose(1));
  ASSERT_GT(entangled.new_face_count(), 0);
  const std::unique_ptr<RepairStage> stage = make_halfway_stage();
  ASSERT_FALSE(fixture.context.pair_analysis->halfway.has_value());

  StageReport first;
  const std::optional<Candidate> computed = stage->run(entangled, fixture.context, first);
  ASSERT_TRUE(computed.has_value());
  ASSERT_TRUE(fixture.context.pair_analysis->halfway.has_value());
  EXPECT_EQ(fixture.context.pair_analysis->halfway->rows(), arm.pose(0).rows());
  EXPECT_GT(testing::stage_detail(first, "halfway_pose_seconds"), 0.0);

  StageReport second;
  const std::optional<Candidate> borrowed = stage->run(entangled, fixture.context, second);
  ASSERT_TRUE(borrowed.has_value());
  EXPECT_EQ(testing::stage_detail(second, "halfway_pose_seconds"), 0.0);
  EXPECT_TRUE(borrowed->pose() == computed->pose());
  EXPECT_EQ(borrowed->new_face_count(), computed->new_face_count());
}

}  // namespace
}  // namespace posekit::detail
