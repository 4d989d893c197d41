#include "correct/global_intersection_fallback.hpp"

#include <posekit/self_intersections.hpp>
#include <posekit/topology.hpp>

#include <algorithm>
#include <optional>

namespace posekit::detail {
namespace {

// Connected regions of the flagged vertices (edges between flagged vertices only).
std::vector<std::vector<int>> flagged_regions(const std::vector<char>& flagged, const AdjacencyLists& neighbours) {
  const int vertex_count = neighbours.item_count();
  std::vector<char> seen(static_cast<size_t>(vertex_count), 0);
  std::vector<std::vector<int>> regions;
  for (int seed = 0; seed < vertex_count; ++seed) {
    if (!flagged[static_cast<size_t>(seed)] || seen[static_cast<size_t>(seed)]) continue;
    std::vector<int> region{seed};
    seen[static_cast<size_t>(seed)] = 1;
    for (size_t next = 0; next < region.size(); ++next) {
      for (int neighbour : neighbours[region[next]]) {
        if (flagged[static_cast<size_t>(neighbour)] && !seen[static_cast<size_t>(neighbour)]) {
          seen[static_cast<size_t>(neighbour)] = 1;
          region.push_back(neighbour);
        }
      }
    }
    regions.push_back(std::move(region));
  }
  return regions;
}

}  // namespace

FallbackResult restore_unreachable_regions(Eigen::MatrixX3d& result, const Eigen::MatrixX3d& target,
                                           const std::vector<int>& reference_intersecting,
                                           const Eigen::MatrixX3i& faces, const std::vector<char>& in_transit,
                                           double deviation_threshold) {
  FallbackResult outcome;
  const int vertex_count = static_cast<int>(result.rows());
  const AdjacencyLists neighbours = vertex_neighbours(faces, vertex_count);
  std::optional<size_t> new_faces;  // counted when the first region needs it
  for (const std::vector<int>& region : flagged_regions(in_transit, neighbours)) {
    double deviation = 0.0;
    for (int v : region) deviation = std::max(deviation, (result.row(v) - target.row(v)).norm());
    if (deviation <= deviation_threshold) continue;
    Eigen::MatrixX3d candidate = result;
    for (int v : region) candidate.row(v) = target.row(v);
    const std::vector<int> fresh =
        new_intersecting_faces(self_intersecting_faces(candidate, faces), reference_intersecting);
    if (!new_faces) {
      new_faces = new_intersecting_faces(self_intersecting_faces(result, faces), reference_intersecting).size();
    }
    if (fresh.size() > *new_faces) {
      ++outcome.rejected_regions;
      continue;
    }
    result = std::move(candidate);
    new_faces = fresh.size();
    ++outcome.regions;
    outcome.vertices += static_cast<int>(region.size());
  }
  return outcome;
}

}  // namespace posekit::detail
