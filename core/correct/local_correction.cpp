#include "correct/local_correction.hpp"

#include "correct/nested_correction.hpp"
#include "correct/repair_stage.hpp"
#include <posekit/vertex_regions.hpp>

#include <posekit/as_rigid_as_possible.hpp>
#include <posekit/error.hpp>
#include <posekit/submesh.hpp>

#include <algorithm>
#include <utility>

namespace posekit::detail {
namespace {

// Margins of the passes: the region must hold the whole entangled part, its surroundings and
// room to blend.
constexpr int kMarginRings[] = {4, 8, 16};

// Rounds of the passes at most.
constexpr int kRounds = 3;

// Beyond this fraction of the vertices a region is the pose again, with the pose's problems (and
// its cost); up to it, a region on its own still misses the parts the whole pose's key frames pass
// it through.
constexpr double kLargestRegionFraction = 0.5;

// A region of fewer faces gives the field too little to fit.
constexpr int kFewestFaces = 16;

// The share of its new faces the candidate's own pass frees at which the target's pass is not tried:
// the field's result is then nearly right, and the target's regions, which start from all of the
// target's entanglement, cost the most there and beat it on no pose measured (docs/correct.md).
constexpr double kFreedShareWithoutTargetPass = 0.75;

// Local correction of the candidate and, where that leaves over a quarter of its new faces, of the
// target itself: where the target is entangled over much of the pose, the field leaves most of it
// off the target, and correcting only the target's own entangled regions, each on its own, can free
// the pose and stay nearer the target.
class LocalCorrectionStage final : public RepairStage {
 public:
  explicit LocalCorrectionStage(EntangledPoses entangled)
      : RepairStage({"local-correction", "correct each region that still intersects again, as a mesh of its own"},
                    scope_bit(CorrectionScope::whole_pose) | scope_bit(CorrectionScope::leg) |
                        scope_bit(CorrectionScope::stretch_retry)),
        entangled_(entangled) {}

  // The first place leaves a candidate that still has at least half of the target's new faces to
  // the stages after it: the pose is then entangled throughout, the regions around its faces join
  // into large parts of the pose whose own corrections cost the most and free the least, and the
  // relaxation and the push free more of such a pose. The later place corrects whatever they leave,
  // entangled or not: where they free nothing, the regions of the target's own entanglement,
  // corrected each on its own, are what is left to try before the legs through the halfway pose.
  bool wanted(const Candidate& current, const CorrectionContext& context) const override {
    return RepairStage::wanted(current, context) &&
           (entangled_ == EntangledPoses::corrected || !context.entangled_throughout(current.new_face_count()));
  }

  std::optional<Candidate> run(const Candidate& current, CorrectionContext& context, StageReport& report) override {
    Candidate corrected = current;
    SweepOutcome outcome = correct_regions_locally(corrected, context);
    bool from_target = false;
    const bool target_tried =
        target_pass_wanted(current.new_face_count(), corrected.new_face_count()) && current.pose() != context.target;
    if (target_tried) {
      Candidate target(context.target, context.faces, context.reference_intersecting, context.target_pairs);
      const SweepOutcome target_outcome = correct_regions_locally(target, context);
      if (better(target, corrected, context)) {
        corrected = std::move(target);
        outcome = target_outcome;
        from_target = true;
      }
    }
    report.details = {{"from_target", from_target ? 1.0 : 0.0}, {"target_tried", target_tried ? 1.0 : 0.0}};
    return sweep_proposal(std::move(corrected), outcome, report,
                          std::to_string(outcome.regions) + " region(s) (" + std::to_string(outcome.vertices) +
                              " vertices) " +
                              (from_target ? "of the target corrected on their own, in place of the field's result"
                                           : "corrected again on their own"));
  }

