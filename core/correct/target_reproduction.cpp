#include "correct/target_reproduction.hpp"

#include <posekit/error.hpp>

#include <algorithm>
#include <limits>

namespace posekit::detail {

Eigen::VectorXd correction_weights(const std::vector<char>& corrected, const AdjacencyLists& neighbours,
                                   int keep_rings, int blend_rings) {
  if (keep_rings < 0 || blend_rings < 0) throw ArgumentError("reproduction rings must be >= 0");
  const int vertex_count = neighbours.item_count();
  if (static_cast<int>(corrected.size()) != vertex_count) {
    throw ArgumentError("correction flags for " + std::to_string(corrected.size()) + " vertices, mesh of " +
                        std::to_string(vertex_count));
  }
  // Ring distance to the nearest corrected vertex, by breadth-first search from all of them.
  constexpr int kFar = std::numeric_limits<int>::max();
  std::vector<int> distance(static_cast<size_t>(vertex_count), kFar);
  std::vector<int> frontier;
  for (int v = 0; v < vertex_count; ++v) {
    if (corrected[static_cast<size_t>(v)]) {
      distance[static_cast<size_t>(v)] = 0;
      frontier.push_back(v);
    }
  }
  const int reach = keep_rings + blend_rings;
  for (int ring = 1; ring <= reach && !frontier.empty(); ++ring) {
    std::vector<int> next;
    for (int v : frontier) {
      for (int w : neighbours[v]) {
        if (distance[static_cast<size_t>(w)] != kFar) continue;
        distance[static_cast<size_t>(w)] = ring;
        next.push_back(w);
      }
    }
    frontier = std::move(next);
  }
  Eigen::VectorXd weights(vertex_count);
  for (int v = 0; v < vertex_count; ++v) {
    const int d = distance[static_cast<size_t>(v)];
    if (d <= keep_rings) {
      weights(v) = 1.0;
    } else if (d > reach) {
      weights(v) = 0.0;
    } else {
      // Smoothstep from 1 at keep_rings to 0 one ring past the band.
      const double s = static_cast<double>(d - keep_rings) / (blend_rings + 1);
      weights(v) = 1.0 - s * s * (3.0 - 2.0 * s);
    }
  }
  return weights;
}

Eigen::MatrixX3d blend_towards_target(const Eigen::MatrixX3d& integrated, const Eigen::MatrixX3d& target,
                                      const Eigen::VectorXd& weights) {
  if (integrated.rows() != target.rows() || weights.size() != target.rows()) {
    throw ArgumentError("blend of poses and weights of different sizes");
  }
  Eigen::MatrixX3d blended = integrated - target;
  blended.array().colwise() *= weights.array();
  return blended + target;
}

}  // namespace posekit::detail
