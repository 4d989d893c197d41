// The skeleton of a skinning decomposition: which bones are jointed, and where.
#pragma once

#include <posekit/topology.hpp>

#include <Eigen/Core>

#include <vector>

namespace posekit::detail {

/// A bone's motion to one example in the decomposition's internal frame: x -> R x + t.
using RigidMotion = Eigen::Matrix<double, 3, 4>;

/// A forest over the bones with a joint per tree edge.
struct BoneSkeleton {
  std::vector<int> parents;               ///< -1 for the root of each connected part
  Eigen::MatrixX3d joints;                ///< joint to the parent; a root's centroid
  std::vector<std::vector<int>> jointed;  ///< each bone's parent and children
};

/// The skeleton of bones whose vertices meet across mesh edges (`primary`: each vertex's bone of
/// largest weight): each such pair gets the point its two motions carry to the same place in every
/// example (least squares, pulled slightly towards the pair's boundary where the motions leave it free,
/// as for a hinge); its residual is the pair's cost; the minimum spanning forest of these costs is the
/// skeleton, rooted at the bone of largest mass in each part. `motions[k * bones + j]`, examples k >= 1
/// only (k = 0 is the reference). `mass` weights the vertices.
BoneSkeleton bone_skeleton(const Eigen::MatrixX3d& rest, const AdjacencyLists& neighbours, const std::vector<int>& primary,
                           const Eigen::VectorXd& mass, const std::vector<RigidMotion>& motions, int bones, int examples);

}  // namespace posekit::detail
