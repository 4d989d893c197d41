#include "correct/time_rollback.hpp"

#include "correct/vertex_regions.hpp"

#include <posekit/rigid_motion.hpp>
#include <posekit/self_intersections.hpp>
#include <posekit/topology.hpp>

#include <algorithm>
#include <utility>

namespace posekit::detail {
namespace {

// Core growth of the three passes: a residue that one ring cannot free usually belongs to a part
// that has to move back as a whole.
constexpr int kCoreRings[] = {1, 3, 6};

// Beyond this fraction of the vertices a region is no longer a part that went too far but the
// pose itself, and moving it back would undo the correction it was meant to finish.
constexpr double kLargestRegionFraction = 0.1;

// A fit of the region's earlier shape onto its surroundings needs points that span a plane.
constexpr int kFewestAnchors = 3;

bool touches(const std::vector<int>& face_list, const Eigen::MatrixX3i& faces, const std::vector<int>& distance,
             int within) {
  for (int f : face_list) {
    for (int c = 0; c < 3; ++c) {
      const int d = distance[static_cast<size_t>(faces(f, c))];
      if (d >= 0 && d <= within) return true;
    }
  }
  return false;
}

}  // namespace

RollbackResult roll_back_regions(Eigen::MatrixX3d& result, const PathSampler& paths, const Eigen::MatrixX3i& faces,
                                 const std::vector<int>& reference_intersecting, const RollbackOptions& options) {
  const int vertex_count = static_cast<int>(result.rows());
  const auto new_faces = [&](const Eigen::MatrixX3d& pose) {
    return new_intersecting_faces(self_intersecting_faces(pose, faces), reference_intersecting);
  };
  RollbackResult out;
  std::vector<int> current = new_faces(result);
  out.new_faces_before = static_cast<int>(current.size());
  const AdjacencyLists neighbours = vertex_neighbours(faces, vertex_count);
  std::vector<char> moved(static_cast<size_t>(vertex_count), 0);
  const int reach = options.blend_rings + options.anchor_rings;

  for (const int core_rings : kCoreRings) {
    if (current.empty()) break;
    const std::vector<char> core =
        within_rings(face_vertices(current, faces, static_cast<size_t>(vertex_count)), neighbours, core_rings);

    for (const std::vector<int>& region : connected_sets(core, neighbours)) {
      if (current.empty()) break;
      std::vector<char> inside(static_cast<size_t>(vertex_count), 0);
      for (int v : region) inside[static_cast<size_t>(v)] = 1;
      const std::vector<int> distance = ring_distances(inside, neighbours, reach);
      // An earlier move may have freed this region already.
      if (!touches(current, faces, distance, 0)) continue;

      std::vector<int> support;
      std::vector<double> weight;
      std::vector<int> anchors;  // rows of `support`
      for (int v = 0; v < vertex_count; ++v) {
        const int d = distance[static_cast<size_t>(v)];
        if (d < 0) continue;
        if (d > options.blend_rings) anchors.push_back(static_cast<int>(support.size()));
        support.push_back(v);
        weight.push_back(d > options.blend_rings ? 0.0 : 1.0 - static_cast<double>(d) / (options.blend_rings + 1));
      }
      if (static_cast<double>(support.size()) > kLargestRegionFraction * vertex_count) continue;
      const std::vector<Eigen::MatrixX3d> path = paths(support, options.segments);
      const Eigen::MatrixX3d& end = path.back();
      Eigen::MatrixX3d end_anchors(static_cast<Eigen::Index>(anchors.size()), 3);
      for (size_t a = 0; a < anchors.size(); ++a) end_anchors.row(static_cast<Eigen::Index>(a)) = end.row(anchors[a]);

      std::vector<int> best_faces = current;
      Eigen::MatrixX3d best_pose;
      int best_step = options.segments;
      for (int step = options.segments - 1; step >= 0; --step) {
        const Eigen::MatrixX3d& earlier = path[static_cast<size_t>(step)];
        RigidTransform placement;
        if (static_cast<int>(anchors.size()) >= kFewestAnchors) {
          Eigen::MatrixX3d earlier_anchors(end_anchors.rows(), 3);
          for (size_t a = 0; a < anchors.size(); ++a) earlier_anchors.row(static_cast<Eigen::Index>(a)) = earlier.row(anchors[a]);
          placement = best_rigid_transform(earlier_anchors, end_anchors);
        }
        Eigen::MatrixX3d candidate = result;
        for (size_t i = 0; i < support.size(); ++i) {
          if (weight[i] == 0.0) continue;
          const Eigen::Index row = static_cast<Eigen::Index>(i);
          candidate.row(support[i]) += weight[i] * (placement.apply_to_point(earlier.row(row)) - end.row(row));
        }
        std::vector<int> remaining = new_faces(candidate);
        if (remaining.size() < best_faces.size()) {
          best_faces = std::move(remaining);
          best_pose = std::move(candidate);
          best_step = step;
          // The latest time that frees the region and its blend is the one to keep.
          if (!touches(best_faces, faces, distance, options.blend_rings)) break;
        }
      }
      if (best_step == options.segments) continue;
      result = std::move(best_pose);
      current = std::move(best_faces);
      ++out.regions;
      out.earliest_time = std::min(out.earliest_time, static_cast<double>(best_step) / options.segments);
      for (size_t i = 0; i < support.size(); ++i) {
        if (weight[i] > 0.0) moved[static_cast<size_t>(support[i])] = 1;
      }
    }
  }
  out.new_faces_after = static_cast<int>(current.size());
  out.vertices = static_cast<int>(std::count(moved.begin(), moved.end(), 1));
  return out;
}

}  // namespace posekit::detail
