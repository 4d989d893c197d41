// The wider-collar stage: the whole correction again with a collar of 8 rings, offered only where
// the options give a narrower one and fit per region of interest, and wanted where faces remain or
// the surface tore.
#include "correct/repair_stage.hpp"

#include "bent_arm.hpp"
#include "correction_fixture.hpp"

#include <posekit/self_intersections.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

namespace posekit::detail {
namespace {

double detail_of(const StageReport& report, const std::string& name) {
  const auto found = std::find_if(report.details.begin(), report.details.end(),
                                  [&](const auto& entry) { return entry.first == name; });
  EXPECT_NE(found, report.details.end()) << name;
  return found == report.details.end() ? -1.0 : found->second;
}

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
  EXPECT_EQ(detail_of(report, "collar_rings"), 8.0);
  EXPECT_EQ(detail_of(report, "new_faces"), 0.0);
  EXPECT_EQ(report.regions, 1);
  EXPECT_GT(report.vertices, 0);
  EXPECT_FALSE(report.note.empty());
}

}  // namespace
}  // namespace posekit::detail
