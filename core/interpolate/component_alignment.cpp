#include "interpolate/component_alignment.hpp"

#include <algorithm>
#include <map>
#include <queue>
#include <utility>

namespace posekit::interpolation {
namespace {

// Enough shared vertices to fix a rotation.
constexpr int kStrongOverlap = 3;

}  // namespace

ComponentAlignment::ComponentAlignment(const std::vector<std::vector<int>>& component_vertices, int vertex_count)
    : overlaps_(component_vertices.size()) {
  const int count = static_cast<int>(component_vertices.size());
  // Which (component, row) pairs hold each vertex.
  std::vector<std::vector<std::pair<int, int>>> holders(static_cast<size_t>(vertex_count));
  for (int c = 0; c < count; ++c) {
    sizes_.push_back(static_cast<int>(component_vertices[static_cast<size_t>(c)].size()));
    const std::vector<int>& vertices = component_vertices[static_cast<size_t>(c)];
    for (size_t row = 0; row < vertices.size(); ++row) {
      holders[static_cast<size_t>(vertices[row])].emplace_back(c, static_cast<int>(row));
    }
  }
  std::vector<std::map<int, Overlap>> pairs(static_cast<size_t>(count));
  for (const auto& list : holders) {
    for (const auto& [c, row] : list) {
      for (const auto& [d, other_row] : list) {
        if (c == d) continue;
        Overlap& overlap = pairs[static_cast<size_t>(c)][d];
        overlap.other = d;
        overlap.own_rows.push_back(row);
        overlap.other_rows.push_back(other_row);
      }
    }
  }
  for (int c = 0; c < count; ++c) {
    for (auto& [d, overlap] : pairs[static_cast<size_t>(c)]) overlaps_[static_cast<size_t>(c)].push_back(std::move(overlap));
  }
  std::vector<char> seen(static_cast<size_t>(count), 0);
  for (int start = 0; start < count; ++start) {
    if (seen[static_cast<size_t>(start)]) continue;
    seen[static_cast<size_t>(start)] = 1;
    std::vector<int> cluster(1, start);
    for (size_t next = 0; next < cluster.size(); ++next) {
      for (const Overlap& overlap : overlaps_[static_cast<size_t>(cluster[next])]) {
        if (seen[static_cast<size_t>(overlap.other)] || static_cast<int>(overlap.own_rows.size()) < kStrongOverlap) continue;
        seen[static_cast<size_t>(overlap.other)] = 1;
        cluster.push_back(overlap.other);
      }
    }
    clusters_.push_back(std::move(cluster));
  }
}

std::vector<RigidTransform> ComponentAlignment::align(const std::vector<Eigen::MatrixX3d>& shapes, int sweeps) const {
  const int count = static_cast<int>(shapes.size());
  std::vector<RigidTransform> transforms(static_cast<size_t>(count));
  std::vector<char> placed(static_cast<size_t>(count), 0);
  // Registers component c onto the current positions of its placed neighbours.
  const auto register_onto_placed = [&](int c) {
    int rows = 0;
    for (const Overlap& overlap : overlaps_[static_cast<size_t>(c)]) {
      if (placed[static_cast<size_t>(overlap.other)]) rows += static_cast<int>(overlap.own_rows.size());
    }
    if (rows == 0) return;
    Eigen::MatrixX3d source(rows, 3);
    Eigen::MatrixX3d target(rows, 3);
    int row = 0;
    for (const Overlap& overlap : overlaps_[static_cast<size_t>(c)]) {
      if (!placed[static_cast<size_t>(overlap.other)]) continue;
      const Eigen::MatrixX3d& other = shapes[static_cast<size_t>(overlap.other)];
      const RigidTransform& motion = transforms[static_cast<size_t>(overlap.other)];
      for (size_t i = 0; i < overlap.own_rows.size(); ++i, ++row) {
        source.row(row) = shapes[static_cast<size_t>(c)].row(overlap.own_rows[i]);
        target.row(row) = motion.apply_to_point(other.row(overlap.other_rows[i]));
      }
    }
    transforms[static_cast<size_t>(c)] = best_rigid_transform(source, target);
  };

  for (const std::vector<int>& cluster : clusters_) {
    const int root = *std::max_element(cluster.begin(), cluster.end(), [&](int a, int b) {
      return sizes_[static_cast<size_t>(a)] < sizes_[static_cast<size_t>(b)];
    });
    // Spanning tree over the strongest overlaps (Prim): each component joins through its placed neighbours.
    std::vector<int> order;
    using Candidate = std::pair<int, int>;  // shared vertices, component
    std::priority_queue<Candidate> candidates;
    candidates.emplace(0, root);
    while (!candidates.empty()) {
      const int c = candidates.top().second;
      candidates.pop();
      if (placed[static_cast<size_t>(c)]) continue;
      if (c != root) register_onto_placed(c);
      placed[static_cast<size_t>(c)] = 1;
      order.push_back(c);
      for (const Overlap& overlap : overlaps_[static_cast<size_t>(c)]) {
        const int shared = static_cast<int>(overlap.own_rows.size());
        if (!placed[static_cast<size_t>(overlap.other)] && shared >= kStrongOverlap) candidates.emplace(shared, overlap.other);
      }
    }
    for (int sweep = 0; sweep < sweeps; ++sweep) {
      for (const int c : order) {
        if (c != root) register_onto_placed(c);
      }
    }
  }
  return transforms;
}

}  // namespace posekit::interpolation
