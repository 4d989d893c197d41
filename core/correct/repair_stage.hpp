// One stage of the repair ladder: a name, the options that switch it off, the scopes it runs in,
// when it is wanted, and a run that proposes a better candidate. The ladder (repair_ladder.hpp)
// runs the stages in their order and keeps a proposal only when it is better; each stage fills its
// own report entry.
#pragma once

#include "correct/candidate.hpp"
#include "correct/correction_context.hpp"
#include "correct/region_sweep.hpp"

#include <posekit/correct.hpp>

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace posekit::detail {

class RepairStage {
 public:
  RepairStage(RepairStageInfo info, ScopeSet scopes) : info_(std::move(info)), scopes_(scopes) {}
  virtual ~RepairStage() = default;
  RepairStage(const RepairStage&) = delete;
  RepairStage& operator=(const RepairStage&) = delete;

  const RepairStageInfo& info() const { return info_; }
  /// Whether the stage runs in `scope` (nested runs leave some out).
  bool runs_in(CorrectionScope scope) const { return (scopes_ & scope_bit(scope)) != 0; }
  /// Whether the options allow the stage: not disabled by name, and whatever else it needs.
  virtual bool enabled(const CorrectionOptions& options) const;
  /// Whether there is anything for the stage to do on `current`: by default, new faces remain.
  virtual bool wanted(const Candidate& current, const CorrectionContext& context) const;
  /// Stages of one repair propose the same for the same candidate and keep it by the same rule, so
  /// the ladder does not run one on a candidate another has already left unchanged: by default, the
  /// stages of one name.
  virtual std::string repair() const { return info_.name; }
  /// A candidate to compare with `current`, or none. Fills `report`'s regions, vertices, note and
  /// details; the ladder fills the rest.
  virtual std::optional<Candidate> run(const Candidate& current, CorrectionContext& context, StageReport& report) = 0;

 private:
  RepairStageInfo info_;
  ScopeSet scopes_;
};

using RepairLadder = std::vector<std::unique_ptr<RepairStage>>;

/// What a region-by-region stage proposes: `swept` where its sweep kept a region, none otherwise.
/// The report gets the sweep's regions and vertices, and `note` when a region was kept.
std::optional<Candidate> sweep_proposal(Candidate swept, const SweepOutcome& outcome, StageReport& report,
                                        std::string note);

/// What a stage that corrects the whole pose anew proposes: `current` moved to `pose`, reported as
/// one region of the vertices that differ.
Candidate whole_pose_proposal(const Candidate& current, const Eigen::Ref<const Eigen::MatrixX3d>& pose,
                              StageReport& report);

// The stages, each defined in the file of its method.
std::unique_ptr<RepairStage> make_field_stage();                // field_correction.cpp
std::unique_ptr<RepairStage> make_fallback_stage();             // intersection_fallback.cpp
std::unique_ptr<RepairStage> make_rollback_stage();             // time_rollback.cpp
std::unique_ptr<RepairStage> make_reference_zones_stage();      // reference_zones.cpp
/// What a place of the local correction does with a candidate still entangled throughout
/// (CorrectionContext::entangled_throughout): leaves it to the stages after it, or corrects it.
enum class EntangledPoses { left_to_later_stages, corrected };
std::unique_ptr<RepairStage> make_local_correction_stage(EntangledPoses entangled);  // local_correction.cpp
std::unique_ptr<RepairStage> make_relaxation_stage();           // region_relaxation.cpp
std::unique_ptr<RepairStage> make_halfway_stage();              // halfway_legs.cpp
std::unique_ptr<RepairStage> make_final_reproduction_stage();   // target_reproduction.cpp
std::unique_ptr<RepairStage> make_stretch_relief_stage();       // stretch_relief.cpp
std::unique_ptr<RepairStage> make_contact_push_stage();         // contact_separation.cpp
std::unique_ptr<RepairStage> make_wider_collar_stage();         // wider_collar.cpp
/// The contact separation early (kept only when clean, where the pose is entangled throughout) and
/// late (competing as is), sharing one outcome: contact_separation.cpp.
std::pair<std::unique_ptr<RepairStage>, std::unique_ptr<RepairStage>> make_contact_separation_stages();

}  // namespace posekit::detail
