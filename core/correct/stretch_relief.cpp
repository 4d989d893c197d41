#include "correct/stretch_relief.hpp"

#include "correct/repair_stage.hpp"
#include "correct/target_reproduction.hpp"
#include <posekit/vertex_regions.hpp>

#include <posekit/as_rigid_as_possible.hpp>

#include <algorithm>
#include <utility>

namespace posekit::detail {
namespace {

// Rings grown around the stretched faces' corners, smallest first: the displacement has to spread
// over more edges the farther it reaches.
constexpr int kMarginRings[] = {1, 2, 4, 8};

// Beyond this fraction of the vertices a region is no longer a stretched band but the pose.
constexpr double kLargestRegionFraction = 0.25;

// Rounds while they help: relieving one band can leave its neighbour stretched.
constexpr int kRounds = 2;

class StretchReliefStage final : public RepairStage {
 public:
  StretchReliefStage()
      : RepairStage({"stretch-relief",
                     "give regions the correction stretched the target's shape where that adds no intersection"},
                    scope_bit(CorrectionScope::whole_pose) | scope_bit(CorrectionScope::stretch_retry)) {}

  bool wanted(const Candidate& current, const CorrectionContext& context) const override {
    return context.stretch.count(current.pose()) > 0;
  }

  std::optional<Candidate> run(const Candidate& current, CorrectionContext& context, StageReport& report) override {
    Candidate relieved = current;
    const int before = context.stretch.count(current.pose());
    const SweepOutcome outcome = relieve_stretch(relieved, context);
    const int after = context.stretch.count(relieved.pose());
    report.details = {{"stretched_faces_before", before}, {"stretched_faces_after", after}};
    return sweep_proposal(std::move(relieved), outcome, report,
                          std::to_string(outcome.regions) + " stretched region(s) (" +
                              std::to_string(outcome.vertices) + " vertices) given the target's shape; stretched faces " +
                              std::to_string(before) + " -> " + std::to_string(after));
  }
};

}  // namespace

SweepOutcome relieve_stretch(Candidate& candidate, const CorrectionContext& context) {
  const auto vertex_count = static_cast<size_t>(context.vertex_count());
  const std::vector<char> no_handles(vertex_count, 0);
  RegionSweep sweep;
  sweep.seed_rings = {1};
  sweep.rounds = kRounds;
  sweep.goal.faces_to_mend = [&](const Candidate& current) { return context.stretch.stretched_faces(current.pose()); };
  sweep.goal.improves = [&](const Probe& proposal, const Candidate& current) {
    return proposal.new_faces.size() <= current.new_faces().size() &&
           context.stretch.count(proposal.pose) < context.stretch.count(current.pose());
  };
  const auto relieve = [&](const std::vector<int>& band, const Candidate& current) -> std::optional<Probe> {
    std::vector<char> core(vertex_count, 0);
    for (int v : band) core[static_cast<size_t>(v)] = 1;
    const auto region_limit = kLargestRegionFraction * static_cast<double>(vertex_count);
    const auto too_large = [&](const std::vector<char>& region) {
      return static_cast<double>(std::count(region.begin(), region.end(), 1)) > region_limit;
    };
    // The target's shape displaced as the surroundings are; failing that, as rigid as possible
    // towards it, which keeps more of the correction's displacement inside the region; where the
    // target is itself entangled there, as rigid as possible towards the reference's shape.
    const auto relief_in = [&](const std::vector<char>& region) -> std::optional<Probe> {
      for (int variant = 0; variant < 3; ++variant) {
        std::optional<Eigen::MatrixX3d> moved =
            variant == 0 ? std::optional<Eigen::MatrixX3d>(with_shape_of(current.pose(), context.target, region, context.neighbours))
                         : as_rigid_as_possible(variant == 1 ? context.target : context.reference, current.pose(),
                                                context.faces, region, no_handles, current.pose(), context.neighbours);
        if (!moved) continue;
        Probe probe = current.probe(std::move(*moved));
        if (sweep.goal.improves(probe, current)) return probe;
      }
      return std::nullopt;
    };
    std::vector<std::vector<char>> tried;  // the regions within the size limit, by margin
    for (const int margin : kMarginRings) {
      std::vector<char> region = within_rings(core, context.neighbours, margin);
      if (too_large(region)) break;
      if (std::optional<Probe> probe = relief_in(region)) return probe;
      tried.push_back(std::move(region));
    }
    // A band torn around a limb (faces over three times as long) may cut off its tip, which the
    // target pins where the limb has moved away: then the tip joins the region and goes with the
    // limb. Only where the band alone could not be relieved: a whole tail moved to spare a few
    // stretched faces would leave the target's pose far behind. The sweep retries a failed band
    // only after a change within 8 rings of it; one in the far part of a tip goes unseen, which
    // costs at most the second round's retry of that band.
    if (!touches(core, context.stretch.stretched_faces(current.pose(), kStronglyStretchedFactor), context.faces)) {
      return std::nullopt;
    }
    // A region over the limit has a tip over it too: only the regions tried above can take one.
    for (const std::vector<char>& region : tried) {
      const std::vector<char> with_tip = with_cut_off_parts(region, context.neighbours);
      if (too_large(with_tip)) break;
      if (with_tip == region) continue;  // nothing cut off: tried above
      if (std::optional<Probe> probe = relief_in(with_tip)) return probe;
    }
    return std::nullopt;
  };
  return sweep_regions(candidate, context, sweep, relieve);
}

std::unique_ptr<RepairStage> make_stretch_relief_stage() { return std::make_unique<StretchReliefStage>(); }

}  // namespace posekit::detail
