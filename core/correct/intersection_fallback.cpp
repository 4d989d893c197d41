#include "correct/intersection_fallback.hpp"

#include "correct/repair_stage.hpp"
#include "correct/target_reproduction.hpp"
#include <posekit/vertex_regions.hpp>

#include <posekit/topology.hpp>

#include <algorithm>
#include <utility>

namespace posekit::detail {
namespace {

using Flags = std::vector<char>;

// Rounds of region growing; a replacement can uncover a residue next to it, hence more than one.
constexpr int kPasses = 3;
// A region whose integrated position strays this far (relative to the reference's diagonal) from
// the target counts as one the field could not reach.
constexpr double kFallbackDeviation = 1e-2;
// A part dragged along by an obstacle is followed only up to this fraction of the vertices: beyond
// it the region is no longer a part but the pose, and the target is what was to be corrected.
constexpr double kLargestDraggedFraction = 0.1;
// A membrane flattens what it covers: it is tried only on regions of at most this many vertices.
constexpr int kLargestSmoothedRegion = 40;

bool is_set(const Flags& flags, int vertex) { return flags[static_cast<size_t>(vertex)] != 0; }

// Adds the vertices farther than `threshold` from the target that connect to the flagged ones
// through such vertices: a part dragged along by an obstacle.
void grow_through_deviation(Flags& flags, const AdjacencyLists& neighbours,
                            const Eigen::Ref<const Eigen::MatrixX3d>& result,
                            const Eigen::Ref<const Eigen::MatrixX3d>& target, double threshold) {
  std::vector<int> stack;
  for (int v = 0; v < static_cast<int>(flags.size()); ++v) {
    if (is_set(flags, v)) stack.push_back(v);
  }
  while (!stack.empty()) {
    const int v = stack.back();
    stack.pop_back();
    for (int w : neighbours[v]) {
      if (is_set(flags, w) || (result.row(w) - target.row(w)).norm() <= threshold) continue;
      flags[static_cast<size_t>(w)] = 1;
      stack.push_back(w);
    }
  }
}

int count(const Flags& flags) { return static_cast<int>(std::count(flags.begin(), flags.end(), 1)); }

bool overlaps(const Flags& a, const Flags& b) {
  for (size_t v = 0; v < a.size(); ++v) {
    if (a[v] != 0 && b[v] != 0) return true;
  }
  return false;
}

class FallbackStage final : public RepairStage {
 public:
  FallbackStage()
      : RepairStage({"fallback", "give regions the field cannot free the target's shape, or smooth small folds"},
                    kEveryScope) {}

  bool wanted(const Candidate& current, const CorrectionContext& context) const override {
    return current.new_face_count() > 0 && context.field.has_value();
  }

  std::optional<Candidate> run(const Candidate& current, CorrectionContext& context, StageReport& report) override {
    Candidate restored = current;
    const FallbackOutcome outcome = restore_target_regions(restored, context, context.pair_analysis->classification->in_transit,
                                                           kFallbackDeviation * context.diagonal);
    report.details = {{"global_regions", outcome.global_regions}, {"smoothed_regions", outcome.smoothed_regions}};
    return sweep_proposal(
        std::move(restored), outcome.sweep, report,
        std::to_string(outcome.sweep.regions) + " region(s) (" + std::to_string(outcome.sweep.vertices) +
            " vertices): " + std::to_string(outcome.sweep.regions - outcome.smoothed_regions) +
            " given the target's shape, " + std::to_string(outcome.smoothed_regions) + " small one(s) smoothed; " +
            std::to_string(outcome.global_regions) + " where the tested poses pass a part through another");
  }
};

}  // namespace

FallbackOutcome restore_target_regions(Candidate& candidate, const CorrectionContext& context,
                                       const std::vector<char>& in_transit, double deviation_threshold) {
  const Eigen::Ref<const Eigen::MatrixX3d>& target = context.target;
  const AdjacencyLists& neighbours = context.neighbours;
  const auto vertex_count = static_cast<double>(context.vertex_count());
  FallbackOutcome outcome;
  RegionSweep sweep;
  sweep.seed_rings = {1};
  sweep.rounds = kPasses;
  const auto restore = [&](const std::vector<int>& members, const Candidate& current) -> std::optional<Probe> {
    const Eigen::MatrixX3d& result = current.pose();
    Flags component(static_cast<size_t>(context.vertex_count()), 0);
    for (int v : members) component[static_cast<size_t>(v)] = 1;
    // Smallest first: a few rings for a local residue, then the part dragged along.
    std::vector<Flags> regions{component, within_rings(component, neighbours, 2)};
    if (overlaps(component, in_transit)) {
      Flags dragged = component;
      grow_through_deviation(dragged, neighbours, result, target, deviation_threshold);
      dragged = within_rings(dragged, neighbours, 1);
      if (count(dragged) <= kLargestDraggedFraction * vertex_count) regions.push_back(std::move(dragged));
    }
    // Where the target is itself folded or intersecting (inside a corrected region), only a
    // smooth membrane over the small region can undo a fold: its own surroundings, no target.
    const std::size_t target_shaped = regions.size();
    if (count(component) <= kLargestSmoothedRegion) {
      regions.push_back(component);
      regions.push_back(within_rings(component, neighbours, 1));
      if (count(regions.back()) > kLargestSmoothedRegion) regions.pop_back();
    }
    const Eigen::MatrixX3d no_shape_matrix = Eigen::MatrixX3d::Zero(result.rows(), 3);
    const Eigen::Ref<const Eigen::MatrixX3d> no_shape = no_shape_matrix;

    std::optional<Probe> best;
    std::size_t best_region = 0;
    for (std::size_t k = 0; k < regions.size(); ++k) {
      const bool smoothed = k >= target_shaped;
      if (smoothed && best) break;  // the target's shape already helped
      Probe probe = current.probe(with_shape_of(result, smoothed ? no_shape : target, regions[k], neighbours));
      const size_t fewest = best ? best->new_faces.size() : current.new_faces().size();
      if (probe.new_faces.size() >= fewest) continue;
      best = std::move(probe);
      best_region = k;
      // Nothing left in or at the replaced region: a larger one would only lose more of the result.
      if (!touches(within_rings(regions[k], neighbours, 1), best->new_faces, context.faces)) break;
    }
    if (!best) return std::nullopt;
    if (best_region >= target_shaped) ++outcome.smoothed_regions;
    if (overlaps(regions[best_region], in_transit)) ++outcome.global_regions;
    return best;
  };
  outcome.sweep = sweep_regions(candidate, context, sweep, restore);
  return outcome;
}

std::unique_ptr<RepairStage> make_fallback_stage() { return std::make_unique<FallbackStage>(); }

}  // namespace posekit::detail
