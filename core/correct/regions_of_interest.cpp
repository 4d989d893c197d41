#include "correct/regions_of_interest.hpp"

#include <posekit/vertex_regions.hpp>

#include <algorithm>
#include <numeric>

namespace posekit::detail {

std::vector<std::vector<int>> regions_of_interest(const VertexClassification& classification,
                                                  const std::vector<FacePairs>& tested_pairs,
                                                  const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                                                  const AdjacencyLists& neighbours,
                                                  int collar_rings) {
  std::vector<char> unconstrained(classification.constrained.size(), 0);
  for (size_t v = 0; v < unconstrained.size(); ++v) unconstrained[v] = classification.constrained[v] ? 0 : 1;
  std::vector<std::vector<int>> regions =
      connected_sets(within_rings(unconstrained, neighbours, collar_rings), neighbours);
  FacePairs all_pairs;
  for (const FacePairs& pairs : tested_pairs) all_pairs.insert(all_pairs.end(), pairs.begin(), pairs.end());
  regions = join_intersecting(regions, all_pairs, faces);
  for (std::vector<int>& region : regions) std::sort(region.begin(), region.end());
  return regions;
}

std::vector<std::vector<int>> whole_mesh_region(int vertex_count) {
  std::vector<int> all(static_cast<size_t>(vertex_count));
  std::iota(all.begin(), all.end(), 0);
  return {all};
}

}  // namespace posekit::detail
