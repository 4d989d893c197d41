#include "correct/region_sweep.hpp"

#include <posekit/vertex_regions.hpp>

#include <algorithm>
#include <map>

namespace posekit::detail {
SweepGoal fewer_new_faces() {
  return {[](const Candidate& candidate) { return candidate.new_faces(); },
          [](const Probe& proposal, const Candidate& current) {
            return proposal.new_faces.size() < current.new_faces().size();
          }};
}

namespace {

// A repair sees its region and what lies a few rings around it (the rim it blends into, the anchors
// it is placed by); a region that failed is tried again only once something this near has moved.
constexpr int kRepairReachRings = 8;

}  // namespace

SweepOutcome sweep_regions(Candidate& candidate, const CorrectionContext& context, const RegionSweep& sweep,
                           const RegionRepair& repair) {
  const auto vertex_count = static_cast<size_t>(context.vertex_count());
  SweepOutcome outcome;
  std::vector<char> moved(vertex_count, 0);
  // Regions that failed, by their vertices, with the count of kept proposals (outcome.regions) when
  // they failed; per vertex, that count when something within reach of it last moved.
  std::map<std::vector<int>, int> failed;
  std::vector<int> last_disturbed(vertex_count, 0);
  const auto unchanged_since = [&](const std::vector<int>& region, int since) {
    return std::all_of(region.begin(), region.end(),
                       [&](int v) { return last_disturbed[static_cast<size_t>(v)] <= since; });
  };
  for (int round = 0; round < sweep.rounds; ++round) {
    const int kept_before = outcome.regions;
    for (const int rings : sweep.seed_rings) {
      std::vector<int> to_mend = sweep.goal.faces_to_mend(candidate);
      if (to_mend.empty()) break;
      const std::vector<char> near =
          within_rings(face_vertices(to_mend, context.faces, vertex_count), context.neighbours, rings);
      std::vector<std::vector<int>> regions = connected_sets(near, context.neighbours);
      if (sweep.link_intersecting) {
        regions = join_intersecting(regions, candidate.pairs(), context.faces);
      }
      for (std::vector<int>& region : regions) {
        if (to_mend.empty()) break;
        if (static_cast<double>(region.size()) > sweep.largest_fraction * static_cast<double>(vertex_count)) continue;
        std::sort(region.begin(), region.end());
        std::vector<char> inside(vertex_count, 0);
        for (int v : region) inside[static_cast<size_t>(v)] = 1;
        if (!touches(inside, to_mend, context.faces)) continue;
        const auto previous = failed.find(region);
        if (previous != failed.end() && unchanged_since(region, previous->second)) continue;
        std::optional<Probe> proposal = repair(region, candidate);
        if (!proposal || !sweep.goal.improves(*proposal, candidate)) {
          failed[region] = outcome.regions;
          continue;
        }
        std::vector<char> changed(vertex_count, 0);
        for (int v : differing_vertices(proposal->pose, candidate.pose())) {
          moved[static_cast<size_t>(v)] = 1;
          changed[static_cast<size_t>(v)] = 1;
        }
        candidate.accept(std::move(*proposal));
        ++outcome.regions;
        const std::vector<char> disturbed = within_rings(changed, context.neighbours, kRepairReachRings);
        for (size_t v = 0; v < vertex_count; ++v) {
          if (disturbed[v] != 0) last_disturbed[v] = outcome.regions;
        }
        to_mend = sweep.goal.faces_to_mend(candidate);
      }
    }
    if (outcome.regions == kept_before || sweep.goal.faces_to_mend(candidate).empty()) break;
  }
  outcome.vertices = static_cast<int>(std::count(moved.begin(), moved.end(), 1));
  return outcome;
}

}  // namespace posekit::detail
