// The wider-collar stage: the whole correction again with a collar of 8 rings, offered only where
// the options give a narrower one and fit per region of interest, and wanted where faces remain or
// the surface tore.
#include "correct/nested_correction.hpp"
#include "correct/repair_stage.hpp"

#include "bent_arm.hpp"
#include "correction_fixture.hpp"

#include <posekit/self_intersections.hpp>

#include <gtest/gtest.h>

#include <memory>

namespace posekit::detail {
namespace {

TEST(WiderCollar, EnabledOnlyForANarrowerCollarOfRegions) {
  const std::unique_ptr<RepairStage> stage = make_wider_collar_stage();
  CorrectionOptions options;
  EXPECT_LT(options.collar_rings, 8);
  EXPECT_TRUE(stage->enabled(options));
  options.collar_rings = 8;
  EXPECT_FALSE(stage->enabled(options));
  options = {};
  options.whole_mesh = true;
  EXPECT_FALSE(stage->enabled(options));
  options = {};
  options.disabled_stages = {"wider-collar"};
  EXPECT_FALSE(stage->enabled(options));
  EXPECT_FALSE(stage->runs_in(CorrectionScope::leg));
  EXPECT_FALSE(stage->runs_in(CorrectionScope::region));
}

// Wanted where new faces remain or where the candidate tore the surface, not on a clean untorn pose.
TEST(WiderCollar, WantedWhereFacesRemainOrTheSurfaceTore) {
  const PoseSet& arm = posekit::testing::bent_arm(16, 150.0);
  testing::StageFixture fixture(arm.pose(0), arm.pose(1), arm.faces());
  const std::unique_ptr<RepairStage> stage = make_wider_collar_stage();
  EXPECT_TRUE(stage->wanted(fixture.candidate(arm.pose(1)), fixture.context));
  const Candidate rest = fixture.candidate(arm.pose(0));
  ASSERT_EQ(rest.new_face_count(), 0);
  EXPECT_FALSE(stage->wanted(rest, fixture.context));
  // One vertex pulled out of the surface, away from the arm's middle, by many edge lengths.
  Eigen::MatrixX3d spiked = arm.pose(0);
  const Eigen::RowVector3d middle = spiked.colwise().mean();
  const int pulled = arm.faces()(0, 0);
  const Eigen::RowVector3d outward = (spiked.row(pulled) - middle).normalized();
  const double edge = (spiked.row(pulled) - spiked.row(arm.faces()(0, 1))).norm();
  spiked.row(pulled) += 10.0 * edge * outward;
  const Candidate torn = fixture.candidate(spiked);
  ASSERT_EQ(torn.new_face_count(), 0);
  EXPECT_TRUE(stage->wanted(torn, fixture.context));
}

// From the bent arm itself, its new faces untouched, the stage's own correction frees it.
TEST(WiderCollar, CorrectsTheWholePoseAgain) {
  const PoseSet& arm = posekit::testing::bent_arm(16, 150.0);
  testing::StageFixture fixture(arm.pose(0), arm.pose(1), arm.faces());
  const Candidate entangled = fixture.candidate(arm.pose(1));
  ASSERT_GT(entangled.new_face_count(), 0);
  const std::unique_ptr<RepairStage> stage = make_wider_collar_stage();
  StageReport report;
  const std::optional<Candidate> proposal = stage->run(entangled, fixture.context, report);
  ASSERT_TRUE(proposal.has_value());
  EXPECT_EQ(proposal->new_face_count(), 0);
  EXPECT_EQ(testing::stage_detail(report, "collar_rings"), 8.0);
  EXPECT_EQ(testing::stage_detail(report, "new_faces"), 0.0);
  EXPECT_EQ(report.regions, 1);
  EXPECT_GT(report.vertices, 0);
  EXPECT_FALSE(report.note.empty());
}

// The wider collar's run corrects the same pair in the same frame: it borrows the key frames, the
// tested pairs and the classification the field stage computed, and gives what it would give
// computing them itself.
TEST(WiderCollar, ItsRunBorrowsWhatDependsOnThePairAlone) {
  const PoseSet& arm = posekit::testing::bent_arm(16, 150.0);
  testing::StageFixture fixture(arm.pose(0), arm.pose(1), arm.faces());
  FieldReport field_report;
  fixture.context.field_report = &field_report;
  StageReport field_stage;
  ASSERT_TRUE(make_field_stage()->run(fixture.candidate(arm.pose(1)), fixture.context, field_stage).has_value());
  const std::shared_ptr<PairAnalysis> analysis = fixture.context.pair_analysis;
  ASSERT_TRUE(analysis->classification.has_value());
  ASSERT_NE(analysis->trajectories, nullptr);

  CorrectionOptions wider = fixture.options;
  wider.collar_rings = 8;
  const auto run = [&](std::shared_ptr<PairAnalysis> lent, CorrectionReport& report) {
    return correct_in_scope(fixture.reference, fixture.target, fixture.faces, *fixture.device, wider,
                            CorrectionScope::whole_pose, &report, {}, nullptr, LentAnalysis{std::move(lent), true});
  };
  CorrectionReport borrowed;
  CorrectionReport computed;
  const Eigen::MatrixX3d with_analysis = run(analysis, borrowed);
  const Eigen::MatrixX3d without = run(std::make_shared<PairAnalysis>(), computed);
  EXPECT_EQ(borrowed.field.seconds.key_frames, 0.0);
  EXPECT_EQ(borrowed.field.seconds.classification, 0.0);
  EXPECT_GT(computed.field.seconds.key_frames, 0.0);
  EXPECT_GT(computed.field.seconds.classification, 0.0);
  EXPECT_EQ(borrowed.field.tested_poses, computed.field.tested_poses);
  EXPECT_EQ(borrowed.field.near_intersection_vertices, computed.field.near_intersection_vertices);
  EXPECT_TRUE(with_analysis == without);
  EXPECT_EQ(borrowed.result.new_intersecting_faces, 0);
}

}  // namespace
}  // namespace posekit::detail
