// The repair ladder: its stages run in their order, each only when enabled, in scope, wanted and
// not already run on the same candidate; a proposal replaces the candidate only when better; every
// stage has its report entry.
#include "correct/repair_ladder.hpp"

#include "bent_arm.hpp"
#include "correction_fixture.hpp"

#include <posekit/correct.hpp>

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace posekit::detail {
namespace {

// The stage order the documentation gives (docs/correct.md): the rollback runs again after the
// local correction; repair_stages() names each stage once.
const std::vector<std::string> kLocalRepairs = {"fallback", "rollback", "reference-zones", "relaxation",
                                                "contact-push"};
const std::vector<std::string> kLadderOrder = [] {
  std::vector<std::string> order{"field", "fallback", "rollback", "reference-zones", "contact-separation"};
  for (int place = 0; place < 2; ++place) {
    order.push_back("local-correction");
    order.insert(order.end(), kLocalRepairs.begin(), kLocalRepairs.end());
  }
  order.push_back("halfway");
  order.insert(order.end(), kLocalRepairs.begin(), kLocalRepairs.end());
  for (const char* name : {"final-reproduction", "stretch-relief", "contact-separation", "wider-collar"}) {
    order.push_back(name);
  }
  return order;
}();
const std::vector<std::string> kStageNames = {
    "field",      "fallback",     "rollback", "reference-zones",    "contact-separation", "local-correction",
    "relaxation", "contact-push", "halfway",  "final-reproduction", "stretch-relief",     "wider-collar"};

// A stage that records when it ran and proposes a fixed pose.
class RecordingStage final : public RepairStage {
 public:
  RecordingStage(std::string name, ScopeSet scopes, std::vector<std::string>& log, bool wanted_always,
                 std::optional<Eigen::MatrixX3d> proposal)
      : RepairStage({std::move(name), "records its runs"}, scopes),
        log_(log),
        wanted_always_(wanted_always),
        proposal_(std::move(proposal)) {}

  bool wanted(const Candidate& current, const CorrectionContext& context) const override {
    return wanted_always_ || RepairStage::wanted(current, context);
  }

  std::optional<Candidate> run(const Candidate& current, CorrectionContext& /*context*/, StageReport& report) override {
    log_.push_back(info().name);
    report.note = "ran";
    if (!proposal_) return std::nullopt;
    Candidate proposed = current;
    proposed.move_to(*proposal_);
    return proposed;
  }

 private:
  std::vector<std::string>& log_;
  bool wanted_always_;
  std::optional<Eigen::MatrixX3d> proposal_;
};

class RepairLadderTest : public ::testing::Test {
 protected:
  const PoseSet* arm_ = &posekit::testing::bent_arm(16, 150.0);
};

TEST_F(RepairLadderTest, RunsStagesInOrderAndKeepsOnlyBetterProposals) {
  CorrectionOptions options;
  options.disabled_stages = {"rollback"};  // the name of one of the fakes below
  testing::StageFixture fixture(arm_->pose(0), arm_->pose(1), arm_->faces(), options);
  std::vector<std::string> log;
  RepairLadder ladder;
  // Proposes the clean rest pose: better (no new faces).
  ladder.push_back(std::make_unique<RecordingStage>("first", kEveryScope, log, false, arm_->pose(0)));
  // Disabled by name: never runs.
  ladder.push_back(std::make_unique<RecordingStage>("rollback", kEveryScope, log, true, std::nullopt));
  // Not in the whole pose's scope.
  ladder.push_back(std::make_unique<RecordingStage>("nested-only", scope_bit(CorrectionScope::region), log, true,
                                                    std::nullopt));
  // Wanted only while new faces remain: after "first" none do.
  ladder.push_back(std::make_unique<RecordingStage>("while-faces", kEveryScope, log, false, std::nullopt));
  // Proposes the entangled target again: worse, not kept.
  ladder.push_back(std::make_unique<RecordingStage>("worse", kEveryScope, log, true, arm_->pose(1)));
  std::vector<StageReport> reports;
  const Candidate start = fixture.candidate(arm_->pose(1));
  ASSERT_GT(start.new_face_count(), 0);
  const Candidate end = run_repair_ladder(ladder, start, fixture.context, reports);

  EXPECT_EQ(log, (std::vector<std::string>{"first", "worse"}));
  ASSERT_EQ(reports.size(), 5u);
  EXPECT_EQ(reports[0].name, "first");
  EXPECT_TRUE(reports[0].ran);
  EXPECT_TRUE(reports[0].kept);
  EXPECT_EQ(reports[0].note, "ran");
  EXPECT_EQ(reports[0].new_faces_before, start.new_face_count());
  EXPECT_EQ(reports[0].new_faces_after, 0);
  EXPECT_EQ(reports[1].skipped, "disabled");
  EXPECT_EQ(reports[2].skipped, "nested run");
  EXPECT_EQ(reports[3].skipped, "nothing to repair");
  EXPECT_TRUE(reports[4].ran);
  EXPECT_FALSE(reports[4].kept);
  EXPECT_TRUE(reports[4].note.empty());  // a note only for what was kept
  EXPECT_EQ(reports[4].new_faces_after, 0);
  EXPECT_EQ(end.pose(), arm_->pose(0));
}

// A stage does not run again on the candidate a stage of its repair left unchanged, nor on the one
// such a stage made; it does once another stage changed the candidate.
TEST_F(RepairLadderTest, SkipsARepairOnTheCandidateItLeftUnchangedOrMade) {
  testing::StageFixture fixture(arm_->pose(0), arm_->pose(1), arm_->faces(), CorrectionOptions{});
  std::vector<std::string> log;
  RepairLadder ladder;
  const auto repeat = [&] {
    // Proposes the entangled target: never better than the candidate it starts from.
    return std::make_unique<RecordingStage>("repeat", kEveryScope, log, true, arm_->pose(1));
  };
  const auto change = [&] {
    // Proposes the clean rest pose: better than the entangled target.
    return std::make_unique<RecordingStage>("change", kEveryScope, log, true, arm_->pose(0));
  };
  ladder.push_back(repeat());
  ladder.push_back(repeat());
  ladder.push_back(change());
  ladder.push_back(change());
  ladder.push_back(repeat());
  ladder.push_back(repeat());
  std::vector<StageReport> reports;
  run_repair_ladder(ladder, fixture.candidate(arm_->pose(1)), fixture.context, reports);

  EXPECT_EQ(log, (std::vector<std::string>{"repeat", "change", "repeat"}));
  ASSERT_EQ(reports.size(), 6u);
  EXPECT_TRUE(reports[0].ran);
  EXPECT_FALSE(reports[0].kept);
  EXPECT_FALSE(reports[1].ran);
  EXPECT_EQ(reports[1].skipped, "unchanged since it ran");
  EXPECT_TRUE(reports[2].kept);
  EXPECT_FALSE(reports[3].ran);
  EXPECT_EQ(reports[3].skipped, "unchanged since it ran");
  EXPECT_TRUE(reports[4].ran);
  EXPECT_EQ(reports[5].skipped, "unchanged since it ran");
}

// The separation of the target's contacts keeps its one outcome by two rules (early: only when
// clean; late: when better), so its two places are different repairs; every other name is one.
TEST(RepairLadder, RepairsAreNamedByStageButTheSeparationsDiffer) {
  std::vector<std::string> separations;
  for (const std::unique_ptr<RepairStage>& stage : default_repair_ladder()) {
    if (stage->info().name == "contact-separation") separations.push_back(stage->repair());
    else EXPECT_EQ(stage->repair(), stage->info().name);
  }
  ASSERT_EQ(separations.size(), 2u);
  EXPECT_NE(separations[0], separations[1]);
}

TEST(RepairLadder, DefaultOrderIsTheDocumentedOne) {
  std::vector<std::string> names;
  for (const std::unique_ptr<RepairStage>& stage : default_repair_ladder()) names.push_back(stage->info().name);
  EXPECT_EQ(names, kLadderOrder);
  std::vector<std::string> listed;
  for (const RepairStageInfo& info : repair_stages()) {
    listed.push_back(info.name);
    EXPECT_EQ(info.optional, info.name != "field") << info.name;
    EXPECT_FALSE(info.summary.empty()) << info.name;
  }
  EXPECT_EQ(listed, kStageNames);
}

// Nested runs leave out the stages that would nest again or that the whole pose runs after them.
TEST(RepairLadder, NestedScopesLeaveOutTheirStages) {
  const auto runs_in = [](const std::string& name, CorrectionScope scope) {
    for (const std::unique_ptr<RepairStage>& stage : default_repair_ladder()) {
      if (stage->info().name == name) return stage->runs_in(scope);
    }
    ADD_FAILURE() << "no stage " << name;
    return false;
  };
  for (const std::string& name : kStageNames) EXPECT_TRUE(runs_in(name, CorrectionScope::whole_pose)) << name;
  EXPECT_FALSE(runs_in("local-correction", CorrectionScope::region));
  EXPECT_TRUE(runs_in("local-correction", CorrectionScope::leg));
  EXPECT_FALSE(runs_in("halfway", CorrectionScope::leg));
  EXPECT_FALSE(runs_in("halfway", CorrectionScope::region));
  EXPECT_FALSE(runs_in("contact-separation", CorrectionScope::leg));
  EXPECT_TRUE(runs_in("rollback", CorrectionScope::region));
  EXPECT_FALSE(runs_in("wider-collar", CorrectionScope::leg));
  EXPECT_FALSE(runs_in("wider-collar", CorrectionScope::region));
  // The wider collar's run on a pose already free: every stage but the halfway legs and itself.
  for (const std::string& name : kStageNames) {
    EXPECT_EQ(runs_in(name, CorrectionScope::stretch_retry), name != "halfway" && name != "wider-collar") << name;
  }
}

// A whole correction reports every stage of the ladder in order, with what it did.
TEST_F(RepairLadderTest, CorrectionReportsEveryStageInOrder) {
  const std::unique_ptr<Device> device = make_cpu_device();
  CorrectionOptions options;
  options.disabled_stages = {"halfway"};
  CorrectionReport report;
  correct_pose(arm_->pose(0), arm_->pose(1), arm_->faces(), *device, options, &report);
  std::vector<std::string> names;
  for (const StageReport& stage : report.stages) names.push_back(stage.name);
  EXPECT_EQ(names, kLadderOrder);
  const StageReport& field = report.stages.front();
  EXPECT_TRUE(field.ran);
  EXPECT_TRUE(field.kept);
  EXPECT_GT(field.new_faces_before, field.new_faces_after);
  EXPECT_GT(field.vertices, 0);
  EXPECT_EQ(report.stage("halfway")->skipped, "disabled");
  EXPECT_EQ(report.stages.back().new_faces_after, report.result.new_intersecting_faces);
  for (size_t k = 1; k < report.stages.size(); ++k) {
    EXPECT_EQ(report.stages[k].new_faces_before, report.stages[k - 1].new_faces_after) << report.stages[k].name;
    EXPECT_TRUE(report.stages[k].ran || !report.stages[k].skipped.empty()) << report.stages[k].name;
  }
}

}  // namespace
}  // namespace posekit::detail
