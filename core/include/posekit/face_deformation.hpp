// Per-face deformation gradients between two poses of one connectivity.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <vector>

namespace posekit {

/// A face's edge vectors b - a and c - a, and its normal scaled to the square root of twice its area,
/// as the columns of a 3 x 3 matrix: the normal direction then weighs like the in-plane ones. A
/// degenerate face gets a zero third column.
Eigen::Matrix3d face_basis(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c);

/// The 3 x 3 linear map D with D * face_basis(source face) = face_basis(target face) for every face
/// of the #F by 3 `faces` between the #V by 3 `source` and `target`; the identity for a face that is
/// degenerate in `source`. Throws ArgumentError on mismatched sizes or a bad face index.
std::vector<Eigen::Matrix3d> face_deformation_gradients(const Eigen::Ref<const Eigen::MatrixX3d>& source,
                                                        const Eigen::Ref<const Eigen::MatrixX3d>& target,
                                                        const Eigen::Ref<const Eigen::MatrixX3i>& faces);

/// Rotation vectors (angle times axis) of the #F per-face `rotations` of the #F by 3 `faces`. A rotation
/// by nearly pi has two logarithms far apart (theta * axis and (theta - 2 pi) * axis); picking them
/// face by face would send neighbours around opposite ways (a tail twisted by 180 degrees), so the
/// branch is chosen to agree with the neighbours, spreading out from the faces rotated by less than 0.9 pi.
/// Those keep their principal logarithm, so a twist that goes on beyond about 1.1 pi is not followed.
std::vector<Eigen::Vector3d> consistent_rotation_logs(const std::vector<Eigen::AngleAxisd>& rotations,
                                                      const Eigen::Ref<const Eigen::MatrixX3i>& faces);

}  // namespace posekit
