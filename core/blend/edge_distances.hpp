// Shortest-path distances along the edges of a mesh: a cheap, slightly long approximation of
// geodesic distance, enough to cut geodesic discs.
#pragma once

#include <posekit/topology.hpp>

#include <Eigen/Core>

#include <functional>
#include <limits>
#include <queue>
#include <utility>
#include <vector>

namespace posekit::detail {

/// Distances from `source` to every vertex over the one-rings `ring` (vertex_neighbours of the mesh),
/// Dijkstra stopped beyond `limit` (farther vertices keep infinity).
inline Eigen::VectorXd edge_distances(const Eigen::Ref<const Eigen::MatrixX3d>& vertices, const AdjacencyLists& ring,
                                      int source,
                                      double limit) {
  Eigen::VectorXd distance = Eigen::VectorXd::Constant(vertices.rows(), std::numeric_limits<double>::infinity());
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  distance(source) = 0.0;
  queue.push({0.0, source});
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > distance(v) || d > limit) continue;
    for (int u : ring[v]) {
      const double next = d + (vertices.row(u) - vertices.row(v)).norm();
      if (next < distance(u) && next <= limit) {
        distance(u) = next;
        queue.push({next, u});
      }
    }
  }
  return distance;
}

}  // namespace posekit::detail
