// As-rigid-as-possible deformation of a region of a mesh (CGAL's Surface_mesh_deformation with the
// smoothed rotation-enhanced energy): the region takes a rest shape's local form as rigidly as it
// can, with handles moved to where they must go and the ring around held in place.
#pragma once

#include <posekit/topology.hpp>

#include <Eigen/Core>

#include <optional>
#include <vector>

namespace posekit {

/// `current` (#V by 3) with the `free` vertices moved as-rigidly-as-possible towards the local shape
/// of `rest` (#V by 3, same connectivity `faces`), the `handles` at their rows of `handle_positions`
/// and the one-ring around both held at `current` (one flag per vertex each; `neighbours` the
/// vertex one-rings). Nothing where the region's surface is not a manifold CGAL can take, or where
/// the solve fails or gives a coordinate that is not finite.
std::optional<Eigen::MatrixX3d> as_rigid_as_possible(const Eigen::Ref<const Eigen::MatrixX3d>& rest,
                                                     const Eigen::Ref<const Eigen::MatrixX3d>& current,
                                                     const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                                                     const std::vector<char>& free,
                                                     const std::vector<char>& handles,
                                                     const Eigen::Ref<const Eigen::MatrixX3d>& handle_positions,
                                                     const AdjacencyLists& neighbours);

}  // namespace posekit
