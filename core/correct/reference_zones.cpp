#include "correct/reference_zones.hpp"

#include "correct/repair_stage.hpp"
#include <posekit/vertex_regions.hpp>

#include <posekit/rigid_motion.hpp>

#include <algorithm>
#include <utility>

namespace posekit::detail {
namespace {

// Rings grown around a zone, and rings over which its reference shape fades into the candidate:
// measured on slid creases, a zone with one or two rings and a blend of three to five rings was
// freed where narrower blends fold and wider ones reach surface the rigid placement does not fit.
constexpr int kGrowthRings[] = {1, 0, 2};
constexpr int kBlendRings[] = {3, 5, 2};
// Rings beyond the blend whose positions place the reference's shape.
constexpr int kAnchorRings = 2;
// A fit onto the surroundings needs points that span a plane.
constexpr std::size_t kFewestAnchors = 3;

class ReferenceZonesStage final : public RepairStage {
 public:
  ReferenceZonesStage()
      : RepairStage({"reference-zones",
                     "give the reference's own intersections that slid onto new faces the reference's shape"},
                    kEveryScope) {}

  bool wanted(const Candidate& current, const CorrectionContext& context) const override {
    return !faces_on_reference_zones(current, context.reference_intersecting).empty();
  }

  std::optional<Candidate> run(const Candidate& current, CorrectionContext& context, StageReport& report) override {
    Candidate restored = current;
    const SweepOutcome outcome = restore_reference_zones(restored, context);
    return sweep_proposal(std::move(restored), outcome, report,
                          std::to_string(outcome.regions) + " zone(s) of the reference's own intersections (" +
                              std::to_string(outcome.vertices) + " vertices) given the reference's shape");
  }
};

}  // namespace

std::vector<int> faces_on_reference_zones(const Candidate& candidate, const std::vector<int>& reference_intersecting) {
  const std::vector<int>& fresh = candidate.new_faces();
  std::vector<int> on_zones;
  for (const auto& [f, g] : candidate.pairs()) {
    const bool f_new = std::binary_search(fresh.begin(), fresh.end(), f);
    const bool g_new = std::binary_search(fresh.begin(), fresh.end(), g);
    if (f_new && std::binary_search(reference_intersecting.begin(), reference_intersecting.end(), g)) on_zones.push_back(f);
    if (g_new && std::binary_search(reference_intersecting.begin(), reference_intersecting.end(), f)) on_zones.push_back(g);
  }
  std::sort(on_zones.begin(), on_zones.end());
  on_zones.erase(std::unique(on_zones.begin(), on_zones.end()), on_zones.end());
  return on_zones;
}

SweepOutcome restore_reference_zones(Candidate& candidate, const CorrectionContext& context) {
  const int vertex_count = context.vertex_count();
  // The reference's intersections as zones: connected sets of their faces' vertices, joined where
  // they intersect each other (both sides of a crossing are one zone).
  const std::vector<std::vector<int>> zones = join_intersecting(
      connected_sets(face_vertices(context.reference_intersecting, context.faces, static_cast<size_t>(vertex_count)),
                     context.neighbours),
      context.reference_pairs, context.faces);
  std::vector<int> zone_of(static_cast<size_t>(vertex_count), -1);
  for (size_t z = 0; z < zones.size(); ++z) {
    for (int v : zones[z]) zone_of[static_cast<size_t>(v)] = static_cast<int>(z);
  }
  RegionSweep sweep;
  sweep.seed_rings = {1};
  sweep.goal.faces_to_mend = [&](const Candidate& current) {
    return faces_on_reference_zones(current, context.reference_intersecting);
  };
  const auto restore = [&](const std::vector<int>& region, const Candidate& current) -> std::optional<Probe> {
    std::vector<char> core(static_cast<size_t>(vertex_count), 0);
    for (int v : region) {
      core[static_cast<size_t>(v)] = 1;
      // The whole zone each new face's partner belongs to.
      for (int w : context.neighbours[v]) {
        const int z = zone_of[static_cast<size_t>(w)];
        if (z < 0) continue;
        for (int u : zones[static_cast<size_t>(z)]) core[static_cast<size_t>(u)] = 1;
      }
    }
    for (const auto& [f, g] : current.pairs()) {
      for (const int face : {f, g}) {
        if (core[static_cast<size_t>(context.faces(face, 0))] == 0) continue;
        for (const int other : {f, g}) {
          const int z = zone_of[static_cast<size_t>(context.faces(other, 0))];
          if (z < 0) continue;
          for (int u : zones[static_cast<size_t>(z)]) core[static_cast<size_t>(u)] = 1;
        }
      }
    }
    for (const int growth : kGrowthRings) {
      const std::vector<char> zone = within_rings(core, context.neighbours, growth);
      for (const int blend : kBlendRings) {
        const std::vector<int> distance = ring_distances(zone, context.neighbours, blend + kAnchorRings);
        std::vector<int> support;
        std::vector<int> anchors;
        std::vector<double> weight;
        for (int v = 0; v < vertex_count; ++v) {
          const int d = distance[static_cast<size_t>(v)];
          if (d < 0) continue;
          if (d > blend) anchors.push_back(v);
          support.push_back(v);
          weight.push_back(d > blend ? 0.0 : 1.0 - static_cast<double>(d) / (blend + 1));
        }
        if (anchors.size() < kFewestAnchors) continue;
        const RigidTransform placement =
            best_rigid_transform(context.reference(anchors, Eigen::all), current.pose()(anchors, Eigen::all));
        Eigen::MatrixX3d placed = current.pose();
        for (size_t i = 0; i < support.size(); ++i) {
          if (weight[i] == 0.0) continue;
          const int v = support[i];
          placed.row(v) = (1.0 - weight[i]) * current.pose().row(v) +
                          weight[i] * placement.apply_to_point(context.reference.row(v));
        }
        Probe probe = current.probe(std::move(placed));
        if (probe.new_faces.size() < current.new_faces().size()) return probe;
      }
    }
    return std::nullopt;
  };
  return sweep_regions(candidate, context, sweep, restore);
}

std::unique_ptr<RepairStage> make_reference_zones_stage() { return std::make_unique<ReferenceZonesStage>(); }

}  // namespace posekit::detail