 private:
  EntangledPoses entangled_;
};

}  // namespace

SweepOutcome correct_regions_locally(Candidate& candidate, const CorrectionContext& context) {
  const int vertex_count = context.vertex_count();
  const int blend_rings = context.options.blend_rings;
  RegionSweep sweep;
  sweep.seed_rings.assign(std::begin(kMarginRings), std::end(kMarginRings));
  sweep.rounds = kRounds;
  sweep.largest_fraction = kLargestRegionFraction;
  sweep.link_intersecting = true;
  const auto correct = [&](const std::vector<int>& region, const Candidate& current) -> std::optional<Probe> {
    std::vector<char> inside(static_cast<size_t>(vertex_count), 0);
    for (int v : region) inside[static_cast<size_t>(v)] = 1;
    std::vector<int> sub_vertices;
    const Mesh sub = submesh(context.reference, context.faces, faces_within(inside, context.faces), &sub_vertices);
    if (sub.faces.rows() < kFewestFaces) return std::nullopt;
    Eigen::MatrixX3d corrected;
    try {
      corrected = correct_in_scope(sub.vertices, current.pose()(sub_vertices, Eigen::all), sub.faces, context.device,
                                   context.options, CorrectionScope::region);
    } catch (const DeviceError&) {
      throw;
    } catch (const Error&) {
      return std::nullopt;  // a region the pipeline cannot take on its own (a degenerate field, say)
    }
    // Blended in from the region's rim, which keeps its place, so the seam stays closed: linearly
    // over the band, and as-rigidly-as-possible, the band keeping its own shape between the
    // corrected core and the rim, which stretches it less where the core moved far.
    std::vector<char> outside(static_cast<size_t>(vertex_count), 0);
    for (int v = 0; v < vertex_count; ++v) outside[static_cast<size_t>(v)] = inside[static_cast<size_t>(v)] == 0;
    const std::vector<int> depth = ring_distances(outside, context.neighbours, blend_rings + 1);
    Eigen::MatrixX3d blended = current.pose();
    Eigen::MatrixX3d core_positions = current.pose();
    std::vector<char> band(static_cast<size_t>(vertex_count), 0);
    std::vector<char> core(static_cast<size_t>(vertex_count), 0);
    for (size_t i = 0; i < sub_vertices.size(); ++i) {
      const int v = sub_vertices[i];
      const int d = depth[static_cast<size_t>(v)];
      const double weight = d < 0 ? 1.0 : std::min(1.0, static_cast<double>(d - 1) / static_cast<double>(blend_rings + 1));
      core_positions.row(v) = corrected.row(static_cast<Eigen::Index>(i));
      if (weight >= 1.0) core[static_cast<size_t>(v)] = 1;
      else if (weight > 0.0) band[static_cast<size_t>(v)] = 1;
      if (weight <= 0.0) continue;
      blended.row(v) += weight * (corrected.row(static_cast<Eigen::Index>(i)) - blended.row(v));
    }
    std::optional<Probe> best;
    const auto consider = [&](Eigen::MatrixX3d pose) {
      Probe probe = current.probe(std::move(pose));
      if (probe.new_faces.size() >= current.new_faces().size()) return;
      if (best && (probe.new_faces.size() > best->new_faces.size() ||
                   (probe.new_faces.size() == best->new_faces.size() &&
                    context.stretch.count(probe.pose) >= context.stretch.count(best->pose)))) {
        return;
      }
      best = std::move(probe);
    };
    consider(std::move(blended));
    if (std::optional<Eigen::MatrixX3d> rigid = as_rigid_as_possible(current.pose(), current.pose(), context.faces, band,
                                                                      core, core_positions, context.neighbours)) {
      consider(std::move(*rigid));
    }
    return best;
  };
  return sweep_regions(candidate, context, sweep, correct);
}

bool target_pass_wanted(int faces_before, int faces_left) {
  if (faces_left <= 0 || faces_before <= 0) return false;
  const double freed_share = 1.0 - static_cast<double>(faces_left) / static_cast<double>(faces_before);
  return freed_share < kFreedShareWithoutTargetPass;
}

std::unique_ptr<RepairStage> make_local_correction_stage(EntangledPoses entangled) {
  return std::make_unique<LocalCorrectionStage>(entangled);
}

}  // namespace posekit::detail
