// Rotation clusters for the as-rigid-as-possible energy of blended deformation: groups of vertices
// that turn together across the example poses, each sharing one rotation per example.
#pragma once

#include <Eigen/Core>

#include <vector>

namespace posekit {

/// Labels in [0, count) for the vertices of the example poses (each #V by 3, reference first, on the
/// #F by 3 `faces`): k-means (farthest-first start, Lloyd iterations) on per-vertex features made of
/// the reference position divided by the square root of its area, times `position_weight`, and the
/// 3 by 3 rotation of each vertex's one-ring from the reference to every other example (divided by
/// the square root of the number of examples). Vertices that move rigidly together across all
/// examples share a label. Deterministic. Throws ArgumentError for bad sizes or count outside [1, #V].
std::vector<int> rotation_clusters(const std::vector<Eigen::MatrixX3d>& examples,
                                   const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                                   int count, double position_weight = 1.0);

/// Labels from skinning weights (#V by m): each vertex goes to its largest weight; labels are
/// renumbered 0, 1, ... in order of first appearance so that none is empty.
std::vector<int> weight_clusters(const Eigen::MatrixXd& weights);

}  // namespace posekit
