#include "correct/region_relaxation.hpp"

#include "correct/repair_stage.hpp"
#include <posekit/vertex_regions.hpp>

#include <posekit/as_rigid_as_possible.hpp>

#include <utility>

namespace posekit::detail {
namespace {

// Margins tried around a fold, smallest first: a crease needs a ring or two, a part folded through
// itself six to twelve.
constexpr int kMarginRings[] = {1, 2, 3, 4, 6, 8, 12, 16};

// Beyond this fraction of the vertices a region is no longer a fold but the pose.
constexpr double kLargestRegionFraction = 0.25;

// Rounds of the passes at most: a relaxation can uncover a crease next to it.
constexpr int kRounds = 3;

class RelaxationStage final : public RepairStage {
 public:
  RelaxationStage()
      : RepairStage({"relaxation", "relax folded regions as-rigidly-as-possible towards the reference's shape"},
                    kEveryScope) {}

  std::optional<Candidate> run(const Candidate& current, CorrectionContext& context, StageReport& report) override {
    Candidate relaxed = current;
    const SweepOutcome outcome = relax_folded_regions(relaxed, context);
    return sweep_proposal(std::move(relaxed), outcome, report,
                          std::to_string(outcome.regions) + " folded region(s) (" + std::to_string(outcome.vertices) +
                              " vertices) relaxed towards the reference's shape");
  }
};

}  // namespace

SweepOutcome relax_folded_regions(Candidate& candidate, const CorrectionContext& context,
                                  const RelaxationLimits& limits) {
  const auto vertex_count = static_cast<size_t>(context.vertex_count());
  const std::vector<char> no_handles(vertex_count, 0);
  RegionSweep sweep;
  sweep.seed_rings = {1};
  sweep.rounds = kRounds;
  const auto relax = [&](const std::vector<int>& fold, const Candidate& current) -> std::optional<Probe> {
    std::vector<char> core(vertex_count, 0);
    for (int v : fold) core[static_cast<size_t>(v)] = 1;
    std::optional<Probe> best;
    for (const int margin : kMarginRings) {
      if (margin > limits.widest_margin) break;
      const std::vector<char> region = within_rings(core, context.neighbours, margin);
      if (static_cast<double>(std::count(region.begin(), region.end(), 1)) >
          kLargestRegionFraction * static_cast<double>(vertex_count)) {
        break;
      }
      std::optional<Eigen::MatrixX3d> moved = as_rigid_as_possible(context.reference, current.pose(), context.faces,
                                                                   region, no_handles, current.pose(), context.neighbours);
      if (!moved) continue;
      if (((*moved - current.pose()).rowwise().norm().array() > limits.largest_move).any()) continue;
      Probe probe = current.probe(std::move(*moved));
      const size_t fewest = best ? best->new_faces.size() : current.new_faces().size();
      if (probe.new_faces.size() >= fewest) continue;
      best = std::move(probe);
      // Nothing left in or at the region: a larger one would only lose more of the pose.
      if (!touches(within_rings(region, context.neighbours, 1), best->new_faces, context.faces)) break;
    }
    return best;
  };
  return sweep_regions(candidate, context, sweep, relax);
}

std::unique_ptr<RepairStage> make_relaxation_stage() { return std::make_unique<RelaxationStage>(); }

}  // namespace posekit::detail
