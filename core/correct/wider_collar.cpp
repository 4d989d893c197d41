// The whole correction again with a wider collar around the regions of interest. A narrow collar
// keeps the fields small and fast, but where a region's field is pinned too close to what
// intersects, its path lines can bend parts through each other that a wider collar holds apart;
// the costly stages after it then work on what the field should have freed. Where faces remain or
// the surface tore, the correction runs once more with the collar that freed every pose we
// measured (docs/correct.md), and the better of the two is kept. Where only the tearing calls for
// it, the run leaves out the halfway legs.
#include "correct/nested_correction.hpp"
#include "correct/repair_stage.hpp"

#include <string>

namespace posekit::detail {
namespace {

constexpr int kWideCollarRings = 8;

class WiderCollarStage final : public RepairStage {
 public:
  WiderCollarStage()
      : RepairStage({"wider-collar", "correct again with a wider collar of constrained vertices around each region"},
                    scope_bit(CorrectionScope::whole_pose)) {}

  bool enabled(const CorrectionOptions& options) const override {
    return RepairStage::enabled(options) && !options.whole_mesh && options.collar_rings < kWideCollarRings;
  }

  // Also where the candidate tore the surface (faces over three times as long as in both poses): a
  // field pinned close to what it moves bends its collar sharply.
  bool wanted(const Candidate& current, const CorrectionContext& context) const override {
    return RepairStage::wanted(current, context) ||
           context.stretch.count(current.pose(), kStronglyStretchedFactor) > 0;
  }

  std::optional<Candidate> run(const Candidate& current, CorrectionContext& context, StageReport& report) override {
    CorrectionOptions wider = context.options;
    wider.collar_rings = kWideCollarRings;
    // On a candidate already free, only a free proposal can win, by its stretch: the halfway legs,
    // which free the most entangled poses at the cost of two more corrections, are left out there.
    const CorrectionScope scope =
        current.new_face_count() == 0 ? CorrectionScope::stretch_retry : CorrectionScope::whole_pose;
    // The same pair in the same frame: the run borrows what depends on the pair alone.
    const Eigen::MatrixX3d corrected = correct_in_scope(context.reference, context.target, context.faces,
                                                        context.device, wider, scope, nullptr, {}, nullptr,
                                                        LentAnalysis{context.pair_analysis, true});
    // The proposal's own count: the nested run need not measure its result a second time.
    Candidate proposal = whole_pose_proposal(current, corrected, report);
    const int new_faces = proposal.new_face_count();
    report.details = {{"collar_rings", kWideCollarRings}, {"new_faces", new_faces}};
    report.note = "corrected again with a collar of " + std::to_string(kWideCollarRings) + " rings (" +
                  std::to_string(new_faces) + " new intersecting faces)";
    return proposal;
  }
};

}  // namespace

std::unique_ptr<RepairStage> make_wider_collar_stage() { return std::make_unique<WiderCollarStage>(); }

}  // namespace posekit::detail
