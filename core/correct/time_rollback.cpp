#include "correct/time_rollback.hpp"

#include "correct/repair_stage.hpp"
#include <posekit/vertex_regions.hpp>

#include <posekit/rigid_motion.hpp>

#include <algorithm>
#include <sstream>
#include <utility>

namespace posekit::detail {
namespace {

// Core growth of the three passes: a residue that one ring cannot free usually belongs to a part
// that has to move back as a whole.
constexpr int kCoreRings[] = {1, 3, 6};

// Beyond this fraction of the vertices a region is no longer a part that went too far but the
// pose itself, and moving it back would undo the correction it was meant to finish.
constexpr double kLargestRegionFraction = 0.1;

// A fit of the region's earlier shape onto its surroundings needs points that span a plane.
constexpr int kFewestAnchors = 3;

bool touches_within(const std::vector<int>& face_list, const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                    const std::vector<int>& distance,
                    int within) {
  for (int f : face_list) {
    for (int c = 0; c < 3; ++c) {
      const int d = distance[static_cast<size_t>(faces(f, c))];
      if (d >= 0 && d <= within) return true;
    }
  }
  return false;
}

class RollbackStage final : public RepairStage {
 public:
  RollbackStage()
      : RepairStage({"rollback", "move regions that still intersect back along their path lines to the latest clean time"},
                    kEveryScope) {}

  bool wanted(const Candidate& current, const CorrectionContext& context) const override {
    return current.new_face_count() > 0 && context.field.has_value();
  }

  std::optional<Candidate> run(const Candidate& current, CorrectionContext& context, StageReport& report) override {
    Candidate moved = current;
    const PathLines& paths = context.field->paths;
    const RollbackOutcome outcome = roll_back_regions(
        moved, context, [&](const std::vector<int>& vertices, int segments) { return paths.sample(vertices, segments); });
    report.details = {{"earliest_time", outcome.earliest_time}};
    std::ostringstream note;
    note << outcome.sweep.regions << " region(s) (" << outcome.sweep.vertices
         << " vertices) moved back along their path lines, to time " << outcome.earliest_time << " at the earliest";
    return sweep_proposal(std::move(moved), outcome.sweep, report, note.str());
  }
};

}  // namespace

RollbackOutcome roll_back_regions(Candidate& candidate, const CorrectionContext& context, const PathSampler& paths,
                                  const RollbackOptions& options) {
  const int vertex_count = context.vertex_count();
  const int reach = options.blend_rings + options.anchor_rings;
  RollbackOutcome outcome;
  RegionSweep sweep;
  sweep.seed_rings.assign(std::begin(kCoreRings), std::end(kCoreRings));
  const auto roll_back = [&](const std::vector<int>& region, const Candidate& current) -> std::optional<Probe> {
    std::vector<char> inside(static_cast<size_t>(vertex_count), 0);
    for (int v : region) inside[static_cast<size_t>(v)] = 1;
    const std::vector<int> distance = ring_distances(inside, context.neighbours, reach);
    std::vector<int> support;
    std::vector<double> weight;
    std::vector<int> anchors;  // rows of `support`
    for (int v = 0; v < vertex_count; ++v) {
      const int d = distance[static_cast<size_t>(v)];
      if (d < 0) continue;
      if (d > options.blend_rings) anchors.push_back(static_cast<int>(support.size()));
      support.push_back(v);
      weight.push_back(d > options.blend_rings ? 0.0 : 1.0 - static_cast<double>(d) / (options.blend_rings + 1));
    }
    if (static_cast<double>(support.size()) > kLargestRegionFraction * vertex_count) return std::nullopt;
    const std::vector<Eigen::MatrixX3d> path = paths(support, options.segments);
    const Eigen::MatrixX3d& end = path.back();
    const Eigen::MatrixX3d end_anchors = end(anchors, Eigen::all);

    std::optional<Probe> best;
    int best_step = options.segments;
    for (int step = options.segments - 1; step >= 0; --step) {
      const Eigen::MatrixX3d& earlier = path[static_cast<size_t>(step)];
      RigidTransform placement;
      if (static_cast<int>(anchors.size()) >= kFewestAnchors) {
        placement = best_rigid_transform(earlier(anchors, Eigen::all), end_anchors);
      }
      Eigen::MatrixX3d moved = current.pose();
      for (size_t i = 0; i < support.size(); ++i) {
        if (weight[i] == 0.0) continue;
        const auto row = static_cast<Eigen::Index>(i);
        moved.row(support[i]) += weight[i] * (placement.apply_to_point(earlier.row(row)) - end.row(row));
      }
      Probe probe = current.probe(std::move(moved));
      const size_t fewest = best ? best->new_faces.size() : current.new_faces().size();
      if (probe.new_faces.size() >= fewest) continue;
      best = std::move(probe);
      best_step = step;
      // The latest time that frees the region and its blend is the one to keep.
      if (!touches_within(best->new_faces, context.faces, distance, options.blend_rings)) break;
    }
    if (best) outcome.earliest_time = std::min(outcome.earliest_time, static_cast<double>(best_step) / options.segments);
    return best;
  };
  outcome.sweep = sweep_regions(candidate, context, sweep, roll_back);
  return outcome;
}

std::unique_ptr<RepairStage> make_rollback_stage() { return std::make_unique<RollbackStage>(); }

}  // namespace posekit::detail
