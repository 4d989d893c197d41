// The self-intersections of a pose that changes in places. After one whole-mesh test, a changed
// pose is tested again only where it moved: the faces with a moved corner, against the faces near
// them (a uniform grid over the faces' bounding boxes finds those). Repairs that move a region at a
// time, and try several moves before keeping one, then pay for the region and not for the mesh.
#pragma once

#include <Eigen/Core>

#include <memory>
#include <utility>
#include <vector>

namespace posekit {

/// Intersecting face pairs (f, g), f < g, sorted, as from self_intersecting_face_pairs().
using FacePairs = std::vector<std::pair<int, int>>;

class SelfIntersectionTracker {
 public:
  /// Tests the #V by 3 `vertices` of the #F by 3 `faces` whole; keeps its own copy of both.
  /// Throws ArgumentError on a face index outside [0, #V) or a coordinate that is not finite.
  SelfIntersectionTracker(const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                          const Eigen::Ref<const Eigen::MatrixX3i>& faces);
  /// The same with the pairs of `vertices` already known (self_intersecting_face_pairs of them).
  SelfIntersectionTracker(const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                          const Eigen::Ref<const Eigen::MatrixX3i>& faces, FacePairs known_pairs);
  ~SelfIntersectionTracker();
  SelfIntersectionTracker(const SelfIntersectionTracker& other);
  SelfIntersectionTracker& operator=(const SelfIntersectionTracker& other);
  SelfIntersectionTracker(SelfIntersectionTracker&&) noexcept;
  SelfIntersectionTracker& operator=(SelfIntersectionTracker&&) noexcept;

  /// The pose as last tested (#V by 3).
  const Eigen::MatrixX3d& vertices() const;
  /// The faces it was made with.
  const Eigen::MatrixX3i& faces() const;
  /// Its intersecting pairs.
  const FacePairs& pairs() const { return pairs_; }
  /// The pairs `changed` (#V by 3, the same faces) has: only the faces with a corner that differs from
  /// vertices() are tested again. Safe to call from several threads at once.
  FacePairs pairs_if(const Eigen::Ref<const Eigen::MatrixX3d>& changed) const;
  /// Moves the tracker to `changed`, testing again as pairs_if() does.
  void update(const Eigen::Ref<const Eigen::MatrixX3d>& changed);
  /// Moves the tracker to `changed` whose pairs are `known` (pairs_if(changed) of this tracker as it is).
  void update(const Eigen::Ref<const Eigen::MatrixX3d>& changed, FacePairs known);

 private:
  class Grid;
  void check_pose(const Eigen::Ref<const Eigen::MatrixX3d>& changed) const;
  std::unique_ptr<Grid> grid_;
  FacePairs pairs_;
};

}  // namespace posekit
