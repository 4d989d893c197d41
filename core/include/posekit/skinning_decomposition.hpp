// Skinning weights and bone motions learned from example poses alone: smooth skinning decomposition
// with rigid bones (Le and Deng), then a skeleton over the bones and a refinement in which every bone
// turns about its joint and every vertex blends only its own bone and the bones jointed to it.
//
// Model: example k is approximated by linear blend skinning of the reference (the first example),
//   v^k_i ~ sum_j w_ij (R^k_j p_i + t^k_j),  w_ij >= 0,  sum_j w_ij = 1,  at most `influences` nonzero.
#pragma once

#include <posekit/mesh.hpp>

#include <Eigen/Core>

#include <vector>

namespace posekit {

/// Settings of decompose_skinning(). Lengths are fractions of the reference's bounding-box diagonal.
struct SkinningOptions {
  /// Number of bones; 0 chooses it: bones are added (each splitting off the part the others fit worst)
  /// until the rigid parts fit the examples within `fit_tolerance`, or `max_bones` is reached. Either
  /// way a bone left without any vertex is removed, so the count is an upper bound.
  int bones = 0;
  int max_bones = 24;
  /// RMS vertex error of the rigid parts at which the automatic count stops adding bones (> 0).
  double fit_tolerance = 0.006;
  /// Bones blended at one vertex, in [1, 8].
  int influences = 4;
  /// Alternations of the weight and bone updates before the skeleton, and after it (each >= 0).
  int iterations = 8;
  int skeleton_iterations = 4;
  /// Laplacian smoothness of the weights: a weight differing by 1 from its neighbours' mean costs as
  /// much as a vertex error of `smoothness` mean edge lengths in every example (>= 0).
  double smoothness = 1.0;
  /// Weight of each joint (the point two jointed bones must carry to the same place in every
  /// example) against the bone's own vertices, as a fraction of their total weight (>= 0).
  double joint_weight = 0.5;
};

/// One bone's motion from the reference to an example: x -> rotation x + translation.
struct BoneMotion {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
};

/// The learned skinning of an example set.
struct SkinningDecomposition {
  /// #V by bones; every row non-negative, summing to one, with at most `influences` nonzero entries.
  Eigen::MatrixXd weights;
  /// motions[k][j]: bone j from the reference to example k, in the examples' own coordinates.
  std::vector<std::vector<BoneMotion>> motions;
  /// The skeleton: parent bone of each bone (-1 for a root; one root per connected part of the mesh)
  /// and the joint to the parent in the reference's coordinates (a root's row is its centroid).
  std::vector<int> parents;
  Eigen::MatrixX3d joints;
  /// RMS and largest vertex error of the skinned examples, fractions of the reference's diagonal.
  double rms_error = 0.0;
  double max_error = 0.0;
  double seconds = 0.0;

  int bone_count() const { return static_cast<int>(weights.cols()); }
  int vertex_count() const { return static_cast<int>(weights.rows()); }
  int example_count() const { return static_cast<int>(motions.size()); }
};

/// Learns weights, bone motions and skeleton from `examples` (the first is the reference; at least
/// two poses). Deterministic. Throws ArgumentError for fewer than two examples, more bones than
/// vertices, a degenerate reference or options out of range.
SkinningDecomposition decompose_skinning(const PoseSet& examples, const SkinningOptions& options = {});

/// Example `example` rebuilt from the decomposition by linear blend skinning of `reference` (#V by 3).
Eigen::MatrixX3d skinned_pose(const SkinningDecomposition& decomposition,
                              const Eigen::Ref<const Eigen::MatrixX3d>& reference, int example);

/// Throws ArgumentError unless `decomposition` is whole and consistent: sizes, finite values,
/// weights non-negative with rows summing to one, a forest of parents.
void check_skinning_decomposition(const SkinningDecomposition& decomposition);

}  // namespace posekit
