// Which vertices constrain the space-time field: all but those near self-intersections that
// appear on the way from the reference to the target.
#pragma once

#include <posekit/self_intersection_tracker.hpp>
#include <posekit/topology.hpp>

#include <Eigen/Core>
#include <vector>

namespace posekit::detail {

struct VertexClassification {
  std::vector<char> constrained;            ///< one flag per vertex: constrained at every time
  std::vector<int> reference_intersecting;  ///< faces intersecting in the reference (sorted)
  std::vector<int> target_intersecting;     ///< faces intersecting in the last frame (sorted)
  /// Unconstrained only because of intersections in the in-between frames, not in the target:
  /// where the key frames move one part through another.
  std::vector<char> in_transit;
  int excluded = 0;                         ///< vertices not constrained
  /// Near an intersection in some frame or excluded by the user, reference-intersecting ones too:
  /// every vertex whose position the field, not the target, has to give.
  std::vector<char> near_intersections;
  /// Per tested pose, one flag per vertex: near an intersection of that frame (grown by the rings,
  /// reference-intersecting vertices given back) or excluded by the user.
  std::vector<std::vector<char>> unconstrained_in_frame;
};

/// Marks as unconstrained the vertices of faces that self-intersect in any of the tested poses
/// (`pairs_per_pose` holds each pose's intersecting pairs, the reference first, the target last),
/// grown by `rings` one-rings, and the `user_excluded` vertices; then gives the vertices of faces
/// already intersecting in the reference back to the constraints (those intersections are
/// reproduced, not repaired). `faces` is #F by 3 over `neighbours.item_count()` vertices.
VertexClassification classify_vertices(const std::vector<FacePairs>& pairs_per_pose,
                                       const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                                       const AdjacencyLists& neighbours, int rings,
                                       const std::vector<int>& user_excluded);

}  // namespace posekit::detail
