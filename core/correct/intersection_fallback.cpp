#include "correct/intersection_fallback.hpp"

#include "correct/vertex_regions.hpp"

#include <posekit/self_intersections.hpp>
#include <posekit/topology.hpp>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <utility>

namespace posekit::detail {
namespace {

using Flags = std::vector<char>;

// Rounds of region growing; a replacement can uncover a residue next to it, hence more than one.
constexpr int kPasses = 3;
// A part dragged along by an obstacle is followed only up to this fraction of the vertices: beyond
// it the region is no longer a part but the pose, and the target is what was to be corrected.
constexpr double kLargestDraggedFraction = 0.1;
// A membrane flattens what it covers: it is tried only on regions of at most this many vertices.
constexpr int kLargestSmoothedRegion = 40;

bool is_set(const Flags& flags, int vertex) { return flags[static_cast<size_t>(vertex)] != 0; }

// Adds the vertices farther than `threshold` from the target that connect to the flagged ones
// through such vertices: a part dragged along by an obstacle.
void grow_through_deviation(Flags& flags, const AdjacencyLists& neighbours, const Eigen::MatrixX3d& result,
                            const Eigen::MatrixX3d& target, double threshold) {
  std::vector<int> stack;
  for (int v = 0; v < static_cast<int>(flags.size()); ++v) {
    if (is_set(flags, v)) stack.push_back(v);
  }
  while (!stack.empty()) {
    const int v = stack.back();
    stack.pop_back();
    for (int w : neighbours[v]) {
      if (is_set(flags, w) || (result.row(w) - target.row(w)).norm() <= threshold) continue;
      flags[static_cast<size_t>(w)] = 1;
      stack.push_back(w);
    }
  }
}

// Connected regions of the flagged vertices (edges between flagged vertices only).
std::vector<Flags> flagged_regions(const Flags& flagged, const AdjacencyLists& neighbours) {
  Flags seen(flagged.size(), 0);
  std::vector<Flags> regions;
  for (int seed = 0; seed < static_cast<int>(flagged.size()); ++seed) {
    if (!is_set(flagged, seed) || is_set(seen, seed)) continue;
    Flags region(flagged.size(), 0);
    std::vector<int> stack{seed};
    seen[static_cast<size_t>(seed)] = region[static_cast<size_t>(seed)] = 1;
    while (!stack.empty()) {
      const int v = stack.back();
      stack.pop_back();
      for (int w : neighbours[v]) {
        if (is_set(flagged, w) && !is_set(seen, w)) {
          seen[static_cast<size_t>(w)] = region[static_cast<size_t>(w)] = 1;
          stack.push_back(w);
        }
      }
    }
    regions.push_back(std::move(region));
  }
  return regions;
}

int count(const Flags& flags) { return static_cast<int>(std::count(flags.begin(), flags.end(), 1)); }

bool overlaps(const Flags& a, const Flags& b) {
  for (size_t v = 0; v < a.size(); ++v) {
    if (a[v] != 0 && b[v] != 0) return true;
  }
  return false;
}

// `result` with the region given the target's shape, displaced by the harmonic interpolation of
// the offsets result - target at the vertices around it: the region keeps the target's detail and
// joins its surroundings smoothly, wherever integration moved them.
Eigen::MatrixX3d replaced(const Eigen::MatrixX3d& result, const Eigen::MatrixX3d& target, const Flags& region,
                          const AdjacencyLists& neighbours) {
  std::vector<int> unknown_of(region.size(), -1);
  std::vector<int> vertices;
  for (int v = 0; v < static_cast<int>(region.size()); ++v) {
    if (!is_set(region, v)) continue;
    unknown_of[static_cast<size_t>(v)] = static_cast<int>(vertices.size());
    vertices.push_back(v);
  }
  const auto size = static_cast<Eigen::Index>(vertices.size());
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixX3d rhs = Eigen::MatrixX3d::Zero(size, 3);
  for (Eigen::Index i = 0; i < size; ++i) {
    const int v = vertices[static_cast<size_t>(i)];
    entries.emplace_back(i, i, static_cast<double>(neighbours[v].size()));
    for (int w : neighbours[v]) {
      const int j = unknown_of[static_cast<size_t>(w)];
      if (j >= 0) {
        entries.emplace_back(i, j, -1.0);
      } else {
        rhs.row(i) += result.row(w) - target.row(w);
      }
    }
  }
  Eigen::SparseMatrix<double> laplacian(size, size);
  laplacian.setFromTriplets(entries.begin(), entries.end());
  Eigen::MatrixX3d candidate = result;
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(laplacian);
  // A region that is a whole closed component has no surroundings: it is the target's, unmoved.
  const Eigen::MatrixX3d offsets =
      solver.info() == Eigen::Success ? Eigen::MatrixX3d(solver.solve(rhs)) : Eigen::MatrixX3d::Zero(size, 3);
  for (Eigen::Index i = 0; i < size; ++i) {
    const int v = vertices[static_cast<size_t>(i)];
    if (offsets.row(i).allFinite()) candidate.row(v) = target.row(v) + offsets.row(i);
    else candidate.row(v) = target.row(v);
  }
  return candidate;
}

}  // namespace

FallbackResult restore_target_regions(Eigen::MatrixX3d& result, const Eigen::MatrixX3d& target,
                                      const std::vector<int>& reference_intersecting, const Eigen::MatrixX3i& faces,
                                      const std::vector<char>& in_transit, double deviation_threshold) {
  FallbackResult outcome;
  const Eigen::Index vertex_count = result.rows();
  const AdjacencyLists neighbours = vertex_neighbours(faces, static_cast<int>(vertex_count));
  const auto new_faces = [&](const Eigen::MatrixX3d& pose) {
    return new_intersecting_faces(self_intersecting_faces(pose, faces), reference_intersecting);
  };
  std::vector<int> current = new_faces(result);
  outcome.new_faces_before = static_cast<int>(current.size());

  for (int pass = 0; pass < kPasses && !current.empty(); ++pass) {
    const Flags seeds = within_rings(face_vertices(current, faces, static_cast<size_t>(vertex_count)), neighbours, 1);
    for (const Flags& component : flagged_regions(seeds, neighbours)) {
      // An earlier replacement in this pass may have settled this one already.
      if (!overlaps(component, face_vertices(current, faces, static_cast<size_t>(vertex_count)))) continue;
      // Smallest first: a few rings for a local residue, then the part dragged along.
      std::vector<Flags> regions{component};
      regions.push_back(component);
      regions.back() = within_rings(regions.back(), neighbours, 2);
      if (overlaps(component, in_transit)) {
        Flags dragged = component;
        grow_through_deviation(dragged, neighbours, result, target, deviation_threshold);
        dragged = within_rings(dragged, neighbours, 1);
        if (count(dragged) <= kLargestDraggedFraction * static_cast<double>(vertex_count)) {
          regions.push_back(std::move(dragged));
        }
      }

      // Where the target is itself folded or intersecting (inside a corrected region), only a
      // smooth membrane over the small region can undo a fold: its own surroundings, no target.
      const std::size_t target_shaped = regions.size();
      if (count(component) <= kLargestSmoothedRegion) {
        regions.push_back(component);
        regions.push_back(component);
        regions.back() = within_rings(regions.back(), neighbours, 1);
        if (count(regions.back()) > kLargestSmoothedRegion) regions.pop_back();
      }
      const Eigen::MatrixX3d no_shape = Eigen::MatrixX3d::Zero(result.rows(), 3);

      std::vector<int> best_faces = current;
      Eigen::MatrixX3d best;
      Flags best_changed;
      bool best_smoothed = false;
      for (std::size_t k = 0; k < regions.size(); ++k) {
        const Flags& region = regions[k];
        const bool smoothed = k >= target_shaped;
        if (smoothed && !best_changed.empty()) break;  // the target's shape already helped
        Eigen::MatrixX3d candidate = replaced(result, smoothed ? no_shape : target, region, neighbours);
        std::vector<int> fresh = new_faces(candidate);
        if (fresh.size() >= best_faces.size()) continue;
        best_faces = std::move(fresh);
        best = std::move(candidate);
        best_changed = region;
        best_smoothed = smoothed;
        // Nothing left in or at the replaced region: a larger one would only lose more of the result.
        Flags around = region;
        around = within_rings(around, neighbours, 1);
        if (!overlaps(around, face_vertices(best_faces, faces, static_cast<size_t>(vertex_count)))) break;
      }
      if (best_changed.empty()) {
        ++outcome.rejected_regions;
        continue;
      }
      result = std::move(best);
      current = std::move(best_faces);
      ++(best_smoothed ? outcome.smoothed_regions : outcome.regions);
      outcome.vertices += count(best_changed);
      if (overlaps(best_changed, in_transit)) ++outcome.global_regions;
    }
  }
  return outcome;
}

}  // namespace posekit::detail
