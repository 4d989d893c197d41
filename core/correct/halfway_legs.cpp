// Correction in two legs through the pose halfway between the reference and the target in edge
// space (edge lengths and dihedral angles interpolated), each leg with its own key frames and
// field: the reference to the halfway pose, then the corrected halfway pose to the target. On the
// most entangled poses the two shorter motions free what the whole way could not; the halfway pose
// of the gradient-space key frames did worse than the edge-space one (docs/correct.md). The pose
// depends on the pair alone: a run of the same pair with a wider collar borrows it (0 seconds), and
// the first leg's analysis with it.
#include "correct/nested_correction.hpp"
#include "correct/repair_stage.hpp"

#include <posekit/error.hpp>
#include <posekit/interpolate.hpp>
#include <posekit/mesh.hpp>

#include <optional>
#include <utility>

namespace posekit::detail {
namespace {

class HalfwayStage final : public RepairStage {
 public:
  HalfwayStage()
      : RepairStage({"halfway", "correct in two legs through the pose halfway in edge space"},
                    scope_bit(CorrectionScope::whole_pose)) {}

  std::optional<Candidate> run(const Candidate& current, CorrectionContext& context, StageReport& report) override {
    std::optional<Eigen::MatrixX3d>& halfway = context.pair_analysis->halfway;
    double pose_seconds = 0.0;  // the interpolator's own figures: its preparation and the one pose
    if (!halfway) {
      try {
        PoseSet ends(context.faces);
        ends.add_pose(context.reference);
        ends.add_pose(context.target);
        InterpolationOptions edge_space;
        edge_space.method = InterpolationMethod::edge;
        PoseInterpolator interpolator(std::move(ends), edge_space);
        InterpolationStepReport step;
        halfway = interpolator.interpolate(two_pose_weights(0.5), &step);
        pose_seconds = interpolator.precomputation_seconds().total + step.seconds.total;
      } catch (const DeviceError&) {
        throw;
      } catch (const Error&) {
        return std::nullopt;  // no halfway pose for this mesh (edge space needs a manifold surface)
      }
    }
    // The first leg's pair is the same in every run of this pair: its analysis is made once and lent.
    std::shared_ptr<PairAnalysis>& first_leg_analysis = context.pair_analysis->first_leg;
    if (!first_leg_analysis) first_leg_analysis = std::make_shared<PairAnalysis>();
    CorrectionReport first_leg;
    const Eigen::MatrixX3d halfway_corrected =
        correct_in_scope(context.reference, *halfway, context.faces, context.device, context.options,
                         CorrectionScope::leg, &first_leg, {}, nullptr, LentAnalysis{first_leg_analysis, false});
    CorrectionReport second_leg;
    const Eigen::MatrixX3d corrected =
        correct_in_scope(halfway_corrected, context.target, context.faces, context.device, context.options,
                         CorrectionScope::leg, &second_leg, {}, &context.reference_intersecting);
    report.details = {{"halfway_new_faces", first_leg.result.new_intersecting_faces},
                      {"halfway_pose_seconds", pose_seconds},
                      {"first_leg_seconds", first_leg.seconds},
                      {"second_leg_seconds", second_leg.seconds}};
    report.note = "corrected in two legs through the pose halfway in edge space (" +
                  std::to_string(first_leg.result.new_intersecting_faces) +
                  " new intersecting faces there after its correction)";
    return whole_pose_proposal(current, corrected, report);
  }
};

}  // namespace

std::unique_ptr<RepairStage> make_halfway_stage() { return std::make_unique<HalfwayStage>(); }

}  // namespace posekit::detail
