// The halfway stage: the correction in two legs through the pose halfway in edge space, whose
// halfway pose depends on the pair alone and is computed once per pair analysis.
#include "correct/nested_correction.hpp"
#include "correct/repair_stage.hpp"

#include "bent_arm.hpp"
#include "correction_fixture.hpp"

#include <posekit/cpu_device.hpp>

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

  // The first leg's analysis is kept beside the halfway pose, and the second run lends the same one.
  const std::shared_ptr<PairAnalysis> first_leg = fixture.context.pair_analysis->first_leg;
  ASSERT_NE(first_leg, nullptr);
  ASSERT_TRUE(first_leg->classification.has_value());
  const std::shared_ptr<const VertexTrajectories> first_leg_frames = first_leg->trajectories;

  StageReport second;
  const std::optional<Candidate> borrowed = stage->run(entangled, fixture.context, second);
  ASSERT_TRUE(borrowed.has_value());
  EXPECT_EQ(testing::stage_detail(second, "halfway_pose_seconds"), 0.0);
  EXPECT_EQ(fixture.context.pair_analysis->first_leg, first_leg);
  EXPECT_EQ(first_leg->trajectories, first_leg_frames);
  EXPECT_TRUE(borrowed->pose() == computed->pose());
  EXPECT_EQ(borrowed->new_face_count(), computed->new_face_count());
}

// The wider collar's run lends the first leg's analysis made under the first run's narrower collar:
// its legs give what they give computing that analysis under their own collar.
TEST(HalfwayLegs, TheFirstLegsAnalysisHoldsForAWiderCollar) {
  const PoseSet& arm = posekit::testing::bent_arm(16, 150.0);
  const std::unique_ptr<RepairStage> stage = make_halfway_stage();
  testing::StageFixture narrow(arm.pose(0), arm.pose(1), arm.faces());
  StageReport narrow_report;
  ASSERT_TRUE(stage->run(narrow.candidate(arm.pose(1)), narrow.context, narrow_report).has_value());
  ASSERT_NE(narrow.context.pair_analysis->first_leg, nullptr);

  testing::StageFixture borrowing(arm.pose(0), arm.pose(1), arm.faces());
  borrowing.options.collar_rings = 8;
  borrowing.context.pair_analysis = narrow.context.pair_analysis;
  testing::StageFixture computing(arm.pose(0), arm.pose(1), arm.faces());
  computing.options.collar_rings = 8;
  StageReport borrowed_report;
  StageReport computed_report;
  const std::optional<Candidate> borrowed =
      stage->run(borrowing.candidate(arm.pose(1)), borrowing.context, borrowed_report);
  const std::optional<Candidate> computed =
      stage->run(computing.candidate(arm.pose(1)), computing.context, computed_report);
  ASSERT_TRUE(borrowed.has_value());
  ASSERT_TRUE(computed.has_value());
  EXPECT_NE(computing.context.pair_analysis->first_leg, narrow.context.pair_analysis->first_leg);
  EXPECT_TRUE(borrowed->pose() == computed->pose());
}

// An analysis lent with poses that are not in its frame yet (a first leg again): the run normalizes
// them as the run that made the analysis did, borrows what it holds, and gives the same bits as a
// run that lends nothing.
TEST(HalfwayLegs, ALentAnalysisOfPosesOutsideItsFrameGivesTheSameBits) {
  const PoseSet& arm = posekit::testing::bent_arm(16, 150.0);
  // Far from the unit sphere, so that the run's normalization does move the poses.
  const Eigen::MatrixX3d reference = (3.0 * arm.pose(0)).rowwise() + Eigen::RowVector3d(5.0, -2.0, 1.0);
  const Eigen::MatrixX3d target = (3.0 * arm.pose(1)).rowwise() + Eigen::RowVector3d(5.0, -2.0, 1.0);
  const CorrectionOptions options;
  const std::unique_ptr<Device> device = make_cpu_device();
  const auto run = [&](LentAnalysis lent, CorrectionReport& report) {
    return correct_in_scope(reference, target, arm.faces(), *device, options, CorrectionScope::leg, &report, {},
                            nullptr, std::move(lent));
  };
  CorrectionReport alone;
  CorrectionReport first;
  CorrectionReport again;
  const Eigen::MatrixX3d without = run({}, alone);
  const auto analysis = std::make_shared<PairAnalysis>();
  const Eigen::MatrixX3d making = run(LentAnalysis{analysis, false}, first);
  ASSERT_TRUE(analysis->classification.has_value());
  const Eigen::MatrixX3d borrowing = run(LentAnalysis{analysis, false}, again);
  EXPECT_TRUE(making == without);
  EXPECT_TRUE(borrowing == without);
  EXPECT_GT(first.field.seconds.classification, 0.0);
  EXPECT_EQ(again.field.seconds.key_frames, 0.0);
  EXPECT_EQ(again.field.seconds.classification, 0.0);
  EXPECT_EQ(again.result.new_intersecting_faces, alone.result.new_intersecting_faces);
}

}  // namespace
}  // namespace posekit::detail
