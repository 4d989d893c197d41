#include "correct/repair_ladder.hpp"

#include <posekit/error.hpp>

#include <algorithm>
#include <chrono>
#include <map>

namespace posekit::detail {

bool RepairStage::enabled(const CorrectionOptions& options) const {
  return !info_.optional || std::find(options.disabled_stages.begin(), options.disabled_stages.end(), info_.name) ==
                                options.disabled_stages.end();
}

bool RepairStage::wanted(const Candidate& current, const CorrectionContext& /*context*/) const {
  return current.new_face_count() > 0;
}

std::optional<Candidate> sweep_proposal(Candidate swept, const SweepOutcome& outcome, StageReport& report,
                                        std::string note) {
  report.regions = outcome.regions;
  report.vertices = outcome.vertices;
  if (outcome.regions == 0) return std::nullopt;
  report.note = std::move(note);
  return swept;
}

Candidate whole_pose_proposal(const Candidate& current, const Eigen::Ref<const Eigen::MatrixX3d>& pose,
                              StageReport& report) {
  Probe probe = current.probe(pose);
  report.regions = 1;
  report.vertices = static_cast<int>(differing_vertices(probe.pose, current.pose()).size());
  Candidate proposal = current;
  proposal.accept(std::move(probe));
  return proposal;
}

namespace {

// The local repairs, by how they change a region: restored to the target's shape, moved back in
// time along the path lines, the reference's slid intersections given back its shape, relaxed
// towards the reference's shape, pushed out of what it lies in. They are cheap, and the costly
// stages leave a few faces they free, so they run again after each. The first round leaves out the
// relaxation and the push, which move more of the pose than the local correction after them.
void add_local_repairs(RepairLadder& ladder, bool all) {
  if (all) ladder.push_back(make_fallback_stage());
  ladder.push_back(make_rollback_stage());
  ladder.push_back(make_reference_zones_stage());
  if (!all) return;
  ladder.push_back(make_relaxation_stage());
  ladder.push_back(make_contact_push_stage());
}

}  // namespace

// Field, the fallback and the first local repairs; where they freed less than half of what the
// target had, the separation of the target's contacts, which frees poses pressed together
// throughout in a few seconds; then the costly stages, each a region or the whole motion corrected
// anew and followed by the local repairs (the local correction twice: a pose entangled throughout
// is left to the relaxation and the push first, and what they leave is corrected locally after
// them); then the target given back wherever nothing is wrong, stretched regions given its shape,
// the separation of the target's contacts competing as is, and last, where faces remain, the whole
// correction again with a wider collar.
RepairLadder default_repair_ladder() {
  auto [early_separation, late_separation] = make_contact_separation_stages();
  RepairLadder ladder;
  ladder.push_back(make_field_stage());
  ladder.push_back(make_fallback_stage());
  add_local_repairs(ladder, false);
  ladder.push_back(std::move(early_separation));
  for (const EntangledPoses entangled : {EntangledPoses::left_to_later_stages, EntangledPoses::corrected}) {
    ladder.push_back(make_local_correction_stage(entangled));
    add_local_repairs(ladder, true);
  }
  ladder.push_back(make_halfway_stage());
  add_local_repairs(ladder, true);
  ladder.push_back(make_final_reproduction_stage());
  ladder.push_back(make_stretch_relief_stage());
  ladder.push_back(std::move(late_separation));
  ladder.push_back(make_wider_collar_stage());
  return ladder;
}

Candidate run_repair_ladder(const RepairLadder& ladder, Candidate start, CorrectionContext& context,
                            std::vector<StageReport>& reports) {
  Candidate current = std::move(start);
  // The candidate's version (proposals kept so far) and, per repair, the version it last ran on or
  // made: a stage's own proposal is the candidate it would start from again.
  int version = 0;
  std::map<std::string, int> ran_on;
  for (const std::unique_ptr<RepairStage>& stage : ladder) {
    StageReport report;
    report.name = stage->info().name;
    report.new_faces_before = current.new_face_count();
    const std::string repair = stage->repair();
    if (!stage->enabled(context.options)) {
      report.skipped = "disabled";
    } else if (!stage->runs_in(context.scope)) {
      report.skipped = "nested run";
    } else if (!stage->wanted(current, context)) {
      report.skipped = "nothing to repair";
    } else if (const auto seen = ran_on.find(repair); seen != ran_on.end() && seen->second == version) {
      report.skipped = "unchanged since it ran";
    } else {
      const auto begin = std::chrono::steady_clock::now();
      context.report_progress(report.name, 0.0);
      report.ran = true;
      std::optional<Candidate> proposal = stage->run(current, context, report);
      if (proposal && better(*proposal, current, context)) {
        current = std::move(*proposal);
        report.kept = true;
        ++version;
      }
      ran_on[repair] = version;
      if (!report.kept) report.note.clear();
      report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
      context.report_progress(report.name, 1.0);
    }
    report.new_faces_after = current.new_face_count();
    reports.push_back(std::move(report));
  }
  return current;
}

void check_disabled_stages(const std::vector<std::string>& disabled) {
  for (const std::string& name : disabled) {
    const std::vector<RepairStageInfo>& stages = repair_stages();
    const auto found = std::find_if(stages.begin(), stages.end(), [&](const RepairStageInfo& s) { return s.name == name; });
    if (found == stages.end()) {
      std::string known;
      for (const RepairStageInfo& s : stages) {
        if (s.optional) known += (known.empty() ? "" : ", ") + s.name;
      }
      throw ArgumentError("disabled_stages names '" + name + "', which is not a repair stage (" + known + ")");
    }
    if (!found->optional) throw ArgumentError("the " + name + " stage cannot be disabled");
  }
}

}  // namespace posekit::detail

const std::vector<posekit::RepairStageInfo>& posekit::repair_stages() {
  static const std::vector<RepairStageInfo> stages = [] {
    std::vector<RepairStageInfo> infos;
    for (const std::unique_ptr<detail::RepairStage>& stage : detail::default_repair_ladder()) {
      const auto same = [&](const RepairStageInfo& info) { return info.name == stage->info().name; };
      if (std::none_of(infos.begin(), infos.end(), same)) infos.push_back(stage->info());
    }
    return infos;
  }();
  return stages;
}
