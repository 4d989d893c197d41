// Alignment of the interpolated components (rigid pieces and joints, each in a frame of its own) on
// the vertices they share: rigid motions found by simultaneous registration (Williams and Bennamoun)
// started from a spanning tree over the strongest overlaps.
#pragma once

#include <posekit/rigid_motion.hpp>

#include <Eigen/Core>

#include <vector>

namespace posekit::interpolation {

class ComponentAlignment {
 public:
  /// `component_vertices`: the ascending mesh vertices of every component (rows of its shape, in order).
  ComponentAlignment(const std::vector<std::vector<int>>& component_vertices, int vertex_count);

  /// One rigid motion per component for the component `shapes` (rows as in component_vertices), with
  /// the largest component of each cluster left in place; `sweeps` rounds of re-registering every
  /// component against its placed neighbours after the spanning tree.
  std::vector<RigidTransform> align(const std::vector<Eigen::MatrixX3d>& shapes, int sweeps) const;

  /// Groups of components joined through overlaps of three or more vertices.
  const std::vector<std::vector<int>>& clusters() const { return clusters_; }

 private:
  struct Overlap {
    int other = -1;
    std::vector<int> own_rows;    // rows of this component's shape
    std::vector<int> other_rows;  // the same vertices in the other component's shape
  };
  std::vector<std::vector<Overlap>> overlaps_;  // per component
  std::vector<std::vector<int>> clusters_;
  std::vector<int> sizes_;
};

}  // namespace posekit::interpolation
