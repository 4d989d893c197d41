// Rotations and rigid motions: the polar decomposition of a 3 x 3 map, best-fitting rigid motions
// between corresponding point sets (Kabsch), and the simultaneous registration of several copies of
// one point set (generalized Procrustes analysis, as in Williams and Bennamoun).
#pragma once

#include <Eigen/Core>

#include <vector>

namespace posekit {

/// M = rotation * stretch with det(rotation) = +1 and a symmetric stretch; a reflection in M, if
/// any, is kept in the stretch (its smallest principal value turns negative).
struct PolarDecomposition {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Matrix3d stretch = Eigen::Matrix3d::Identity();
};

/// Polar decomposition of the 3 x 3 `m` through its singular value decomposition.
PolarDecomposition polar_decomposition(const Eigen::Matrix3d& m);

/// The rotation closest to `m` in the Frobenius norm (the rotation of its polar decomposition).
Eigen::Matrix3d nearest_rotation(const Eigen::Matrix3d& m);

/// x -> rotation * x + translation, applied to row vectors as x * rotation^T + translation.
struct RigidTransform {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::RowVector3d translation = Eigen::RowVector3d::Zero();

  /// #N by 3 transformed copy of the #N by 3 `points`.
  Eigen::MatrixX3d apply(const Eigen::Ref<const Eigen::MatrixX3d>& points) const;
  Eigen::RowVector3d apply_to_point(const Eigen::RowVector3d& point) const { return point * rotation.transpose() + translation; }
  /// The motion that applies `first` and then this one.
  RigidTransform after(const RigidTransform& first) const;
  RigidTransform inverse() const;
};

/// The rigid motion T minimizing sum_i |T(source_i) - target_i|^2 over the corresponding rows of the
/// #N by 3 `source` and `target` (Kabsch). Throws ArgumentError when the sizes differ or N is 0; for
/// fewer than three independent points the rotation is one of the minimizers.
RigidTransform best_rigid_transform(const Eigen::Ref<const Eigen::MatrixX3d>& source,
                                    const Eigen::Ref<const Eigen::MatrixX3d>& target);

/// Rigid motions T_k, one per copy (each #N by 3, rows corresponding), minimizing the squared
/// distances between all pairs of transformed copies, with T_0 the identity: each copy is aligned
/// to the mean of the aligned copies, `iterations` times or until no rotation changes by more than
/// 1e-12. Throws ArgumentError when there is no copy or the sizes differ.
std::vector<RigidTransform> register_simultaneously(const std::vector<Eigen::MatrixX3d>& copies, int iterations = 10);

}  // namespace posekit
