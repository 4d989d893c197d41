// Regions of a mesh's vertices: rings around a flagged set, and its connected parts. The stages that
// repair what integration left behind grow such regions around intersecting faces.
#pragma once

#include <posekit/topology.hpp>

#include <vector>

namespace posekit::detail {

/// Edge distance of every vertex from the flagged ones (0 for those), -1 beyond `limit` edges.
std::vector<int> ring_distances(const std::vector<char>& flagged, const AdjacencyLists& neighbours, int limit);

/// The connected sets of flagged vertices (through edges between flagged vertices), largest first.
std::vector<std::vector<int>> connected_sets(const std::vector<char>& flagged, const AdjacencyLists& neighbours);

}  // namespace posekit::detail
